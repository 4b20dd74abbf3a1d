"""The notes in plain words that both reports share: accuracy, saturation, what is unknown."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from famcc.reporting.tables import _label, _t


def _count(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")


def _episodes_text(eps: Iterable[Sequence[float]], min_len: float = 0.0) -> str:
    parts = [
        (f"{a:.2f}-{b:.2f} s" if b - a >= 0.02 else f"{a:.3f}-{b:.3f} s")
        for a, b in eps
        if b - a >= min_len
    ]
    return ", ".join(parts) if parts else "none"


def _saturation_note(r: dict[str, Any]) -> str:
    """Plain words on a run's saturation: episodes, -F/G against the limits, the bounds."""
    lo, hi = r["u_limits"]
    eps_list = r["saturation_episodes"]
    startup = [e for e in eps_list if e[1] <= 0.1]
    later = [e for e in eps_list if e[1] > 0.1]
    line = (
        f"- **{_label(r)}.** u stayed in [{r['u_min']:.3g}, {r['u_max']:.3g}] "
        f"inside [{lo:g}, {hi:g}]; v was outside the limits at "
        f"{100 * r['saturated_fraction']:.1f} % of the samples"
    )
    long_ = [e for e in later if e[1] - e[0] >= 0.02]
    short = [e for e in later if e[1] - e[0] < 0.02]
    if long_:
        line += f", after start-up during {_episodes_text(long_)}"
        if short:
            line += f" (plus {_count(len(short), 'episode')} shorter than 20 ms)"
    elif short:
        line += (
            f", after start-up only in {_count(len(short), 'episode')} shorter than "
            f"20 ms ({_episodes_text(short)})"
        )
    if startup:
        line += (
            f"; {_count(len(startup), 'episode')} before 0.1 s "
            f"{'is' if len(startup) == 1 else 'are'} the start-up transient (the "
            "latched first input and the differentiator's peaking)"
        )
    line += "."
    out_fg = [e for e in r["neg_f_over_g_outside_limits"] if e[1] - e[0] >= 0.01]
    if out_fg:
        line += (
            f" -F/G itself (the input that merely holds z_n constant) is outside the "
            f"limits during {_episodes_text(out_fg)}: there no admissible input can even "
            "hold the error still, so that saturation is physical, not a tuning "
            "artefact; the other saturated stretches are the law's own transient "
            "demand."
        )
    elif later and r["neg_f_over_g_range"] is not None:
        line += (
            " -F/G stays inside the limits; the saturation comes from the law's "
            "transient demand (the envelope asks for more than the actuator gives)."
        )
    elif later:
        line += " -F/G is unknown, so whether any admissible input could hold the error is open."
    if r["largest_expansion"] not in (None, 1.0):
        ret = r["nominal_return_time"]
        line += (
            f" The flexible bounds expanded up to {r['largest_expansion']:.3g}x the "
            "nominal ones and "
            + (
                f"were nominal again from t = {_t(ret)} s."
                if ret is not None
                else "had not returned by the end."
            )
        )
    elif r["largest_expansion"] is not None:
        line += " The flexible bounds never expanded."
    return line


def _accuracy_text(r: dict[str, Any]) -> str:
    """When ``|z1| < eps`` was reached, lost and held (empty without an eps)."""
    eps = r["eps_z"]
    if eps is None:
        return ""
    ts, fe = r["settling_time"], r["first_entry"]
    if ts is None:
        first = "never reached" if fe is None else f"first reached at {_t(fe)} s"
        return (
            f" |z1| < {eps:g} was {first} but was outside the band at the end (max |z1| in "
            f"the last second: {r['max_abs_z1_last_second']:.3g})."
        )
    if fe is not None and ts > fe + r["dt"]:
        return (
            f" |z1| < {eps:g} was first reached at {_t(fe)} s, lost while "
            f"saturated, and held from {_t(ts)} s to the end."
        )
    return f" |z1| < {eps:g} held from {_t(ts)} s to the end."


def _missing_notes(r: dict[str, Any]) -> list[str]:
    """What the run could not compute, and the plant's reason."""
    notes = []
    if r.get("neg_f_over_g_error"):
        notes.append(
            f"- **{_label(r)}: -F/G unknown.** {r['neg_f_over_g_error']}. The u panel "
            "therefore draws no -F/G, and saturation cannot be told physical or not."
        )
    if r.get("derivatives_error"):
        notes.append(
            f"- **{_label(r)}: the true derivatives of z1 unknown.** {r['derivatives_error']}. "
            "Only z1 "
            "and the controller's estimate are drawn."
        )
    return notes
