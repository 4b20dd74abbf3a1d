"""The steps every worked example takes (docs/tuning.md): tune for a requirement,
simulate the tuned controller, judge it, and compare with the rules alone.

Used by ``dc_motor.py``, ``pendulum.py`` and ``fourth_order.py``.
"""

from __future__ import annotations

import time
from typing import Any

import famcc


def tune_and_check(
    plant: Any,
    *,
    dt: float,
    u_limits: tuple[float, float],
    eps: float,
    settle_time: float,
    reference: Any,
    t_end: float,
) -> tuple[Any, Any, Any]:
    """``famcc.tune`` for the requirement, a run of the tuned controller and its
    :func:`famcc.tuning.assess` verdict; prints both, and the same for
    ``famcc.design`` alone (the datasheet's gain and hold input, no simulation).

    Returns ``(design, result, verdict)`` of the tuned controller.
    """
    req = {"eps": eps, "settle_time": settle_time, "u_limits": u_limits}
    t0 = time.perf_counter()
    design = famcc.tune(plant, dt=dt, reference=reference, **req)
    print(f"famcc.tune took {time.perf_counter() - t0:.1f} s: {design.choice}")
    print(design)
    res = famcc.simulate(plant, design.controller(), t_end, reference=reference, u_limits=u_limits)
    verdict = famcc.tuning.assess(res, **req)
    print("tuned:", verdict)

    ruled = famcc.design(
        plant.order,
        dt,
        hold_input=plant.hold_input(),
        gain=plant.gain,
        max_error=design.requirements["max_error"],
        **req,
    )
    alone = famcc.simulate(plant, ruled.controller(), t_end, reference=reference, u_limits=u_limits)
    print("design alone:", famcc.tuning.assess(alone, **req))
    return design, res, verdict
