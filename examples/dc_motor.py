"""Worked example: position control of a DC motor with a load, tuned by famcc.tune.

Requirement: move the shaft by 1 rad and hold it within eps = 0.01 rad of the
set point within 1.5 s, with the armature voltage limited to |u| <= 12 V, while
the motor lifts a 1 N m load (4 V to hold it: R T / K); the loop runs at 1 kHz.
Afterwards the load grows by another 0.5 N m (a load step) and the loop must
recover.

The plant, ``theta'' = (K/(J R)) V - (b/J + K^2/(J R)) theta' - T/J`` with
J = 0.01 kg m^2, K = 0.25 N m/A, R = 1 ohm (``famcc.plants.dc_motor``), is
known to famcc.tune only through simulation and its datasheet gain and hold input.

Run: ``python examples/dc_motor.py [OUT_DIR]`` (writes ``dc_motor.png``); exit
status 0 when the requirement is met.
"""

from __future__ import annotations

import sys
from pathlib import Path

import famcc
from requirement import tune_and_check

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
DT, U_LIMITS, EPS, SETTLE = 1e-3, (-12.0, 12.0), 0.01, 1.5
SET_POINT = famcc.Constant(1.0)

# The requirement run: the load is there from the start.
plant = famcc.plants.dc_motor(load=1.0, t_load=0.0)
design, res, verdict = tune_and_check(
    plant,
    dt=DT,
    u_limits=U_LIMITS,
    eps=EPS,
    settle_time=SETTLE,
    reference=SET_POINT,
    t_end=4.0,
)

# A load step after settling: 1 N m -> 1.5 N m at t = 3 s.
stepped = famcc.plants.dc_motor(load=1.0, t_load=0.0, load_step=0.5, t_step=3.0)
res2 = famcc.simulate(stepped, design.controller(), 6.0, reference=SET_POINT, u_limits=U_LIMITS)
after = res2.t >= 3.0
peak = float(abs(res2.z1[after]).max())
recovered = famcc.tuning.assess(res2, eps=EPS, settle_time=6.0, u_limits=U_LIMITS)
print(
    f"load step at 3 s: peak |e| {peak:.3g} rad, back within eps from {recovered.settling_time} s"
)
fig = res2.plot(title="DC motor: 1 rad set point, 1 N m load, +0.5 N m at 3 s")
fig.savefig(OUT / "dc_motor.png", dpi=80)
print(f"figure: {OUT / 'dc_motor.png'}")
sys.exit(0 if verdict.ok else 1)
