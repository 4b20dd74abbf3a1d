"""The tuned controllers run unchanged under every condition; the worst of the dispersed plants."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from famcc.compare.conditions import CONDITIONS, DISPERSION, QUICK_CONDITIONS
from famcc.compare.plants import Case
from famcc.compare.spaces import _KINDS
from famcc.compare.workers import _Pool


def _evaluate(
    pool: _Pool,
    chosen: list[Case],
    tuned: dict[str, Any],
    quick: bool,
    n_disp: int,
    seed: int,
    horizon: Callable[[Case], float],
) -> dict[str, Any]:
    conds = QUICK_CONDITIONS if quick else CONDITIONS
    tasks = []
    for ci, c in enumerate(chosen):
        rng = np.random.default_rng([seed, 99, ci])
        draws = [
            {k: float(rng.uniform(1 - DISPERSION, 1 + DISPERSION)) for k in c.params}
            for _ in range(n_disp)
        ]
        for kind in _KINDS:
            params = tuned[c.name][kind]["params"]
            for cond in conds:
                if cond == "nominal":
                    continue  # the tuning's best run is the nominal one
                if cond == "dispersion":
                    for i, f in enumerate(draws):
                        tasks.append(
                            {
                                "stage": "eval",
                                "case": c.name,
                                "kind": kind,
                                "params": params,
                                "condition": "nominal",
                                "factors": f,
                                "seed": seed + i,
                                "dispersion": i,
                                "t_end": horizon(c),
                            }
                        )
                    continue
                tasks.append(
                    {
                        "stage": "eval",
                        "case": c.name,
                        "kind": kind,
                        "params": params,
                        "condition": cond,
                        "seed": seed,
                        "t_end": horizon(c),
                    }
                )
    done = pool.map(tasks)
    runs: dict[str, Any] = {
        c.name: {k: {"nominal": tuned[c.name][k]["nominal"]} for k in _KINDS} for c in chosen
    }
    disp: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for r in done:
        if "dispersion" in r:
            disp.setdefault((r["case"], r["kind"]), []).append(r["metrics"])
        else:
            runs[r["case"]][r["kind"]][r["condition"]] = r["metrics"]
    for (name, kind), ms in disp.items():
        runs[name][kind]["dispersion"] = _worst_of(ms)
    return runs


def _worst_of(ms: list[dict[str, Any]]) -> dict[str, Any]:
    """The worst over dispersed plants: largest numbers, any flag; counts of failures."""
    out: dict[str, Any] = {"plants": len(ms)}
    for key in (
        "iae",
        "steady_rms",
        "final_rms",
        "settling_time",
        "rms_u",
        "tv_u",
        "z1_ripple",
        "u_ripple",
        "saturated",
        "objective",
    ):
        vals = [m.get(key) for m in ms]
        nums = [float(v) for v in vals if v is not None]
        out[key] = None if len(nums) < len(vals) else max(nums)
    out["diverged"] = any(m.get("diverged") for m in ms)
    out["never_settled"] = any(m.get("never_settled") for m in ms)
    out["diverged_count"] = sum(1 for m in ms if m.get("diverged"))
    out["never_settled_count"] = sum(1 for m in ms if m.get("never_settled"))
    return out
