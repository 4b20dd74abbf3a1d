"""Small shared pieces: named signals with units, and famcc's warning classes.

:class:`FamccWarning` and :class:`DesignWarning` are the compiled extension's
(``famcc._core``, which emits them without importing this module);
:class:`DefaultReferenceWarning` is defined here.

>>> angle = Signal.of(("angle", "rad"), "y")
>>> angle.name, angle.unit, angle.derivative_unit(2)
('angle', 'rad', 'rad/s²')
>>> Signal.of(None, "u"), Signal.of("torque", "u").bracket()
(Signal(name='u', unit=None), '')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from famcc._core import DesignWarning, FamccWarning

__all__ = ["DefaultReferenceWarning", "DesignWarning", "FamccWarning", "Signal"]

_SUPERSCRIPTS = {2: "²", 3: "³", 4: "⁴", 5: "⁵", 6: "⁶", 7: "⁷", 8: "⁸", 9: "⁹"}


class DefaultReferenceWarning(FamccWarning, FutureWarning):
    """:func:`famcc.simulate` was called without a reference.

    It then tracks the paper's ``y_d = sin t``, which is surprising for a
    regulator; pass ``reference=`` explicitly (``famcc.Sine()`` keeps the old
    behaviour, ``famcc.Constant(c)`` regulates to the set point ``c``).
    """


@dataclass(frozen=True)
class Signal:
    """A plant's output or input: a name and, when known, a unit.

    Parameters
    ----------
    name : str
        What the signal is, in the user's words (``"angle"``, ``"voltage"``).
    unit : str or None
        Its unit (``"rad"``, ``"V"``); None when not given. Figures and reports
        then print no unit rather than an invented one.

    Examples
    --------
    >>> v = Signal("speed", "m/s")
    >>> v.derivative_unit(1), v.bracket(1)
    ('(m/s)/s', ' [(m/s)/s]')
    """

    name: str
    unit: str | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise ValueError(f"a signal's name must be a non-empty string, got {self.name!r}")
        if self.unit is not None and not isinstance(self.unit, str):
            raise ValueError(f"a signal's unit must be a string or None, got {self.unit!r}")

    @classmethod
    def of(cls, value: Any, default_name: str) -> Signal:
        """A :class:`Signal` from a Signal, a name, a ``(name, unit)`` pair or None.

        Raises
        ------
        ValueError
            For anything else (the message shows what was given).
        """
        if value is None:
            return cls(default_name)
        if isinstance(value, Signal):
            return value
        if isinstance(value, str):
            return cls(value)
        if isinstance(value, (tuple, list)) and len(value) == 2:
            name, unit = value
            return cls(str(name), None if unit is None else str(unit))
        raise ValueError(
            f"expected a name, a (name, unit) pair or None, got {value!r} "
            '(for example ("angle", "rad"))'
        )

    def derivative_unit(self, k: int) -> str | None:
        """The unit of the ``k``-th time derivative (None when the unit is unknown)."""
        if self.unit is None:
            return None
        if k == 0:
            return self.unit
        simple = not any(c in self.unit for c in "/* ")
        base = self.unit if simple else f"({self.unit})"
        power = "" if k == 1 else _SUPERSCRIPTS.get(k, f"^{k}")
        return f"{base}/s{power}"

    def bracket(self, k: int = 0) -> str:
        """``" [unit]"`` of the ``k``-th derivative, or ``""`` when the unit is unknown."""
        unit = self.derivative_unit(k)
        return "" if unit is None else f" [{unit}]"
