"""``famcc reproduce``: run the paper's scenarios, draw them, write the report.

:func:`reproduce` runs the chosen scenarios of :mod:`famcc.scenarios`, writes one
PNG per scenario (:func:`famcc.plot.scenario_figure`), ``report.md`` (one table
and notes, figures embedded) and ``summary.json`` (the same numbers), and
returns the records. The numbers come from :class:`famcc.SimResult`'s metrics and
:meth:`famcc.scenarios.Scenario.check`; nothing is tuned or re-derived here.

>>> import tempfile, famcc
>>> from famcc import report
>>> with tempfile.TemporaryDirectory() as d:
...     recs = report.reproduce(d, names=["finite-time"], t_end=2.0, figures=False,
...                             progress=None)
>>> recs[0]["guarantees"], recs[0]["settling_time"] < 3.0
('OK', True)
"""

from __future__ import annotations

import json
import math
import sys
import time
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any, TextIO

import numpy as np

__all__ = ["Progress", "measure", "reproduce", "write_report"]

#: The differentiator's start-up window, s: inputs before it are reported apart.
STARTUP = 0.15

#: docs/design.md §6 in a few lines: what differs between the two variants.
VARIANT_DIFFERENCES = (
    ("second-order plant: disturbance `3 sin t + 3 cos 2t` in the authors' code, "
     "`sin t + cos 2t` in the paper"),
    ("third-order plant: x(0) = (1, 0.5, 4) and eps_y = 3 in the code, (1, -0.2, 0.4) and "
     "eps_y = 5 in the paper (the paper's printed x1-dot also omits the factor x2, which makes "
     "the plant uncontrollable; both variants restore it)"),
    ("skew offsets: the code multiplies the whole skewed function by its gain, so in famcc's "
     "terms example 2 uses eps_s = 0.225 (paper 0.15) and example 3's first stage "
     "eps_s = 0.1 (paper 0.2)"),
    ("envelope latch: the code uses rho_0 = max(k0 |s(0)|, eps) (`latch=\"authors\"`), the "
     "paper k0 max(|s(0)|, eps)"),
)


# ---------------------------------------------------------------------------
# progress
# ---------------------------------------------------------------------------

class Progress:
    """A small text progress bar on a stream (stderr by default).

    ``step(label, seconds)`` reports one finished item as
    ``[3/6] ##########---------- rfc ... 0.8 s``. On a terminal the line is
    redrawn in place; elsewhere (logs, pipes) one line per item is printed.
    """

    def __init__(self, total: int, title: str = "", stream: TextIO | None = None,
                 width: int = 20) -> None:
        self.total = max(int(total), 1)
        self.done = 0
        self.stream = sys.stderr if stream is None else stream
        self.width = width
        self.t0 = time.perf_counter()
        isatty = getattr(self.stream, "isatty", None)
        self.tty = bool(isatty()) if callable(isatty) else False
        if title:
            self.stream.write(title + "\n")
            self.stream.flush()

    def step(self, label: str, seconds: float | None = None) -> None:
        self.done += 1
        filled = round(self.width * self.done / self.total)
        bar = "#" * filled + "-" * (self.width - filled)
        digits = len(str(self.total))
        tail = "" if seconds is None else f" ... {seconds:.1f} s"
        line = f"[{self.done:>{digits}}/{self.total}] {bar} {label}{tail}"
        if self.tty:
            end = "\n" if self.done >= self.total else ""
            self.stream.write("\r\033[K" + line + end)
        else:
            self.stream.write(line + "\n")
        self.stream.flush()

    def elapsed(self) -> float:
        return time.perf_counter() - self.t0


# ---------------------------------------------------------------------------
# numbers
# ---------------------------------------------------------------------------

def _intervals(t: np.ndarray, mask: np.ndarray) -> list[list[float]]:
    """Runs of True in ``mask`` as ``[start, end]`` sample times."""
    m = np.asarray(mask, dtype=np.int8)
    if not m.any():
        return []
    edges = np.diff(np.concatenate(([0], m, [0])))
    starts = np.flatnonzero(edges == 1)
    stops = np.flatnonzero(edges == -1)
    last = len(t) - 1
    return [[float(t[int(a)]), float(t[min(int(b), last)])] for a, b in zip(starts, stops)]


