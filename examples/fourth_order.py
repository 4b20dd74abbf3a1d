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
from pathlib import Path

import famcc
from requirement import tune_and_check

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
DT, U_LIMITS, EPS, SETTLE = 1e-3, (-5.0, 5.0), 0.01, 6.0
TARGET = famcc.Constant(0.5)

plant = famcc.plants.flexible_joint()
design, res, verdict = tune_and_check(
    plant,
    dt=DT,
    u_limits=U_LIMITS,
    eps=EPS,
    settle_time=SETTLE,
    reference=TARGET,
    t_end=10.0,
)

fig = res.plot(title="Flexible joint (order 4): 0.5 rad step")
fig.savefig(OUT / "fourth_order.png", dpi=80)
print(f"figure: {OUT / 'fourth_order.png'}")
sys.exit(0 if verdict.ok else 1)
