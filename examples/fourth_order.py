"""Worked example: a fourth-order plant, a link driven through an elastic joint.

The output is the link angle; the motor torque reaches it only through the
spring, so the relative degree is 4 (``famcc.plants.flexible_joint``: link
inertia 0.05 kg m^2, motor inertia 0.02 kg m^2, stiffness 20 N m/rad, gravity
0.5 N m at horizontal; input gain G = k / (J_l J_m) = 2e4 rad/s^4 per N m).

Requirement: move the link by 0.5 rad and hold it within eps = 0.01 rad within
6 s, with |u| <= 5 N m, at 1 kHz; the differentiator estimates three
derivatives of the measured angle.

Run: ``python examples/fourth_order.py [OUT_DIR]`` (writes ``fourth_order.png``);
exit status 0 when the requirement is met.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import famcc

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
DT, U_LIMITS, EPS, SETTLE = 1e-3, (-5.0, 5.0), 0.01, 6.0
TARGET = famcc.Constant(0.5)

plant = famcc.plants.flexible_joint()
t0 = time.perf_counter()
design = famcc.tune(plant, dt=DT, u_limits=U_LIMITS, eps=EPS, settle_time=SETTLE, reference=TARGET)
print(f"famcc.tune took {time.perf_counter() - t0:.1f} s: {design.choice}")
print(design)

res = famcc.simulate(plant, design.controller(), 10.0, reference=TARGET, u_limits=U_LIMITS)
verdict = famcc.tuning.assess(res, eps=EPS, settle_time=SETTLE, u_limits=U_LIMITS)
print("tuned:", verdict)

ruled = famcc.design(
    4,
    DT,
    u_limits=U_LIMITS,
    eps=EPS,
    settle_time=SETTLE,
    hold_input=plant.hold_input(),
    gain=plant.gain,
)
res_rules = famcc.simulate(plant, ruled.controller(), 10.0, reference=TARGET, u_limits=U_LIMITS)
print(
    "design alone:", famcc.tuning.assess(res_rules, eps=EPS, settle_time=SETTLE, u_limits=U_LIMITS)
)

fig = res.plot(title="Flexible joint (order 4): 0.5 rad step")
fig.savefig(OUT / "fourth_order.png", dpi=80)
print(f"figure: {OUT / 'fourth_order.png'}")
sys.exit(0 if verdict.ok else 1)
