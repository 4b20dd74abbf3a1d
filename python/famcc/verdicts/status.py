"""The one encoding of a judgement: held, failed or untested, and how several combine.

Every judge of the package speaks it: a :class:`famcc.verdicts.Verdict`'s
``status``, a campaign's per-case columns (as :attr:`Status.code`, int8),
:class:`famcc.tuning.Assessment`'s requirements and the sweep's records.
A :class:`Status` is a ``str`` (``Status.HELD == "held"``), so reports and
JSON read as before.

>>> from famcc.verdicts import Status, combine
>>> combine([Status.HELD, "untested"]), combine(["held", "failed", "untested"])
(<Status.UNTESTED: 'untested'>, <Status.FAILED: 'failed'>)
>>> Status.FAILED.code, Status.from_code(-1), Status.FAILED.shown
(0, <Status.UNTESTED: 'untested'>, 'FAILED')
"""

from __future__ import annotations

import enum
from collections.abc import Iterable

import numpy as np


class Status(enum.StrEnum):
    """Whether a run kept a claim: ``"held"``, ``"failed"`` or ``"untested"``."""

    HELD = "held"
    FAILED = "failed"
    UNTESTED = "untested"

    @property
    def code(self) -> int:
        """The status as an integer (1 held, 0 failed, -1 untested): a campaign's column."""
        return _CODES[self]

    @classmethod
    def from_code(cls, code: int) -> Status:
        """The status of an integer code (1, 0 or -1)."""
        for status, c in _CODES.items():
            if c == int(code):
                return status
        raise ValueError(f"a status code is 1 (held), 0 (failed) or -1 (untested), got {code!r}")

    @property
    def shown(self) -> str:
        """The status as reports print it: a failure in capitals, so it stands out."""
        return self.value.upper() if self is Status.FAILED else self.value


_CODES = {Status.HELD: 1, Status.FAILED: 0, Status.UNTESTED: -1}

#: The three statuses, in the order reports list them.
STATUSES: tuple[Status, ...] = tuple(Status)


def combine(statuses: Iterable[Status | str]) -> Status:
    """Several claims together: failed when any failed, else untested when any
    was untested, else held (also for none)."""
    found = {Status(s) for s in statuses}
    if Status.FAILED in found:
        return Status.FAILED
    return Status.UNTESTED if Status.UNTESTED in found else Status.HELD


def combine_codes(codes: np.ndarray) -> np.ndarray:
    """:func:`combine` over axis 0 of an array of :attr:`Status.code` values
    (claims by cases): the combined code of each case, int8."""
    c = np.asarray(codes)
    failed = (c == Status.FAILED.code).any(axis=0)
    untested = (c == Status.UNTESTED.code).any(axis=0)
    held = np.full(c.shape[1:], Status.HELD.code)
    out = np.where(failed, Status.FAILED.code, np.where(untested, Status.UNTESTED.code, held))
    return out.astype(np.int8)
