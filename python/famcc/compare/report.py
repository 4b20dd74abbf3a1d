"""``report.md`` and ``results.json`` of ``famcc compare``: the text, the tables, the losses."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from famcc.compare.figures import _LABEL, _radar_figure, _series_figure, _telling
from famcc.compare.findings import (
    LOSS_FACTOR,
    LOSS_METRICS,
    _g,
    _value,
    loss_text,
    losses,
    radar_scores,
)
from famcc.compare.plants import _case
from famcc.compare.runs import run
from famcc.compare.spaces import _KINDS, SLOWER_OBSERVER
from famcc.compare.tuning import NOISE_CHECK_CONDITION, NOISE_CHECKS


def write_report(result: dict[str, Any], out: str | Path, *, figures: bool = True) -> Path:
    """Writes ``report.md``, ``results.json`` and the figures into ``out``; returns the report."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out)
    (out / "figures").mkdir(parents=True, exist_ok=True)
    found = losses(result)
    meta = result["meta"]
    lines = _intro(result) + _overview(result)
    for name in meta["cases"]:
        case, info = _case(name), result["cases"][name]
        lines += [
            f"## {name}",
            "",
            (
                f"{info['title']}; band {_g(case.band)} {case.output_unit}, "
                f"horizon {_g(info['t_end'])} s, limits {_lims(case.limits)}, saturated "
                f"{_lims(case.saturated)}."
            ),
            "",
        ]
        lines += _tuned_table(result, name) + [""] + _table(result, name) + [""]
        if figures:
            scores = radar_scores(result, name)
            fig = _radar_figure(scores, f"{name}: characteristics (1 kHz)")
            fig.savefig(out / "figures" / f"{name}-radar.png")
            plt.close(fig)
            cond = _telling(result, name, found)
            series = {
                k: run(
                    case,
                    k,
                    result["tuned"][name][k]["params"],
                    cond,
                    t_end=info["t_end"],
                    seed=meta["seed"],
                )
                for k in _KINDS
            }
            fig = _series_figure(case, series, cond)
            fig.savefig(out / "figures" / f"{name}-series.png")
            plt.close(fig)
            # famcc's own run of that case, in the figure of `famcc reproduce`
            fig = series["famcc"][0].plot(
                ["accuracy", "input"], eps=case.band, title=f"famcc on {name}, {cond}"
            )
            fig.savefig(out / "figures" / f"{name}-famcc.png", dpi=55)
            plt.close(fig)
            lines += [
                f"![{name} radar](figures/{name}-radar.png)",
                f"![{name} time series, {cond}](figures/{name}-series.png)",
                "",
                "famcc's run in that case (`SimResult.plot`; the first joint for the arm):",
                "",
                f"![famcc on {name}, {cond}](figures/{name}-famcc.png)",
                "",
            ]
    lines += ["## Where famcc loses", ""]
    if not found:
        lines += [
            (
                "Nowhere in these runs: no peer beat famcc by more than "
                f"{LOSS_FACTOR:g}x on {', '.join(lb for _, lb in LOSS_METRICS)}."
            ),
            "",
        ]
    else:
        lines += [
            (
                f"Generated from the tables: every plant and condition where a peer beats "
                f"famcc by more than {LOSS_FACTOR:g}x on {', '.join(lb for _, lb in LOSS_METRICS)}"
                ", or where famcc diverged or never settled and a peer did not "
                f"({len(found)} cases)."
            ),
            "",
        ]
        for name in meta["cases"]:
            mine = [x for x in found if x["case"] == name]
            if mine:
                lines += [f"- {loss_text(x)}" for x in mine]
        lines += [""]
        lines += _loss_summary(found, meta)
    (out / "report.md").write_text("\n".join(lines) + "\n")
    payload = {**result, "losses": found}
    (out / "results.json").write_text(json.dumps(payload, indent=1, default=_json))
    return out / "report.md"


def _json(v: Any) -> Any:
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    raise TypeError(type(v).__name__)


def _lims(limits: Sequence[Sequence[float]]) -> str:
    return ", ".join(f"[{_g(lo)}, {_g(hi)}]" for lo, hi in limits)


