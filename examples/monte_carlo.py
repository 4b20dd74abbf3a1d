"""Monte Carlo with a ControllerBank: one controller per random initial state.

The paper's second-order plant (authors' variant, disturbance amplitude 3) is
integrated for all N runs at once with a vectorized RK4 in NumPy; the bank
steps the N controllers (example 1: LaMC, finite-time law, eps = 0.1) in one
call per sample. Prints the fraction of runs that settled to |y - y_d| < 0.1
within the paper's bound T_s + T_fn' (which depends on |z1(0)|).

Run: ``python examples/monte_carlo.py [N]``

The library does this (and more: dispersed plant parameters, references, noise
and controller settings, success rates with confidence intervals, worst cases,
Dask) in ``famcc.campaign``: see docs/campaigns.md and ``famcc campaign``.
"""

import sys

import famcc
import numpy as np

N = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
DT, T_END, SUBSTEPS, U_LIM = 1e-3, 5.0, 1, 100.0
rng = np.random.default_rng(2024)


def rhs(t: float, x: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The second-order plant of famcc.plants.second_order("code"), vectorized."""
    x1, x2 = x
    g1 = 1.0 + 0.1 * np.cos(x1) + 0.1 * np.sin(t)
    g2 = 2.0 + 0.2 * np.sin(x1 * x2) + 0.1 * np.cos(t)
    f2 = -(x1 * x1 - 1.0) * x2 + 3.0 * (np.sin(t) + np.cos(2.0 * t))
    return np.stack([g1 * x2 - x1 + np.sin(t), g2 * u + f2])


sc = famcc.scenarios.paper("finite-time")
bank = famcc.ControllerBank(sc.controller(dt=DT), N)
x = rng.uniform(-2.0, 2.0, size=(2, N))  # random initial states
steps = round(T_END / DT)
z1_0 = x[0] - np.sin(0.0)
bound = sc.settle_time + np.abs(z1_0) ** 0.5 / 0.5  # T_s + T_fn'(z1(0)), k = 1, p = 0.5
last_out = np.full(N, -1)  # last sample with |z1| >= 0.1
max_xi = np.zeros(N)
h = DT / SUBSTEPS
for k in range(steps + 1):
    t = k * DT
    e = x[0] - np.sin(t)
    last_out[np.abs(e) >= 0.1] = k
    u = np.clip(bank.step(e), -U_LIM, U_LIM)
    max_xi = np.maximum(max_xi, np.abs(bank.xi))
    for j in range(SUBSTEPS):  # RK4, u held over the sample
        tj = t + j * h
        k1 = rhs(tj, x, u)
        k2 = rhs(tj + h / 2, x + h / 2 * k1, u)
        k3 = rhs(tj + h / 2, x + h / 2 * k2, u)
        k4 = rhs(tj + h, x + h * k3, u)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)

settled = last_out < steps  # inside at the end of the horizon
settling_time = (last_out + 1) * DT
print(f"{N} runs, x(0) uniform in [-2, 2]^2, {T_END} s at dt = {DT} s")
print(
    f"settled to |z1| < 0.1:              {settled.mean():.1%} "
    f"(median settling time {np.median(settling_time[settled]):.3f} s)"
)
print(f"settled within T_s + T_fn'(z1(0)):  {(settled & (settling_time <= bound)).mean():.1%}")
print(f"max |xi~| over all runs = {max_xi.max():.4f} (< 1 by construction)")