def _num(v: Any) -> Any:
    """JSON-friendly float (None for None/NaN)."""
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None


def measure(scenario: Any, result: Any, runtime_s: float | None = None) -> dict[str, Any]:
    """The report's numbers for one run, as a JSON-friendly dict.

    Keys include ``settling_time`` and ``first_entry`` (to ``scenario.eps_z``),
    ``paper_settling_time``, ``bound`` (``T_s + T'`` for a run that never
    saturated, else ``max(T_e, T_s) + T'``) with ``bound_kind``, ``max_abs_xi``,
    ``u_min``/``u_max``, ``saturated_fraction``, ``saturation_episodes``,
    ``largest_expansion``, ``nominal_return_time``, ``violations`` (the list from
    ``scenario.check``) and ``guarantees`` ("OK" or the violations joined).
    """
    eps = scenario.eps_z
    horizon = float(result.t[-1])
    saturated_run = result.saturated_fraction > 0.0
    if saturated_run:
        bound = scenario.recovery_bound(result)
        kind = "max(T_e, T_s) + T'"
    else:
        bound = scenario.bound
        kind = "T_s + T'"
    violations = list(scenario.check(result))
    lo, hi = scenario.u_limits
    negfg = result.neg_f_over_g
    negfg_out: list[list[float]] = []
    negfg_range = None
    if negfg is not None:
        finite = np.isfinite(negfg)
        if finite.any():
            negfg_range = [float(np.min(negfg[finite])), float(np.max(negfg[finite]))]
            negfg_out = _intervals(result.t, finite & ((negfg < lo) | (negfg > hi)))
    ts = result.settling_time(eps)
    late = result.t >= STARTUP
    u_late = result.u[late] if late.any() else result.u
    return {
        "scenario": scenario.name,
        "example": scenario.example,
        "variant": scenario.variant,
        "description": scenario.description,
        "saturated_scenario": bool(scenario.saturated),
        "dt": float(result.dt),
        "t_end": horizon,
        "eps_z": float(eps),
        "settling_time": _num(ts),
        "first_entry": _num(result.first_entry(eps)),
        "paper_settling_time": _num(scenario.paper_settling_time),
        "settle_time_T_s": float(scenario.settle_time),
        "t_prime": float(scenario.t_prime),
        "last_saturation_end_T_e": _num(result.last_saturation_end),
        "bound": float(bound),
        "bound_kind": kind,
        "bound_within_horizon": bool(bound <= horizon),
        "regains_accuracy_claimed": bool(scenario.regains_accuracy),
        "max_abs_xi": _num(result.max_abs_xi),
        "clamp_count": int(result.clamp_count),
        "u_limits": [float(lo), float(hi)],
        "u_min": float(result.u_min),
        "u_max": float(result.u_max),
        "u_range_after_startup": [float(np.min(u_late)), float(np.max(u_late))],
        "u_peak_time": float(result.t[int(np.argmax(np.abs(result.u)))]),
        "u_initial": float(result.u[0]),
        "saturated_fraction": float(result.saturated_fraction),
        "saturation_episodes": [[a, b] for a, b in result.saturation_episodes()],
        "neg_f_over_g_range": negfg_range,
        "neg_f_over_g_outside_limits": negfg_out,
        "largest_expansion": _num(result.largest_expansion),
        "nominal_return_time": _num(result.nominal_return_time),
        "max_abs_z1_last_second": float(
            np.max(np.abs(result.z1[result.t >= horizon - 1.0]))),
        "violations": violations,
        "guarantees": "OK" if not violations else "; ".join(violations),
        "runtime_s": _num(runtime_s),
    }


# ---------------------------------------------------------------------------
# running
# ---------------------------------------------------------------------------