def _intro(result: dict[str, Any]) -> list[str]:
    meta = result["meta"]
    b, rounds = meta["budget"], meta["rounds"]
    mode = "quick (`--quick`)" if meta["quick"] else "full"
    return [
        "# famcc compare: famcc against PID, ADRC and LMCC",
        "",
        (
            f"Run: {mode}, {len(meta['cases'])} plants x {len(meta['controllers'])} controllers x "
            f"{len(meta['conditions'])} conditions, {meta['jobs']} worker processes, "
            f"**{meta['runtime_s']:.0f} s** wall time (seed {meta['seed']}). Written by "
            "`famcc compare` (`famcc.compare`); the numbers are in `results.json`."
        ),
        "",
        (
            "**Controllers.** famcc: its law with the extended observer (docs/observer.md: "
            "the lumped term estimated with `b0` = the plant's nominal gain and cancelled, "
            "bounded by the actuator's range), the finite-time law on the lateral constraint "
            "at order 2 and `Linear` stages on the longitudinal one above, with its flexible "
            "boundary; LMCC: famcc with `Linear` stages and "
            "no flexible boundary (`rho_e=None`), the low-complexity PPC special case the "
            "paper names; PID: simple-pid with its output limits (anti-windup) and a "
            "first-order measurement filter; ADRC: linear ADRC with an ESO, bandwidth-"
            "parameterised, `b0` = the plant's nominal gain (pyadrc at order 2, the same "
            "discretisation generalised at orders 3 and 4). Each joint of the arm has its "
            "own controller (decentralised). famcc and LMCC discretize their differentiator "
            "as famcc picks for the sample period (`HighGain.discretization_for`: the exact "
            "hold while mu >= 10 dt, the first-order hold below, up to order 3; Tustin from "
            "order 4 on)."
        ),
        "",
        (
            f"**Tuning (the same for all four).** Budget {b} closed-loop runs per controller "
            f"and plant on the nominal plant at 1 kHz: the controller's documented default "
            "(famcc: its law with the observer and `b0 = G`, scaled by the plant's holding "
            "input H; PID and ADRC: pole placement at 10 rad/s), "
            "Latin-hypercube points over its documented ranges "
            "(`famcc.compare.space`, scaled by the plant's gain G, H and the band), then "
            f"rounds ({rounds}) of Gaussian steps around the best so far: half the budget "
            "each, famcc's own budget less its noise checks "
            f"({NOISE_CHECKS['famcc']} runs: its best candidate under {NOISE_CHECK_CONDITION}, "
            f"and the same with its observer {SLOWER_OBSERVER:g}x slower nominal and under "
            f"{NOISE_CHECK_CONDITION}; the one with the least product of its two objectives is "
            "chosen, as an observer tuned without noise picks a bandwidth noise punishes). "
            "Objective `J = IAE / (band T) + 0.01 TV(u) / H + 10 [never settled]`, "
            "`J = 1e6` when diverged (`H` the plant's holding input). The best candidate is "
            "then run unchanged under every condition."
        ),
        "",
        (
            "**Conditions.** nominal (1 kHz); saturated (the tighter limits given per plant); "
            "measurement noise, white Gaussian with std 1e-4, 1e-3, 1e-2 output units; "
            f"dispersion: {meta['dispersion_plants']} plants with every physical parameter "
            f"times U(0.7, 1.3), the worst of them shown; 200 Hz (the same parameters; "
            "famcc's observer and LMCC's differentiator discretized for it). "
            "A run diverges when |z1| exceeds 10 max(|z1(0)|, 1) or a value becomes non-finite."
        ),
        "",
        (
            "**Metrics.** IAE (int |z1| dt, output unit s, summed over joints); RMS z1 over "
            "the second half of the run; steady RMS and settling time to the band (- when "
            "never settled); RMS u; TV(u)/s (total variation of u per second); peak-to-peak "
            "ripple of z1 and u after settling; saturated: share of samples with the input "
            "at a limit (the peers clamp their own output); flags. "
            "`famcc.SimResult` has them all (`iae`, `steady_rms`, `rms_u`, `tv_u_per_s`, "
            "`z1_ripple`, `ripple`, `diverged`, `never_settled`)."
        ),
        "",
        (
            "**Radar charts** (the paper's empty figure 'Comparison of characteristics of "
            "different controllers'): accuracy = nominal RMS z1 (2nd half), speed = nominal "
            "settling time (horizon if never), effort = nominal RMS u, smoothness = nominal "
            "TV(u)/s, noise robustness = RMS z1 (2nd half) at noise 1e-3, saturation "
            "robustness = IAE with the tighter limits. Each axis scores "
            "`log(worst / v) / log(worst / best)`: 1 the best of the four, 0 the worst or "
            "diverged; all 1 within 5 %."
        ),
        "",
    ]


