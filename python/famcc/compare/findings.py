"""What the numbers say: the radar's scores and where famcc loses."""

from __future__ import annotations

import math
from typing import Any

#: The radar's axes: (name, condition, metric), lower metric is better.
RADAR = (
    ("accuracy", "nominal", "final_rms"),
    ("speed", "nominal", "settling_time"),
    ("effort", "nominal", "rms_u"),
    ("smoothness", "nominal", "tv_u"),
    ("noise robustness", "noise 1e-3", "final_rms"),
    ("saturation robustness", "saturated", "iae"),
)
#: The metrics "Where famcc loses" compares (lower is better).
LOSS_METRICS = (("iae", "IAE"), ("final_rms", "RMS z1 (2nd half)"), ("tv_u", "TV(u)/s"))
#: A loss is reported when a peer beats famcc by more than this factor.
LOSS_FACTOR = 1.1


def _value(m: dict[str, Any] | None, metric: str, t_end: float) -> float | None:
    """A metric for ranking: None when diverged; a never-settled run takes the horizon."""
    if m is None or m.get("diverged"):
        return None
    v = m.get(metric)
    if v is None and metric == "settling_time":
        return t_end
    return None if v is None else float(v)


def radar_scores(result: dict[str, Any], name: str) -> dict[str, dict[str, float]]:
    """Per controller and radar axis, a score in [0, 1] (1 the best of the four).

    ``score = log(worst / v) / log(worst / best)`` of the axis' metric ``v``
    (lower is better; a log scale because the metrics span decades); all 1 when
    the four are within 5 %; 0 for a diverged run. A never-settled run's
    settling time is the horizon. Axes whose condition was not run are left out.
    """
    runs, t_end = result["runs"][name], result["cases"][name]["t_end"]
    out: dict[str, dict[str, float]] = {k: {} for k in runs}
    for axis, cond, metric in RADAR:
        if any(cond not in runs[k] for k in runs):
            continue
        vals = {k: _value(runs[k][cond], metric, t_end) for k in runs}
        ok = [v for v in vals.values() if v is not None]
        floor = 1e-12
        for k, v in vals.items():
            if v is None:
                out[k][axis] = 0.0
            elif len(ok) < 2 or max(ok) <= 1.05 * max(min(ok), floor):
                out[k][axis] = 1.0
            else:
                lo, hi = max(min(ok), floor), max(ok)
                out[k][axis] = float(math.log(hi / max(v, floor)) / math.log(hi / lo))
    return out


def losses(result: dict[str, Any]) -> list[dict[str, Any]]:
    """Every (plant, condition, metric) where a peer beats famcc, from the numbers.

    A loss: famcc diverged (or never settled) where a peer did not, or a peer's
    metric from :data:`LOSS_METRICS` is more than :data:`LOSS_FACTOR` times
    better than famcc's. Each entry names the best such peer with both values.
    """
    out = []
    for name, runs in result["runs"].items():
        for cond in result["meta"]["conditions"]:
            fm = runs["famcc"].get(cond)
            if fm is None:
                continue
            peers = [k for k in runs if k != "famcc" and cond in runs[k]]
            for flag in ("diverged", "never_settled"):
                if fm.get(flag):
                    fine = [k for k in peers if not runs[k][cond].get(flag)]
                    if fine:
                        out.append(
                            {
                                "case": name,
                                "condition": cond,
                                "metric": flag,
                                "winners": fine,
                                "famcc": True,
                                "peer": False,
                            }
                        )
            if fm.get("diverged"):
                continue
            for metric, _label in LOSS_METRICS:
                fv = fm.get(metric)
                if fv is None:
                    continue
                best = None
                for k in peers:
                    pm = runs[k][cond]
                    pv = None if pm.get("diverged") else pm.get(metric)
                    if pv is not None and pv * LOSS_FACTOR < fv and (best is None or pv < best[1]):
                        best = (k, float(pv))
                if best is not None:
                    out.append(
                        {
                            "case": name,
                            "condition": cond,
                            "metric": metric,
                            "winners": [best[0]],
                            "famcc": float(fv),
                            "peer": best[1],
                            "ratio": float(fv) / max(best[1], 1e-300),
                        }
                    )
    return out


def loss_text(loss: dict[str, Any]) -> str:
    """One line of "Where famcc loses"."""
    where = f"{loss['case']}, {loss['condition']}"
    if loss["metric"] in ("diverged", "never_settled"):
        if loss["metric"] == "diverged":
            what, peers = "diverged", "did not diverge"
        else:
            what, peers = "never settled to the band", "settled"
        return f"{where}: famcc {what}; {', '.join(loss['winners'])} {peers}."
    label = dict(LOSS_METRICS)[loss["metric"]]
    return (
        f"{where}: {label} {loss['winners'][0]} {_g(loss['peer'])} vs famcc "
        f"{_g(loss['famcc'])} ({_ratio(loss['ratio'])})"
    )


def _g(v: Any, digits: int = 3) -> str:
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    return f"{float(v):.{digits}g}"


def _ratio(r: float) -> str:
    """A loss ratio; beyond 1000x (a peer at rounding-error level) only its order."""
    return f"{r:.1f}x" if r < 1000.0 else ">1000x"
