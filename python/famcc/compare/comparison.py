""":func:`compare`: tune every controller on every plant, then run every condition."""

from __future__ import annotations

import os
import time
from collections.abc import Sequence
from typing import Any

from famcc.compare.conditions import CONDITIONS, QUICK_CONDITIONS
from famcc.compare.evaluation import _evaluate
from famcc.compare.plants import _OWN, Case, cases
from famcc.compare.spaces import _KINDS, controllers
from famcc.compare.tuning import _tune, tune_budget
from famcc.compare.workers import _Pool


def compare(
    *,
    quick: bool = False,
    jobs: int | None = None,
    progress: Any = None,
    seed: int = 2026,
    dispersion_plants: int | None = None,
    case_names: Sequence[str] | None = None,
    own_cases: Sequence[Case] = (),
) -> dict[str, Any]:
    """Tune every controller on every plant, then run every condition.

    Parameters
    ----------
    quick : bool
        Two plants, five conditions, budget 8, 2 dispersed plants, 4 s horizons.
    jobs : int, optional
        Worker processes (default: the CPU count).
    progress : object with ``step(label, seconds)``, optional
        E.g. :class:`famcc.reporting.Progress`; :func:`total_runs` gives its total.
    seed : int
        Seeds the tuning, the noise and the dispersion.
    dispersion_plants : int, optional
        Dispersed plants per case (default 6, quick 2).
    case_names : sequence of str, optional
        A subset of :func:`cases`.
    own_cases : sequence of Case
        Plants of your own (each with its ``factory``), compared after the
        chosen built-in ones by the same procedure and budget; pass
        ``case_names=[]`` to compare only these. Their names must be new.

    Returns
    -------
    dict
        ``meta``, ``tuned`` (per case and controller: parameters, objective,
        the search history) and ``runs`` (per case, controller and condition:
        the metrics; ``dispersion`` holds the worst over the dispersed plants).
    """
    t0 = time.perf_counter()
    chosen = [c for c in cases(quick) if case_names is None or c.name in case_names]
    own = _own(own_cases, {c.name for c in cases()})
    if case_names and not chosen:
        raise ValueError(f"case_names matched no case: {case_names!r}")
    chosen += list(own.values())
    if not chosen:
        raise ValueError("no case to compare: give case_names or own_cases")
    jobs = max(1, int(jobs or os.cpu_count() or 1))
    budget, rounds = tune_budget(quick)
    n_disp = dispersion_plants if dispersion_plants is not None else (2 if quick else 6)

    def horizon(c: Case) -> float:
        return min(c.t_end, 4.0) if quick else c.t_end

    pool = _Pool(jobs, progress, own)
    _OWN.clear()
    _OWN.update(own)  # for the report's figures, in this process
    try:
        tuned = _tune(pool, chosen, budget, rounds, seed, horizon)
        runs = _evaluate(pool, chosen, tuned, quick, n_disp, seed, horizon)
    finally:
        pool.close()
    return {
        "meta": {
            "quick": quick,
            "budget": budget,
            "rounds": rounds,
            "dispersion_plants": n_disp,
            "seed": seed,
            "jobs": jobs,
            "conditions": list(QUICK_CONDITIONS if quick else CONDITIONS),
            "controllers": controllers(),
            "cases": [c.name for c in chosen],
            "runtime_s": time.perf_counter() - t0,
        },
        "cases": {c.name: _case_meta(c, horizon(c)) for c in chosen},
        "tuned": tuned,
        "runs": runs,
    }


def total_runs(
    quick: bool = False, dispersion_plants: int | None = None, n_cases: int | None = None
) -> int:
    """The number of closed-loop runs :func:`compare` makes (for a progress bar)."""
    budget, _ = tune_budget(quick)
    conds = QUICK_CONDITIONS if quick else CONDITIONS
    n_disp = dispersion_plants if dispersion_plants is not None else (2 if quick else 6)
    per = budget + len(conds) - 2 + n_disp  # nominal is the tuning's best; dispersion: n_disp
    return per * len(_KINDS) * (n_cases if n_cases is not None else len(cases(quick)))


def _case_meta(c: Case, horizon: float) -> dict[str, Any]:
    return {
        "title": c.title,
        "order": c.order,
        "joints": c.joints,
        "band": c.band,
        "t_end": horizon,
        "limits": c.limits,
        "saturated": c.saturated,
        "gain": c.gain,
        "hold": c.hold,
        "output_unit": c.output_unit,
        "input_unit": c.input_unit,
        "family": c.family,
    }


def _own(own_cases: Sequence[Case], taken: set[str]) -> dict[str, Case]:
    """The user's cases by name, checked: a Case with a factory and a new, unique name."""
    out: dict[str, Case] = {}
    for c in own_cases:
        if not isinstance(c, Case) or c.factory is None:
            raise ValueError(
                f"own_cases takes famcc.compare.Case objects with a factory, got {c!r}"
            )
        if c.name in taken or c.name in out:
            raise ValueError(f"own case name {c.name!r} is taken: choose another")
        if len(c.limits) != c.joints or len(c.gain) != c.joints or len(c.hold) != c.joints:
            raise ValueError(
                f"own case {c.name!r}: limits, gain and hold need one entry per joint ({c.joints})"
            )
        if c.joints > 1 and min(c.gain) < 0:
            raise ValueError(
                f"own case {c.name!r}: a negative gain is supported for one joint only"
            )
        out[c.name] = c
    return out
