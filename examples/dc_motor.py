"""Worked example 1: position control of a DC motor with a load, tuned by famcc.tune.

Requirement: move the shaft by 1 rad and hold it within eps = 0.01 rad of the
set point within 1.5 s, with the armature voltage limited to |u| <= 12 V, while
the motor lifts a 1 N m load (4 V to hold: R T / K); the loop runs at 1 kHz.
Afterwards the load changes by another 0.5 N m (a load step), and the loop must
recover.

The plant, ``theta'' = (K/(J R)) V - (b/J + K^2/(J R)) theta' - T/J`` with
J = 0.01 kg m^2, K = 0.25 N m/A, R = 1 ohm (``famcc.plants.dc_motor``), is
known to famcc.tune only through simulation; it measures the input gain and
the hold input on a first run.

Run: ``python examples/dc_motor.py [OUT_DIR]`` (writes ``dc_motor.png``).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import famcc
import numpy as np

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
DT, U_LIMITS, EPS, SETTLE = 1e-3, (-12.0, 12.0), 0.01, 1.5
SET_POINT = famcc.Constant(1.0)

# The requirement run: the load is there from the start.
plant = famcc.plants.dc_motor(load=1.0, t_load=0.0)
t0 = time.perf_counter()
design = famcc.tune(
    plant,
    dt=DT,
    u_limits=U_LIMITS,
    eps=EPS,
    settle_time=SETTLE,
    reference=SET_POINT,
    progress=False,
)
print(f"famcc.tune: {time.perf_counter() - t0:.1f} s; {design.choice}")
print(design)

res = famcc.simulate(plant, design.controller(), 4.0, reference=SET_POINT, u_limits=U_LIMITS)
t = res.t
steady = t >= 3.0
ts = res.settling_time(EPS)
ripple = float(np.ptp(res.u[steady]))
metrics = {
    "settling time [s]": ts,
    "steady max |e| [rad]": float(np.max(np.abs(res.z1[steady]))),
    "expanded while unsaturated after settling": float(
        np.mean((res.expanded & ~res.saturated)[t >= (ts or t[-1])])
    ),
    "u ripple after 3 s [% of range]": 100 * ripple / (U_LIMITS[1] - U_LIMITS[0]),
    "saturated [% of samples]": 100 * res.saturated_fraction,
}
for k, v in metrics.items():
    print(f"{k:45s} {v:.4g}" if v is not None else f"{k:45s} never")

# A load step after settling: 1 N m -> 1.5 N m at t = 3 s.
stepped = famcc.plants.dc_motor(load=1.0, t_load=0.0, load_step=0.5, t_step=3.0)
res2 = famcc.simulate(stepped, design.controller(), 6.0, reference=SET_POINT, u_limits=U_LIMITS)
after = res2.t >= 3.0
peak = float(np.max(np.abs(res2.z1[after])))
back = res2.settling_time(EPS)
print(f"load step at 3 s: peak |e| {peak:.4g} rad, back within eps at {back} s")
fig = res2.plot(title="DC motor: 1 rad set point, 1 N m load, +0.5 N m at 3 s")
fig.savefig(OUT / "dc_motor.png", dpi=90)
print(f"figure: {OUT / 'dc_motor.png'}")
ok = (
    ts is not None
    and ts <= SETTLE
    and metrics["steady max |e| [rad]"] < EPS
    and metrics["u ripple after 3 s [% of range]"] <= 5.0
    and metrics["expanded while unsaturated after settling"] == 0.0
)
print("requirement met" if ok else "requirement NOT met")
sys.exit(0 if ok else 1)