def reproduce(out: str | Path, *, names: Sequence[str] | None = None, variant: str = "code",
              dt: float = 1e-3, t_end: float | None = None, figures: bool = True,
              progress: Any = "stderr") -> list[dict[str, Any]]:
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

    Returns
    -------
    list of dict
        One :func:`measure` record per scenario (plus ``figure``, the PNG's file
        name or None). The guarantees hold when every ``violations`` is empty.
    """
    from famcc import scenarios

    names = list(scenarios.names() if not names else names)
    for name in names:
        if name not in scenarios.names():
            raise ValueError(f"unknown scenario {name!r}; choose from "
                             f"{', '.join(scenarios.names())}")
    if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be a finite number > 0, got {dt!r}")
    if t_end is not None and not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0, got {t_end!r}")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    bar = (Progress(len(names), f"famcc reproduce: {len(names)} scenario(s), variant "
                    f"{variant!r}, dt = {dt:g} s -> {out}")
           if progress == "stderr" else progress)
    t_start = time.perf_counter()
    records = []
    results = {}
    for name in names:
        sc = scenarios.paper(name, variant)
        t0 = time.perf_counter()
        res = sc.run(dt=dt, t_end=t_end)
        sim_s = time.perf_counter() - t0
        rec = measure(sc, res, sim_s)
        rec["figure"] = None
        if figures:
            from famcc import plot

            fig = plot.scenario_figure(sc, res)
            fname = f"{name}.png"
            plot.save(fig, out / fname)
            rec["figure"] = fname
            del fig
        records.append(rec)
        results[name] = res
        if bar is not None:
            status = "OK" if not rec["violations"] else "VIOLATED"
            bar.step(f"{name} ({status})", time.perf_counter() - t0)
    meta = {
        "variant": variant,
        "dt": float(dt),
        "t_end": t_end,
        "runtime_s": time.perf_counter() - t_start,
    }
    write_report(records, out, meta)
    return records


# ---------------------------------------------------------------------------
# writing
# ---------------------------------------------------------------------------

def _f(v: Any, digits: int = 3) -> str:
    if v is None:
        return "-"
    if isinstance(v, float) and not math.isfinite(v):
        return "-"
    return f"{v:.{digits}g}"


def _t(v: Any) -> str:
    """A time in seconds with ms resolution, trailing zeros dropped."""
    if v is None:
        return "-"
    text = f"{v:.3f}".rstrip("0").rstrip(".")
    return text or "0"


def _bound_cell(r: dict) -> str:
    if r["bound_kind"] == "T_s + T'":
        return f"{r['bound']:.3g} (T_s + T')"
    te = r["last_saturation_end_T_e"]
    return f"{r['bound']:.3g} (T_e = {_t(te)})"


def _table(records: Sequence[dict]) -> list[str]:
    head = ("scenario", "settling time [s]", "first entry [s]", "paper [s]", "bound [s]",
            "max \\|xi~\\|", "u range", "saturated", "largest expansion",
            "bounds nominal again [s]", "guarantees")
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] * len(head)) + "|"]
    for r in records:
        ts = r["settling_time"]
        cells = (
            f"{r['scenario']}",
            "never (not within horizon)" if ts is None else _t(ts),
            _t(r["first_entry"]),
            _t(r["paper_settling_time"]),
            _bound_cell(r),
            "-" if r["max_abs_xi"] is None else f"{r['max_abs_xi']:.4f}",
            (f"[{r['u_min']:.3g}, {r['u_max']:.3g}] in [{r['u_limits'][0]:g}, "
             f"{r['u_limits'][1]:g}]"),
            f"{100 * r['saturated_fraction']:.1f} %",
            "-" if r["largest_expansion"] in (None, 1.0) else f"{r['largest_expansion']:.3g}x",
            "-" if r["nominal_return_time"] is None else _t(r["nominal_return_time"]),
            r["guarantees"].replace("|", "\\|"),
        )
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def _count(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")


def _episodes_text(eps: Iterable[Sequence[float]], min_len: float = 0.0) -> str:
    parts = [(f"{a:.2f}-{b:.2f} s" if b - a >= 0.02 else f"{a:.3f}-{b:.3f} s")
             for a, b in eps if b - a >= min_len]
    return ", ".join(parts) if parts else "none"


def _notes(records: Sequence[dict], meta: dict) -> list[str]:
    notes: list[str] = []
    variant = meta["variant"]
    other = "paper" if variant == "code" else "code"
    notes.append(
        f"- **Variant.** These runs use variant `{variant}`"
        + (" (the numbers of the authors' public MATLAB code, the default)" if variant == "code"
           else " (the numbers printed in the paper)")
        + f"; `famcc reproduce --variant {other}` runs the other one. They differ because the "
        "paper and the code disagree (docs/design.md §6): "
        + "; ".join(VARIANT_DIFFERENCES) + ". With the paper's printed disturbance amplitude 1 "
        "the saturated second-order runs barely saturate; with the code's amplitude 3 they do."
    )
    by_name = {r["scenario"]: r for r in records}
    for r in records:
        p = r["paper_settling_time"]
        if p is None:
            continue
        ts = r["settling_time"]
        if ts is None:
            notes.append(f"- **{r['scenario']}.** Never settled within the horizon; the paper "
                         f"reports {p:g} s.")
            continue
        diff = ts - p
        verdict = ("close to" if abs(diff) <= 0.1 else
                   ("faster than" if diff < 0 else "slower than"))
        line = (f"- **{r['scenario']} (example {r['example']}).** Measured settling time "
                f"{_t(ts)} s, {verdict} the paper's {p:g} s ({diff:+.2f} s); the corollary's "
                f"bound is {r['bound']:.3g} s.")
        if r["example"] == 1:
            line += (" The authors' own code, run closed loop, also settles example 1 in about "
                     "1.3 s: the printed 1.9 s is not what the published law produces, and famcc "
                     "matches the mathematics, not the printed number.")
        if r["example"] == 3:
            line += (" The two variants start from different states (x(0) = (1, 0.5, 4) in the "
                     "code, (1, -0.2, 0.4) in the paper) and use different eps_y, so a "
                     "difference of a few tenths of a second is expected.")
        notes.append(line)
    latch, peaking = [], []
    for r in records:
        lo_late, hi_late = r["u_range_after_startup"]
        late_peak = max(abs(lo_late), abs(hi_late))
        peak = max(abs(r["u_min"]), abs(r["u_max"]))
        if r["saturated_scenario"] or peak <= 1.5 * late_peak:
            continue
        if peak <= 1.05 * abs(r["u_initial"]):
            latch.append(f"{r['scenario']} (u(0) = {r['u_initial']:.3g}, |u| <= "
                         f"{late_peak:.3g} after {STARTUP:g} s)")
        else:
            peaking.append(f"{r['scenario']} (|u| up to {peak:.3g} at t = "
                           f"{r['u_peak_time']:.3f} s, <= {late_peak:.3g} after {STARTUP:g} s)")
    if latch:
        notes.append(
            "- **Initial input.** The envelope latches rho_0 = k0 |s(0)|, so xi~(0) = 1/k0 = 0.5 "
            "and u(0) = -k_u Gamma(+-0.5), larger than anything later in: " + "; ".join(latch)
            + ".")
    if peaking:
        notes.append(
            "- **Start-up peaking.** The high-gain differentiator starts from z_hat = (e0, 0, "
            "...) and overshoots for a few time constants (mu = 0.01 s; about 0.1 s for order "
            "3); the law passes that to u: " + "; ".join(peaking) + ". The u panels are zoomed "
            "past it and state the off-scale range.")
    for r in records:
        if not r["saturated_scenario"] and r["saturated_fraction"] > 0:
            notes.append(
                f"- **{r['scenario']}** is an unsaturated scenario (limits "
                f"[{r['u_limits'][0]:g}, {r['u_limits'][1]:g}]) but v left the limits during "
                f"{_episodes_text(r['saturation_episodes'])}: the differentiator's start-up "
                "peaking (docs/design.md §7.1). The check therefore uses the recovery bound "
                f"max(T_e, T_s) + T' = {r['bound']:.3g} s."
            )
    for r in records:
        if not r["saturated_scenario"]:
            continue
        lo, hi = r["u_limits"]
        eps_list = r["saturation_episodes"]
        startup = [e for e in eps_list if e[1] <= 0.1]
        later = [e for e in eps_list if e[1] > 0.1]
        line = (f"- **{r['scenario']}.** u stayed in [{r['u_min']:.3g}, {r['u_max']:.3g}] "
                f"inside [{lo:g}, {hi:g}]; v was outside the limits at "
                f"{100 * r['saturated_fraction']:.1f} % of the samples")
        long_ = [e for e in later if e[1] - e[0] >= 0.02]
        short = [e for e in later if e[1] - e[0] < 0.02]
        if long_:
            line += f", after start-up during {_episodes_text(long_)}"
            if short:
                line += f" (plus {_count(len(short), 'episode')} shorter than 20 ms)"
        elif short:
            line += (f", after start-up only in {_count(len(short), 'episode')} shorter than "
                     f"20 ms ({_episodes_text(short)})")
        if startup:
            line += (f"; {_count(len(startup), 'episode')} before 0.1 s "
                     f"{'is' if len(startup) == 1 else 'are'} the start-up transient (the "
                     "latched first input and the differentiator's peaking)")
        line += "."
        out_fg = [e for e in r["neg_f_over_g_outside_limits"] if e[1] - e[0] >= 0.01]
        if out_fg:
            line += (f" -F/G itself (the input that merely holds z_n constant) is outside the "
                     f"limits during {_episodes_text(out_fg)}: there no admissible input can even "
                     "hold the error still, so that saturation is physical, not a tuning "
                     "artefact; the other saturated stretches are the law's own transient "
                     "demand.")
        elif later:
            line += (" -F/G stays inside the limits; the saturation comes from the law's "
                     "transient demand (the envelope asks for more than the actuator gives).")
        if r["largest_expansion"] not in (None, 1.0):
            ret = r["nominal_return_time"]
            line += (f" The flexible bounds expanded up to {r['largest_expansion']:.3g}x the "
                     "nominal ones and " + (f"were nominal again from t = {_t(ret)} s."
                                            if ret is not None else "had not returned by the end."))
        else:
            line += " The flexible bounds never expanded."
        ts, fe = r["settling_time"], r["first_entry"]
        if ts is None:
            line += (f" |z1| < {r['eps_z']:g} was first reached at {_t(fe)} s but not regained "
                     f"by the end (max |z1| in the last second: "
                     f"{r['max_abs_z1_last_second']:.3g}).")
            if not r["regains_accuracy_claimed"]:
                line += (" This is the documented behaviour of the paper's own numbers "
                         "(docs/design.md §6: with variant \"paper\" the saturated third-order run "
                         "does not regain 0.1 accuracy within 10 s; with the authors' numbers it "
                         "does); it is reported, not tuned away, and the check only tests the "
                         "invariants here.")
        else:
            if fe is not None and ts > fe + r["dt"]:
                line += (f" |z1| < {r['eps_z']:g} was first reached at {_t(fe)} s, lost while "
                         f"saturated, and regained for good at {_t(ts)} s")
            else:
                line += f" |z1| < {r['eps_z']:g} held from {_t(ts)} s on"
            if r["bound_within_horizon"]:
                line += (f", {'within' if ts <= r['bound'] else 'AFTER'} the recovery bound "
                         f"max(T_e, T_s) + T' = {r['bound']:.3g} s.")
            else:
                line += (f"; the recovery bound max(T_e, T_s) + T' = {r['bound']:.3g} s lies "
                         "beyond the horizon, so the settling-time guarantee cannot be tested "
                         "in this run (the invariants still are).")
        notes.append(line)
    if variant == "code" and "rfc-saturated" in by_name:
        notes.append("- With variant `paper` the saturated third-order run (-F/G reaches about "
                     "[-22, 30], far outside [-7, 9]) never regains 0.1 accuracy within 10 s; "
                     "the scenario knows this (`regains_accuracy=False`) and its check then "
                     "tests only |xi~| < 1 and the input limits.")
    notes.append(
        "- **What \"guarantees\" checks** (`Scenario.check`): |xi~| < 1 at every sample without "
        "clamping (Theorems 1-3), u inside the limits, and |z1| < eps_z = 0.1 from T_s + T' "
        "on (runs that never saturate, Corollaries 1-3) or from max(T_e, T_s) + T' on "
        "(saturated runs, when that time lies inside the horizon). The settling time is the "
        "first time after which |z1| < 0.1 holds to the end; \"first entry\" is the first "
        "sample inside the band."
    )
    return notes


def write_report(records: Sequence[dict], out: str | Path, meta: dict) -> tuple[Path, Path]:
    """Writes ``report.md`` and ``summary.json`` into ``out``; returns their paths."""
    import famcc

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    ok = all(not r["violations"] for r in records)
    summary = {
        "famcc_version": famcc.__version__,
        "variant": meta.get("variant"),
        "dt": meta.get("dt"),
        "t_end": meta.get("t_end"),
        "runtime_s": _num(meta.get("runtime_s")),
        "all_guarantees_hold": ok,
        "scenarios": list(records),
    }
    json_path = out / "summary.json"
    json_path.write_text(json.dumps(summary, indent=2) + "\n")

    horizon = meta.get("t_end") or (records[0]["t_end"] if records else 10.0)
    dt = float(meta.get("dt") or (records[0]["dt"] if records else 1e-3))
    lines = [
        "# famcc reproduce: the paper's simulations",
        "",
        f"Variant `{meta.get('variant')}`, sample period dt = {dt:g} s "
        f"({1.0 / dt:g} Hz), horizon {horizon:g} s, famcc {famcc.__version__}"
        + (f", {meta['runtime_s']:.1f} s wall time" if meta.get("runtime_s") else "")
        + ". The same numbers are in [`summary.json`](summary.json); the figures are explained "
        "in `docs/figures.md`.",
        "",
        "**All guarantees hold.**" if ok else "**Some guarantees are VIOLATED** (see the last "
        "column).",
        "",
        "## Results",
        "",
        *_table(records),
        "",
        ("Settling time: first time after which |z1| < 0.1 to the end (`SimResult."
         "settling_time(0.1)`); first entry: first sample with |z1| < 0.1; paper: the time the "
         "paper reports; bound: the corollary's bound T_s + T' for a run that never saturated, "
         "max(T_e, T_s) + T' otherwise (T_e: end of the last saturation episode); u range: "
         "applied input against the limits; saturated: share of samples whose commanded v lay "
         "outside the limits; largest expansion: flexible over nominal bound; bounds nominal "
         "again: first time after the last expansion with the bounds back at nominal."),
        "",
        "## Notes",
        "",
        *_notes(records, meta),
        "",
    ]
    figs = [r for r in records if r.get("figure")]
    if figs:
        lines += ["## Figures", ""]
        for r in figs:
            lines += [
                f"### {r['scenario']} (example {r['example']})",
                "",
                f"{r['description']}. Panels: (a) z and its estimate, (b) z1 after T_s with the "
                "0.1 band, (c)/(d) the constrained offset with nominal (dashed black) and "
                "flexible (solid red) bounds, (e) phase portrait, "
                + ("(f) constrained stage (s2, ds2), (g) u and -F/G, (h) xi~."
                   if r["example"] == 3 else "(f) u and -F/G.")
                + " Shaded: v outside the limits.",
                "",
                f"![{r['scenario']}]({r['figure']})",
                "",
            ]
    lines += [
        "## Regenerate",
        "",
        "```sh",
        f"famcc reproduce --variant {meta.get('variant')} --dt {meta.get('dt'):g}"
        + (f" --t-end {meta['t_end']:g}" if meta.get("t_end") else "")
        + " --out DIR",
        "```",
        "",
    ]
    md_path = out / "report.md"
    md_path.write_text("\n".join(lines))
    return md_path, json_path
