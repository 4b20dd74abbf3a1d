"""The tuning procedure, the same for every controller: its default, a Latin hypercube, rounds."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from famcc.compare.plants import Case
from famcc.compare.spaces import _KINDS, space
from famcc.compare.workers import _Pool
from famcc.tuning.space import latin_hypercube as _lhs

#: Runs of famcc's own budget spent on the noise check (an observer tuned without
#: noise picks a bandwidth that noise punishes): its best nominal candidate under
#: noise, and the same with the observer slower (``Space.slowed``) nominal and
#: under noise.
NOISE_CHECKS = {"famcc": 3}
#: The condition of those runs.
NOISE_CHECK_CONDITION = "noise 1e-3"


def tune_budget(quick: bool) -> tuple[int, int]:
    """``(B, rounds)``: closed-loop runs per controller and plant, refinement rounds."""
    return (8, 2) if quick else (24, 3)


def _tune(
    pool: _Pool,
    chosen: list[Case],
    budget: int,
    rounds: int,
    seed: int,
    horizon: Callable[[Case], float],
) -> dict[str, Any]:
    spaces = {
        (c.name, k): [space(k, c, j) for j in range(c.joints)] for c in chosen for k in _KINDS
    }
    rngs = {
        key: np.random.default_rng([seed, ci, ki])
        for ci, c in enumerate(chosen)
        for ki, k in enumerate(_KINDS)
        for key in [(c.name, k)]
    }
    hist: dict[tuple[str, str], list[tuple[np.ndarray, float, dict[str, Any]]]] = {
        key: [] for key in spaces
    }
    case_of = {c.name: c for c in chosen}

    def tasks_for(
        points: dict[tuple[str, str], np.ndarray], condition: str = "nominal"
    ) -> list[dict[str, Any]]:
        out = []
        for key, us in points.items():
            for u in us:
                params = [s.params(u) for s in spaces[key]]
                out.append(
                    {
                        "stage": "tune",
                        "case": key[0],
                        "kind": key[1],
                        "params": params,
                        "condition": condition,
                        "u": u.tolist(),
                        "t_end": horizon(case_of[key[0]]),
                    }
                )
        return out

    def record(results: list[dict[str, Any]]) -> None:
        for r in results:
            hist[(r["case"], r["kind"])].append(
                (np.array(r["u"]), float(r["metrics"]["objective"]), r["metrics"])
            )

    own = {key: budget - NOISE_CHECKS.get(key[1], 0) for key in spaces}
    starts = {}
    for key, sp in spaces.items():  # the default first, then a Latin hypercube
        first = own[key] - own[key] // 2
        starts[key] = np.vstack([sp[0].unit(sp[0].default), _lhs(rngs[key], first - 1, sp[0].dims)])
    record(pool.map(tasks_for(starts)))
    left = {key: own[key] - len(starts[key]) for key in spaces}
    for r in range(rounds):
        sigma = 0.2 * 0.5**r
        points = {}
        for key in spaces:
            m = left[key] // (rounds - r)
            left[key] -= m
            if m == 0:
                continue
            best = min(hist[key], key=lambda h: h[1])[0]
            step = rngs[key].normal(0.0, sigma, size=(m, best.size))
            points[key] = np.clip(best + step, 0.0, 1.0)
        record(pool.map(tasks_for(points)))
    chosen_run, noisy = _noise_checked(pool, hist, spaces, tasks_for, record)
    out: dict[str, Any] = {}
    for (name, kind), h in hist.items():
        best_u, best_j, best_m = chosen_run.get((name, kind)) or min(h, key=lambda e: e[1])
        out.setdefault(name, {})[kind] = {
            "params": [s.params(best_u) for s in spaces[(name, kind)]],
            "u": best_u.tolist(),
            "objective": best_j,
            "nominal": best_m,
            # every run of the budget: the nominal ones, then those under noise
            "history": [e[1] for e in h] + noisy.get((name, kind), []),
            "noise_checks": noisy.get((name, kind), []),
            "diverged_candidates": sum(1 for e in h if e[2].get("diverged")),
        }
    return out


def _noise_checked(
    pool: _Pool,
    hist: dict[tuple[str, str], list[tuple[np.ndarray, float, dict[str, Any]]]],
    spaces: dict[tuple[str, str], list[Any]],
    tasks_for: Callable[..., list[dict[str, Any]]],
    record: Callable[[list[dict[str, Any]]], None],
) -> tuple[
    dict[tuple[str, str], tuple[np.ndarray, float, dict[str, Any]]],
    dict[tuple[str, str], list[float]],
]:
    """The nominal run of the candidate chosen with the noise check, per controller that has
    one, and the objectives of the runs under noise.

    The best nominal candidate and the same with its observer slower
    (``Space.slowed``; its nominal run joins the history) run under
    ``NOISE_CHECK_CONDITION``; the one with the least product of its nominal and
    noisy objectives is chosen (its nominal run stands for it): the product weighs
    their relative changes alike, where a sum follows the noisy run's objective,
    10-100x the nominal one (measured: the sum chose a two-link-arm candidate with
    19x the best nominal objective, TV(u) 2e4/s against 88/s).
    """
    best: dict[tuple[str, str], tuple[np.ndarray, float, dict[str, Any]]] = {}
    slowed: dict[tuple[str, str], np.ndarray] = {}
    for key, h in hist.items():
        if NOISE_CHECKS.get(key[1], 0):
            best[key] = min(h, key=lambda e: e[1])
            slow = spaces[key][0].slowed(best[key][0])
            if slow is not None:
                slowed[key] = slow
    if not best:
        return {}, {}
    n_before = {key: len(hist[key]) for key in slowed}
    record(pool.map(tasks_for({key: np.array([u]) for key, u in slowed.items()})))
    candidates = {
        key: [e] + hist[key][n_before[key] :] if key in slowed else [e] for key, e in best.items()
    }
    points = {key: np.array([e[0] for e in es]) for key, es in candidates.items()}
    results = pool.map(tasks_for(points, NOISE_CHECK_CONDITION))
    noisy: dict[tuple[str, str], list[float]] = {key: [] for key in candidates}
    for r in results:
        noisy[(r["case"], r["kind"])].append(float(r["metrics"]["objective"]))
    out = {}
    for key, es in candidates.items():
        js = noisy[key]
        i = min(range(len(es)), key=lambda i: es[i][1] * js[i])
        out[key] = es[i]
    return out, noisy
