"""A famcc controller inside a python-control discrete-time closed loop.

The plant is a damped oscillator ``y'' = 2 u - y - 0.5 y'`` discretized with a
zero-order hold at the controller's sample period; the controller tracks
``y_d = 0.5`` from ``y(0) = -1``. Needs ``pip install control``.

Run: ``python examples/python_control_interop.py``
"""

import control
import famcc
import numpy as np
from famcc.interop import to_nlsys

dt = 1e-3
ctrl = famcc.Controller(
    2, dt, famcc.FiniteTime(k=1.0, p=0.5), constraint="lateral", eps=0.1, k_u=5.0
)

plant = control.c2d(control.ss([[0, 1], [-1, -0.5]], [[0], [2]], [[1, 0]], 0), dt)
plant = control.ss(plant, inputs="u", outputs="y", states=["x1", "x2"], name="plant")
error = control.summing_junction(inputs=["y", "-r"], output="e", name="error")
closed = control.interconnect(
    [plant, error, to_nlsys(ctrl, inputs="e", outputs="u")],
    inplist="r",
    outlist=["y", "u"],
    dt=dt,
    name="closed loop",
)

t = np.arange(0.0, 2.5 + dt / 2, dt)
x0 = np.concatenate(([-1.0, 0.0], ctrl.state()))
resp = control.input_output_response(closed, t, 0.5 * np.ones_like(t), initial_state=x0)
y, u = resp.outputs
z1 = y - 0.5
outside = np.flatnonzero(np.abs(z1) >= 0.1)
settled = "never" if outside[-1] == t.size - 1 else f"{t[outside[-1] + 1]:.3f} s"
print(f"{closed.name}: {closed.nstates} states, dt = {closed.dt} s")
print(f"|y - y_d| < 0.1 from t = {settled}; final error {z1[-1]:+.4f}")
print(f"u in [{u.min():.2f}, {u.max():.2f}]")
