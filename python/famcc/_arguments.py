"""The ``TypeError`` of a wrongly typed argument, named in its message.

The compiled constructors raise :class:`ArgumentTypeError` for an argument of
the wrong type (a ``bool`` where a number is meant, a ``str`` for a float,
...). The extension layer attributes such an error with a note ``while
processing 'dt'``; this class moves that name into the message itself, so
that ``str(error)`` reads ``argument 'dt': must be a real number, not bool``.
"""

from __future__ import annotations

_PREFIX = "while processing '"


class ArgumentTypeError(TypeError):
    """A ``TypeError`` whose message names the argument."""

    def add_note(self, note: str, /) -> None:
        """Moves an argument note into the message; other notes stay notes."""
        if note.startswith(_PREFIX) and note.endswith("'") and len(self.args) == 1:
            name = note[len(_PREFIX) : -1]
            self.args = (f"argument '{name}': {self.args[0]}",)
            return
        super().add_note(note)
