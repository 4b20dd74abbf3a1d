"""Sample-rate sweep: how slow may the controller be sampled?

For every scenario, sample rate (50 Hz to 10 kHz), differentiator
discretization (``"exact"``, ``"euler"``, ``"tustin"``, ``"foh"``) and with or without
saturation of the estimates fed to the law (``HighGain(..., limits=...)``), one
closed-loop run of :meth:`famcc.scenarios.Scenario.run` with the scenario's
differentiator replaced. Each run gets three nested verdicts:

``ok`` (keeps its guarantees)
    no claim of ``scenario.verdicts(result)`` fails (see :mod:`famcc.verdicts`):
    settling within the corollary's bound, no saturation and nominal bounds
    after the start-up for the scenarios designed without saturation;
    settling by 10 s and recovery after every saturation episode for the
    saturated ones. Untested claims are listed apart (never counted as held).
    Runs that blow up fail.
``nominal_ok``
    also the accuracy is never given up with headroom left: after the start-up
    (:data:`famcc.verdicts.STARTUP`) the bounds are never expanded while ``v``
    is inside the limits. (The flexible boundary keeps ``|xi~| < 1`` by
    construction, so ``|xi~| < 1`` alone cannot show that sampling left the
    nominal constraint intact.)
``performance_ok``
    also the run performs like the fastest swept rate (same configuration):
    settles no later than ``1.1 t_ref + 0.25 s`` and saturates at most 5
    percentage points more often.

The plant is integrated with RK4 steps of at most :data:`MAX_RK4_STEP` (the
same 10 substeps per sample as ``famcc reproduce`` at 1 kHz), so the plant is
equally accurate at every rate and only the controller's sampling changes.

Estimate limits a user can know without simulating: ``LIMIT_FACTOR`` times the
initial error vector's magnitudes, floored at 1 (:func:`estimate_limits`).

>>> from famcc import sweep
>>> sweep.substeps_for(1e-3), sweep.substeps_for(1 / 50), sweep.substeps_for(1e-4)
(10, 200, 1)
"""

from __future__ import annotations

from famcc.scenarios import MAX_RK4_STEP, substeps_for
from famcc.sweep.report import write_sweep_report
from famcc.sweep.run import (
    CRITERIA,
    DISCRETIZATIONS,
    LIMIT_FACTOR,
    RATES_HZ,
    TARGET_HZ,
    add_performance,
    estimate_limits,
    initial_error,
    run_one,
    sweep,
)
from famcc.sweep.tables import lowest_rates, question_rate, xi_text

__all__ = [
    "CRITERIA",
    "DISCRETIZATIONS",
    "LIMIT_FACTOR",
    "MAX_RK4_STEP",
    "RATES_HZ",
    "TARGET_HZ",
    "add_performance",
    "estimate_limits",
    "initial_error",
    "lowest_rates",
    "question_rate",
    "run_one",
    "substeps_for",
    "sweep",
    "write_sweep_report",
    "xi_text",
]
