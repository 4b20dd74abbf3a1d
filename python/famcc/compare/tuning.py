"""The tuning procedure, the same for every controller: its default, a Latin hypercube, rounds."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from famcc.compare.plants import Case
from famcc.compare.spaces import _KINDS, space
from famcc.compare.workers import _Pool


def tune_budget(quick: bool) -> tuple[int, int]:
    """``(B, rounds)``: closed-loop runs per controller and plant, refinement rounds."""
    return (8, 2) if quick else (24, 3)


def _lhs(rng: np.random.Generator, n: int, d: int) -> np.ndarray:
    """``n`` Latin-hypercube points in ``[0, 1]^d``."""
    out = np.empty((n, d))
    for j in range(d):
        out[:, j] = (rng.permutation(n) + rng.random(n)) / n
    return out


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

    def tasks_for(points: dict[tuple[str, str], np.ndarray]) -> list[dict[str, Any]]:
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
                        "condition": "nominal",
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

    first = budget - budget // 2
    starts = {}
    for key, sp in spaces.items():  # the default first, then a Latin hypercube
        starts[key] = np.vstack([sp[0].unit(sp[0].default), _lhs(rngs[key], first - 1, sp[0].dims)])
    record(pool.map(tasks_for(starts)))
    left = budget - first
    for r in range(rounds):
        m = left // (rounds - r)
        left -= m
        if m == 0:
            continue
        sigma = 0.2 * 0.5**r
        points = {}
        for key in spaces:
            best = min(hist[key], key=lambda h: h[1])[0]
            step = rngs[key].normal(0.0, sigma, size=(m, best.size))
            points[key] = np.clip(best + step, 0.0, 1.0)
        record(pool.map(tasks_for(points)))
    out: dict[str, Any] = {}
    for (name, kind), h in hist.items():
        best_u, best_j, best_m = min(h, key=lambda e: e[1])
        out.setdefault(name, {})[kind] = {
            "params": [s.params(best_u) for s in spaces[(name, kind)]],
            "u": best_u.tolist(),
            "objective": best_j,
            "nominal": best_m,
            "history": [e[1] for e in h],
            "diverged_candidates": sum(1 for e in h if e[2].get("diverged")),
        }
    return out
