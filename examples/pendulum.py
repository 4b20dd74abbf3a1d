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
from pathlib import Path

import famcc
from requirement import tune_and_check

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
DT, U_LIMITS, EPS, SETTLE = 1e-3, (-3.0, 3.0), 0.01, 2.0
TARGET = famcc.Constant(2.0)

plant = famcc.plants.pendulum()
design, res, verdict = tune_and_check(
    plant,
    dt=DT,
    u_limits=U_LIMITS,
    eps=EPS,
    settle_time=SETTLE,
    reference=TARGET,
    t_end=4.0,
)

fig = res.plot(title="Pendulum: swing to 2 rad with |u| <= 3 N m")
fig.savefig(OUT / "pendulum.png", dpi=80)
print(f"figure: {OUT / 'pendulum.png'}")
sys.exit(0 if verdict.ok else 1)
