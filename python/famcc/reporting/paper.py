"""``famcc reproduce``: the paper's scenarios run, measured and reported with the paper's notes."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from famcc import _core, scenarios
from famcc.progress import Progress
from famcc.reporting.notes import _accuracy_text, _episodes_text, _missing_notes, _saturation_note
from famcc.reporting.records import _num, diverged, measure
from famcc.reporting.tables import _t
from famcc.reporting.writer import _save_figure, _write
from famcc.verdicts import STARTUP

#: docs/design.md §6 in a few lines: what differs between the two variants.
VARIANT_DIFFERENCES = (
    (
        "second-order plant: disturbance `3 sin t + 3 cos 2t` in the authors' code, "
        "`sin t + cos 2t` in the paper"
    ),
    (
        "third-order plant: x(0) = (1, 0.5, 4) and eps_y = 3 in the code, (1, -0.2, 0.4) and "
        "eps_y = 5 in the paper (the paper's printed x1-dot also omits the factor x2, which makes "
        "the plant uncontrollable; both variants restore it)"
    ),
    (
        "skew offsets: the code multiplies the whole skewed function by its gain, so in famcc's "
        "terms example 2 uses eps_s = 0.225 (paper 0.15) and example 3's first stage "
        "eps_s = 0.1 (paper 0.2)"
    ),
    (
        'envelope latch: the code uses rho_0 = max(k0 |s(0)|, eps) (`latch="authors"`), the '
        "paper k0 max(|s(0)|, eps)"
    ),
)


def reproduce(
    out: str | Path,
    *,
    names: Sequence[str] | None = None,
    variant: str = "code",
    dt: float = 1e-3,
    t_end: float | None = None,
    figures: bool = True,
    progress: Any = "stderr",
    observer: float | None = None,
) -> list[dict[str, Any]]:
    """Runs the scenarios, writes figures, ``report.md`` and ``summary.json`` into ``out``.

    Parameters
    ----------
    out : path
        Output directory (created).
    names : list of str, optional
        Scenario names (default: all six, :func:`famcc.scenarios.names`).
    variant : "code" or "paper"
    dt : float
        Sample period, s.
    t_end : float, optional
        Horizon, s (default: the scenario's, 10 s).
    figures : bool
        Draw the PNGs (the report then embeds them).
    progress : "stderr", None or a :class:`Progress`
        Where to report progress.
    observer : float, optional
        Run every scenario with the extended observer of this ``mu`` (s) in the
        differentiator's place (:meth:`famcc.scenarios.Scenario.with_observer`;
        design, plant, limits and claims unchanged). None: the paper's
        differentiator.

    Returns
    -------
    list of dict
        One :func:`measure` record per scenario (plus ``figure``, the PNG's file
        name or None). No guarantee failed when every ``violations`` is empty;
        untested ones are listed in ``verdicts``.
    """
    names = list(scenarios.names() if not names else names)
    for name in names:
        if name not in scenarios.names():
            raise ValueError(
                f"unknown scenario {name!r}; choose from {', '.join(scenarios.names())}"
            )
    if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be a finite number > 0, got {dt!r}")
    if observer is not None and not (
        isinstance(observer, (int, float)) and math.isfinite(observer) and observer > 0
    ):
        raise ValueError(f"observer (its mu, s) must be a finite number > 0, got {observer!r}")
    if t_end is not None and not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0, got {t_end!r}")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    bar = (
        Progress(
            len(names),
            f"famcc reproduce: {len(names)} scenario(s), variant "
            f"{variant!r}, dt = {dt:g} s -> {out}",
        )
        if progress == "stderr"
        else progress
    )
    t_start = time.perf_counter()
    records = []
    results = {}
    for name in names:
        sc = scenarios.paper(name, variant)
        if observer is not None:
            sc = sc.with_observer(mu=float(observer))
        t0 = time.perf_counter()
        try:
            res = sc.run(dt=dt, t_end=t_end)
            if res.diverged:  # stopped there by Scenario.run: a record without metrics
                raise FloatingPointError(f"the run diverged at t = {res.diverged_at:.4g} s")
        except (FloatingPointError, OverflowError) as exc:
            rec = diverged(sc, exc, time.perf_counter() - t0)
            records.append(rec)
            if bar is not None:
                bar.step(f"{name} (diverged)", rec["runtime_s"])
            continue
        sim_s = time.perf_counter() - t0
        rec = measure(sc, res, sim_s)
        rec["figure"] = None
        if figures:
            from famcc import plot  # deferred: famcc.plot loads matplotlib

            panels = plot.scenario_panels(res.z.shape[1])
            _save_figure(rec, plot.scenario_figure(sc, res), out, name, plot.legend(panels))
        records.append(rec)
        results[name] = res
        if bar is not None:
            c = rec["verdict_counts"]
            status = f"{c['held']} held, {c['failed']} failed, {c['untested']} untested"
            bar.step(f"{name} ({status})", time.perf_counter() - t0)
    meta = {
        "variant": variant,
        "dt": float(dt),
        "t_end": t_end,
        "observer_mu": None if observer is None else float(observer),
        "runtime_s": time.perf_counter() - t_start,
    }
    write_report(records, out, meta)
    return records


def write_report(
    records: Sequence[dict[str, Any]], out: str | Path, meta: dict[str, Any]
) -> tuple[Path, Path]:
    """Writes ``famcc reproduce``'s ``report.md`` and ``summary.json``; returns their paths.

    The paper's report is the general one (:func:`report`'s writer) with the
    paper's columns, notes and the command that regenerates it.
    """
    horizon = meta.get("t_end") or 10.0
    dt = float(meta.get("dt") or 1e-3)
    intro = (
        f"Variant `{meta.get('variant')}`, sample period dt = {dt:g} s "
        f"({1.0 / dt:g} Hz), horizon {horizon:g} s (saturated runs are extended until their "
        "recovery claims can fall due, see the table), famcc "
        f"{_core.__version__}"
        + (f", {meta['runtime_s']:.1f} s wall time" if meta.get("runtime_s") else "")
        + (
            f". With the extended observer (mu = {meta['observer_mu']:g} s, b0 = the plant's "
            "nominal gain, docs/observer.md) in the differentiator's place"
            if meta.get("observer_mu")
            else ""
        )
        + ". The same numbers are in [`summary.json`](summary.json); the figures are explained "
        "in `docs/figures.md`."
    )
    regenerate = (
        f"famcc reproduce --variant {meta.get('variant')} --dt {meta.get('dt'):g}"
        + (f" --t-end {meta['t_end']:g}" if meta.get("t_end") else "")
        + (f" --observer {meta['observer_mu']:g}" if meta.get("observer_mu") else "")
        + " --out DIR"
    )
    return _write(
        records,
        Path(out),
        title="famcc reproduce: the paper's simulations",
        intro=intro,
        notes=_notes(records, meta),
        summary_meta={
            "variant": meta.get("variant"),
            "dt": meta.get("dt"),
            "t_end": meta.get("t_end"),
            "observer_mu": meta.get("observer_mu"),
            "runtime_s": _num(meta.get("runtime_s")),
        },
        key="scenarios",
        regenerate=regenerate,
        columns_extra=(
            " Here eps = 0.1 (the paper's accuracy); paper: the time the paper reports; bound: "
            "the corollary's bound T_s + T' for a run that never saturated, max(T_e, T_s) + T' "
            "otherwise (T_e: end of the last saturation episode). Saturated scenarios may run "
            "past 10 s so that their recovery claims fall due (the horizon of each run is in "
            "`summary.json`)."
        ),
    )


def _notes(records: Sequence[dict[str, Any]], meta: dict[str, Any]) -> list[str]:
    notes: list[str] = [
        f"- **{r['scenario']} diverged**: {r['error']}. Every claim of it counts as failed."
        for r in records
        if r.get("error")
    ]
    records = [r for r in records if not r.get("error")]
    variant = meta["variant"]
    other = "paper" if variant == "code" else "code"
    notes.append(
        f"- **Variant.** These runs use variant `{variant}`"
        + (
            " (the numbers of the authors' public MATLAB code, the default)"
            if variant == "code"
            else " (the numbers printed in the paper)"
        )
        + f"; `famcc reproduce --variant {other}` runs the other one. They differ because the "
        "paper and the code disagree (docs/design.md §6): "
        + "; ".join(VARIANT_DIFFERENCES)
        + ". With the paper's printed disturbance amplitude 1 "
        "the saturated second-order runs barely saturate; with the code's amplitude 3 they do."
    )
    by_name = {r["scenario"]: r for r in records}
    for r in records:
        p = r["paper_settling_time"]
        if p is None:
            continue
        ts = r["settling_time"]
        if ts is None:
            notes.append(
                f"- **{r['scenario']}.** Never settled within the horizon; the paper "
                f"reports {p:g} s."
            )
            continue
        diff = ts - p
        verdict = "close to" if abs(diff) <= 0.1 else ("faster than" if diff < 0 else "slower than")
        line = (
            f"- **{r['scenario']} (example {r['example']}).** Measured settling time "
            f"{_t(ts)} s, {verdict} the paper's {p:g} s ({diff:+.2f} s); the corollary's "
            f"bound is {r['bound']:.3g} s."
        )
        if r["example"] == 1:
            line += (
                " The authors' own code, run closed loop, also settles example 1 in about "
                "1.3 s: the printed 1.9 s is not what the published law produces, and famcc "
                "matches the mathematics, not the printed number."
            )
        if r["example"] == 3:
            line += (
                " The two variants start from different states (x(0) = (1, 0.5, 4) in the "
                "code, (1, -0.2, 0.4) in the paper) and use different eps_y, so a "
                "difference of a few tenths of a second is expected."
            )
        notes.append(line)
    latch, peaking = [], []
    for r in records:
        lo_late, hi_late = r["u_range_after_startup"]
        late_peak = max(abs(lo_late), abs(hi_late))
        peak = max(abs(r["u_min"]), abs(r["u_max"]))
        if r["saturated_scenario"] or peak <= 1.5 * late_peak:
            continue
        if peak <= 1.05 * abs(r["u_initial"]):
            latch.append(
                f"{r['scenario']} (u(0) = {r['u_initial']:.3g}, |u| <= "
                f"{late_peak:.3g} after {STARTUP:g} s)"
            )
        else:
            peaking.append(
                f"{r['scenario']} (|u| up to {peak:.3g} at t = "
                f"{r['u_peak_time']:.3f} s, <= {late_peak:.3g} after {STARTUP:g} s)"
            )
    if latch:
        notes.append(
            "- **Initial input.** The envelope latches rho_0 = k0 |s(0)|, so xi~(0) = 1/k0 = 0.5 "
            "and u(0) = -k_u Gamma(+-0.5), larger than anything later in: " + "; ".join(latch) + "."
        )
    if peaking:
        notes.append(
            "- **Start-up peaking.** The high-gain differentiator starts from z_hat = (e0, 0, "
            "...) and overshoots for a few time constants (mu = 0.01 s; about 0.1 s for order "
            "3); the law passes that to u: " + "; ".join(peaking) + ". The u panels are zoomed "
            "past it and state the off-scale range."
        )
    for r in records:
        if not r["saturated_scenario"] and r["saturated_fraction"] > 0:
            notes.append(
                f"- **{r['scenario']}** is an unsaturated scenario (limits "
                f"[{r['u_limits'][0]:g}, {r['u_limits'][1]:g}]) but v left the limits during "
                f"{_episodes_text(r['saturation_episodes'])}: the differentiator's start-up "
                "peaking (docs/design.md §7.1). The settling claim therefore uses "
                f"max(T_e, T_s) + T' = {r['bound']:.3g} s."
            )
    for r in records:
        if not r["saturated_scenario"]:
            continue
        line = _saturation_note(r)
        if r["t_end"] > 10.0 + r["dt"]:
            line += (
                f" The run was extended to {r['t_end']:.3g} s so that the recovery claim of "
                "its last saturation episode could fall due."
            )
        line += _accuracy_text(r)
        for v in r["verdicts"]:
            line += f" Claim *{v['name']}*: {v['status']} ({v['detail']})."
            if v["known"] and v["status"] == "failed":
                line += (
                    " This is the documented behaviour of the paper's own numbers "
                    "(docs/errata.md): it is reported, not tuned away."
                )
        notes.append(line)
    notes += [line for r in records for line in _missing_notes(r)]
    if variant == "code" and "rfc-saturated" in by_name:
        notes.append(
            "- With variant `paper` the saturated third-order run (-F/G reaches about "
            "[-22, 30], far outside [-7, 9]) never regains 0.1 accuracy within 10 s; "
            "its *settles* claim then fails, marked as known (docs/errata.md)."
        )
    notes.append(
        "- **What the guarantees are** (`Scenario.verdicts`, docs/design.md §8). Each claim is "
        "held, failed or untested, and a test shows each one failing on a bad run. A scenario "
        "designed without saturation (limits +-100): *settling*, |z1| < 0.1 for good from "
        "max(T_e, T_s) + T' on (T_e > 0 only when the start-up peaking saturated, Corollaries "
        f"1-3); *unsaturated*, v inside the limits after the first {STARTUP:g} s; *nominal*, "
        "the bounds stay nominal after it (Theorems 1-3 keep the state inside the nominal "
        "constraint set). A saturated scenario: *settles*, settled by the paper's 10 s "
        "horizon; *recovery*, |z1| < 0.1 from each saturation episode's max(T_e, T_s) + T' "
        "until the next episode; *nominal-again*, the bounds nominal in those windows. A claim "
        "whose bound lies beyond the horizon, or that saturation pre-empts every time, is "
        "untested, never held. |xi~| < 1 is not a claim: once the bounds expand it holds by "
        "construction; the table shows the nominal |xi| beside it. The settling time is the "
        'first time after which |z1| < 0.1 holds to the end; "first entry" is the first '
        "sample inside the band."
    )
    return notes
