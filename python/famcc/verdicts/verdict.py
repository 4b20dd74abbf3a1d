"""A verdict (held, failed, untested), the start-up window, and the saturation episodes' recovery windows."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from famcc.verdicts.status import STATUSES, Status

#: Seconds at the start treated as the differentiator's start-up transient:
#: the high-gain differentiator starts from ``(e0, 0, ...)`` and peaks for a
#: few time constants (``mu = 0.01`` s; about 0.1 s at order 3). Saturation
#: and expansion before it are not held against the nominal claims.
STARTUP = 0.15


@dataclass(frozen=True)
class Verdict:
    """One claim about one run, and whether the run kept it.

    Attributes
    ----------
    name : str
        Short identifier (``"settling"``, ``"recovery"``, ...).
    claim : str
        The claim in plain words, with its numbers.
    status : Status
        ``"held"``, ``"failed"`` or ``"untested"`` (given as a string or a
        :class:`Status`; kept as a :class:`Status`, which is a string).
    detail : str
        What the run showed (numbers), or why the claim could not be tested.
    known : bool
        A documented failure (see docs/errata.md); it still counts as failed.
    """

    name: str
    claim: str
    status: Status
    detail: str
    known: bool = False

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise ValueError(
                f"status must be one of {tuple(s.value for s in STATUSES)}, got {self.status!r}"
            )
        object.__setattr__(self, "status", Status(self.status))

    @property
    def failed(self) -> bool:
        """True when the run broke the claim."""
        return self.status is Status.FAILED

    def record(self) -> dict[str, Any]:
        """The verdict as plain data (its fields; the status as a string), for JSON."""
        return {
            "name": self.name,
            "claim": self.claim,
            "status": self.status.value,
            "detail": self.detail,
            "known": self.known,
        }

    def text(self) -> str:
        """``"name: status (detail)"``, one line."""
        tail = " (known, docs/errata.md)" if self.known and self.failed else ""
        return f"{self.name}: {self.status.value}{tail}: {self.detail}"


def count(verdicts: Sequence[Verdict]) -> dict[str, int]:
    """Number of verdicts per status, plus ``"tested"`` (held + failed) and ``"total"``."""
    out = {s.value: sum(v.status == s for v in verdicts) for s in STATUSES}
    out["tested"] = out["held"] + out["failed"]
    out["total"] = len(verdicts)
    return out


# ---------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------


def _t(x: float | None) -> str:
    return "never" if x is None else f"{x:.3f} s"


def _expanded(result: Any) -> np.ndarray | None:
    return None if result.expanded is None else np.asarray(result.expanded, dtype=bool)


def _last_bound(result: Any, settle_time: float, t_prime: float) -> tuple[float, float]:
    """``(T_e, max(T_e, T_s) + T')`` for the last saturation episode (T_e = 0 if none)."""
    t_e = result.last_saturation_end or 0.0
    return t_e, max(t_e, settle_time) + t_prime


def recovery_windows(
    result: Any, settle_time: float, t_prime: float
) -> list[tuple[float, float, float]]:
    """``(T_e, due, until)`` for every saturation episode.

    ``due = max(T_e, T_s) + T'`` is the episode's recovery bound and ``until``
    the start of the next episode (or the end of the run, inclusive). A
    window is *due* in this run when ``due <= until`` (and, for the last one,
    ``due`` lies inside the horizon); otherwise saturation came back, or the
    run ended, before the claim fell due.
    """
    episodes = result.saturation_episodes()
    horizon = float(result.t[-1])
    out = []
    for i, (_, t_e) in enumerate(episodes):
        until = episodes[i + 1][0] if i + 1 < len(episodes) else horizon
        saturated_at_end = i + 1 == len(episodes) and bool(result.saturated[-1])
        due = max(t_e, settle_time) + t_prime
        if saturated_at_end:
            due = horizon + t_prime  # the episode never ended in this run
        out.append((t_e, due, until))
    return out


def _is_due(window: tuple[float, float, float], horizon: float) -> bool:
    _, due, until = window
    return due <= until and due <= horizon


# ---------------------------------------------------------------------------
# claims of a run designed without saturation
# ---------------------------------------------------------------------------


def _diverged(result: Any, name: str, claim: str) -> Verdict | None:
    """A failed verdict for a run :func:`famcc.simulate` stopped as diverged."""
    at = getattr(result, "diverged_at", None)
    if at is None:
        return None
    return Verdict(
        name, claim, Status.FAILED, f"the run diverged at {float(at):.3g} s (stopped there)"
    )
