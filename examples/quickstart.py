"""famcc in ten lines: the paper's example 1 against its second-order plant.

Run: ``python examples/quickstart.py``
"""

import famcc

ctrl = famcc.Controller(
    2,
    1e-3,
    famcc.FiniteTime(k=1.0, p=0.5),  # order, dt, law h_p
    constraint="lateral",
    eps=0.1,  # LaMC, accuracy 0.1
    k_u=5.0,
    settle_time=1.0,
)  # gain, preset time T_s
result = famcc.simulate(
    famcc.plants.second_order(), ctrl, t_end=5.0, reference=famcc.Sine(), u_limits=(-100, 100)
)
print(
    f"settling time to 0.1: {result.settling_time(0.1)} s "
    f"(bound T_s + T_fn' = {1.0 + famcc.bounds.T_fn(1.0, 0.5, -1.0)} s)"
)
print(f"max |xi~| = {result.max_abs_xi:.3f}, u in [{result.u_min:.2f}, {result.u_max:.2f}]")