def _rank(runs: dict[str, Any], cond: str, metric: str) -> list[str]:
    """The controllers that did not diverge, best first by ``metric`` (None last)."""
    live = [k for k in _KINDS if cond in runs[k] and not runs[k][cond].get("diverged")]
    return sorted(
        live, key=lambda k: (runs[k][cond].get(metric) is None, runs[k][cond].get(metric) or 0.0)
    )


def _overview(result: dict[str, Any]) -> list[str]:
    """Per plant and condition: the best IAE, and famcc's place among the four."""
    conds = result["meta"]["conditions"]
    rows = [
        "## Overview",
        "",
        (
            "Best IAE per plant and condition, and famcc's place by IAE among the four "
            "(`div.`: famcc diverged). The tables below have every metric."
        ),
        "",
        "| plant | " + " | ".join(conds) + " |",
        "|---|" + "---|" * len(conds),
    ]
    for name, runs in result["runs"].items():
        cells = []
        for cond in conds:
            order = _rank(runs, cond, "iae")
            place = f"famcc {order.index('famcc') + 1}." if "famcc" in order else "famcc div."
            cells.append(f"{_LABEL[order[0]]} ({place})" if order else "all diverged")
        rows.append(f"| {name} | " + " | ".join(cells) + " |")
    return [*rows, ""]


def _tuned_table(result: dict[str, Any], name: str) -> list[str]:
    rows = [
        "| controller | tuned parameters (joint 1) | J nominal | diverged candidates |",
        "|---|---|---|---|",
    ]
    for k in _KINDS:
        t = result["tuned"][name][k]
        p = t["params"][0]
        shown = ", ".join(
            f"{key} {_g(v)}"
            for key, v in p.items()
            if isinstance(v, float) and key not in ("band", "gain", "b0")
        )
        rows.append(
            f"| {_LABEL[k]} | {shown} | {_g(t['objective'])} | "
            f"{t['diverged_candidates']}/{len(t['history'])} |"
        )
    return rows


def _table(result: dict[str, Any], name: str) -> list[str]:
    runs = result["runs"][name]
    rows = [
        (
            "| condition | controller | IAE | RMS z1 (2nd half) | steady RMS | settling [s] | "
            "RMS u | TV(u)/s | ripple z1 | ripple u | saturated | flags |"
        ),
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for cond in result["meta"]["conditions"]:
        vals = {k: _value(runs[k].get(cond), "iae", 0.0) for k in _KINDS}
        ok = [v for v in vals.values() if v is not None]
        best = min(ok) if ok else None
        for k in _KINDS:
            m = runs[k].get(cond)
            if m is None:
                continue
            flags = []
            if m.get("diverged"):
                n = m.get("diverged_count")
                flags.append("diverged" + (f" {n}/{m['plants']}" if n is not None else ""))
            if m.get("never_settled") and not m.get("diverged"):
                n = m.get("never_settled_count")
                flags.append("never settled" + (f" {n}/{m['plants']}" if n is not None else ""))
            iae = _g(m.get("iae"))
            if best is not None and vals[k] == best:
                iae = f"**{iae}**"
            rows.append(
                f"| {cond} | {_LABEL[k]} | {iae} | {_g(m.get('final_rms'))} | "
                f"{_g(m.get('steady_rms'))} | {_g(m.get('settling_time'))} | "
                f"{_g(m.get('rms_u'))} | {_g(m.get('tv_u'))} | {_g(m.get('z1_ripple'))} | "
                f"{_g(m.get('u_ripple'))} | {_pct(m.get('saturated'))} | {', '.join(flags)} |"
            )
    return rows


def _pct(v: Any) -> str:
    return "-" if v is None else f"{100 * float(v):.3g} %"


def _loss_summary(found: list[dict[str, Any]], meta: dict[str, Any]) -> list[str]:
    """Counts per peer and per condition (from the same list)."""
    by_peer: dict[str, int] = {}
    by_cond: dict[str, int] = {}
    for x in found:
        for w in x["winners"]:
            by_peer[w] = by_peer.get(w, 0) + 1
        by_cond[x["condition"]] = by_cond.get(x["condition"], 0) + 1
    peer_text = ", ".join(f"{_LABEL[k]} {by_peer[k]}" for k in _KINDS if k in by_peer)
    cond_text = ", ".join(f"{c} {by_cond[c]}" for c in meta["conditions"] if c in by_cond)
    return [f"Losses by winning peer: {peer_text}. By condition: {cond_text}.", ""]
