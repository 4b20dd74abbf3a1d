"""The one text progress bar (``famcc.reporting.Progress``).

Used by ``famcc reproduce``, ``famcc compare``, ``famcc.tune`` and the campaigns.
"""

from __future__ import annotations

import sys
import time
from typing import TextIO


class Progress:
    """A small text progress bar on a stream (stderr by default).

    ``step(label, seconds)`` reports one finished item as
    ``[3/6] ##########---------- rfc ... 0.8 s``. On a terminal the line is
    redrawn in place; elsewhere (logs, pipes) one line per item is printed.
    """

    def __init__(
        self, total: int, title: str = "", stream: TextIO | None = None, width: int = 20
    ) -> None:
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
