"""Worked example: a large swing of a pendulum with a weak motor, tuned by famcc.tune.

Requirement: swing a pendulum (m = 0.5 kg, l = 0.5 m, from hanging at rest) up
to 2 rad (115 degrees from hanging) and hold it within eps = 0.01 rad within
2 s, with the torque limited to |u| <= 3 N m, at 1 kHz. Gravity needs up to
m g l = 2.45 N m at 90 degrees and 2.23 N m at the target: the motor has little
headroom, so the swing saturates and the integral must not wind up.

Run: ``python examples/pendulum.py [OUT_DIR]`` (writes ``pendulum.png``); exit
status 0 when the requirement is met.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import famcc

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
DT, U_LIMITS, EPS, SETTLE = 1e-3, (-3.0, 3.0), 0.01, 2.0
TARGET = famcc.Constant(2.0)

plant = famcc.plants.pendulum()
t0 = time.perf_counter()
design = famcc.tune(plant, dt=DT, u_limits=U_LIMITS, eps=EPS, settle_time=SETTLE, reference=TARGET)
print(f"famcc.tune took {time.perf_counter() - t0:.1f} s: {design.choice}")
print(design)

res = famcc.simulate(plant, design.controller(), 4.0, reference=TARGET, u_limits=U_LIMITS)
verdict = famcc.tuning.assess(res, eps=EPS, settle_time=SETTLE, u_limits=U_LIMITS)
print("tuned:", verdict)

ruled = famcc.design(
    2,
    DT,
    u_limits=U_LIMITS,
    eps=EPS,
    settle_time=SETTLE,
    hold_input=plant.hold_input(),
    gain=plant.gain,
)
res_rules = famcc.simulate(plant, ruled.controller(), 4.0, reference=TARGET, u_limits=U_LIMITS)
print(
    "design alone:", famcc.tuning.assess(res_rules, eps=EPS, settle_time=SETTLE, u_limits=U_LIMITS)
)

fig = res.plot(title="Pendulum: swing to 2 rad with |u| <= 3 N m")
fig.savefig(OUT / "pendulum.png", dpi=80)
print(f"figure: {OUT / 'pendulum.png'}")
sys.exit(0 if verdict.ok else 1)
