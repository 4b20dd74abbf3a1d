"""Jets: truncated Taylor series in time, for exact output derivatives of plants.

Private helper of :mod:`famcc.plants` (a user plant built from callables gets
its output derivatives and ``-F/G`` by evaluating the callables on jets). The
controller's own jets live in the Rust core; these only serve the simulator.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any, ClassVar

import numpy as np

__all__ = ["Jet", "as_scalar", "cos", "sin", "tanh"]


# ---------------------------------------------------------------------------


class Jet:
    """Truncated Taylor series ``a(t0 + h) = sum_k c[k] h^k`` (normalised coefficients).

    ``c[k] = a^(k)(t0) / k!``. Arithmetic follows the standard recurrences of
    Griewank & Walther, "Evaluating Derivatives", ch. 13. Jets do not define
    ``__float__`` on purpose: code that silently converts to float (``math.sin``)
    fails loudly instead of dropping derivatives. NumPy ufuncs (``np.sin``,
    ``np.exp``, ...) work through ``__array_ufunc__``.

    Examples
    --------
    >>> t = Jet([0.5, 1.0, 0.0, 0.0])        # the time variable at t0 = 0.5
    >>> y = np.sin(t * t)
    >>> [round(v, 12) for v in y.derivatives()][:2] == [
    ...     round(math.sin(0.25), 12), round(2 * 0.5 * math.cos(0.25), 12)]
    True
    """

    __slots__ = ("c",)

    def __init__(self, coefficients: Sequence[float]) -> None:
        self.c = [float(v) for v in coefficients]

    # -- helpers -----------------------------------------------------------
    @property
    def degree(self) -> int:
        return len(self.c) - 1

    def derivatives(self) -> list[float]:
        """Return ``[a, a', a'', ...]`` (coefficients times ``k!``)."""
        return [v * math.factorial(k) for k, v in enumerate(self.c)]

    def _lift(self, other: Any) -> Jet:
        if isinstance(other, Jet):
            return other
        if isinstance(other, (int, float, np.integer, np.floating)):
            return Jet([float(other)] + [0.0] * self.degree)
        raise TypeError(f"cannot combine a jet with {type(other).__name__}")

    def _binary_degree(self, other: Jet) -> int:
        return min(self.degree, other.degree)

    def __repr__(self) -> str:
        return f"Jet({self.c!r})"

    # -- arithmetic ----------------------------------------------------------
    def __add__(self, other: Any) -> Jet:
        if isinstance(other, Jet):
            d = self._binary_degree(other)
            return Jet([self.c[k] + other.c[k] for k in range(d + 1)])
        o = self._lift(other)
        return Jet([self.c[0] + o.c[0]] + self.c[1:])

    __radd__ = __add__

    def __neg__(self) -> Jet:
        return Jet([-v for v in self.c])

    def __pos__(self) -> Jet:
        return self

    def __sub__(self, other: Any) -> Jet:
        return self + (-self._lift(other))

    def __rsub__(self, other: Any) -> Jet:
        return self._lift(other) + (-self)

    def __mul__(self, other: Any) -> Jet:
        if not isinstance(other, Jet):
            o = float(self._lift(other).c[0])
            return Jet([v * o for v in self.c])
        d = self._binary_degree(other)
        a, b = self.c, other.c
        return Jet([sum(a[i] * b[k - i] for i in range(k + 1)) for k in range(d + 1)])

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> Jet:
        o = self._lift(other)
        d = self._binary_degree(o)
        a, b = self.c, o.c
        if b[0] == 0.0:
            raise ZeroDivisionError("jet division by a jet whose value is zero")
        q: list[float] = []
        for k in range(d + 1):
            acc = a[k] - sum(b[j] * q[k - j] for j in range(1, k + 1))
            q.append(acc / b[0])
        return Jet(q)

    def __rtruediv__(self, other: Any) -> Jet:
        return self._lift(other) / self

    def __pow__(self, exponent: Any) -> Jet:
        if isinstance(exponent, Jet):
            return (exponent * self.log()).exp()
        r = float(exponent)
        if r.is_integer() and 0 <= r <= 16:
            result = Jet([1.0] + [0.0] * self.degree)
            for _ in range(int(r)):
                result = result * self
            return result
        a = self.c
        if a[0] == 0.0:
            raise ZeroDivisionError("jet power with a non-integer exponent at value zero")
        p = [a[0] ** r]
        for k in range(1, len(a)):
            acc = sum(((r + 1.0) * j - k) * a[j] * p[k - j] for j in range(1, k + 1))
            p.append(acc / (k * a[0]))
        return Jet(p)

    def __rpow__(self, base: Any) -> Jet:
        return self._lift(base) ** self

    # -- elementary functions ----------------------------------------------
    def _integrate(self, f0: float, w: Jet) -> Jet:
        """Jet of ``f`` with ``f(t0) = f0`` and ``f' = a' * w``."""
        a, out = self.c, [f0]
        for k in range(1, len(a)):
            out.append(sum(j * a[j] * w.c[k - j] for j in range(1, k + 1)) / k)
        return Jet(out)

    def sin_cos(self) -> tuple[Jet, Jet]:
        a = self.c
        s, c = [math.sin(a[0])], [math.cos(a[0])]
        for k in range(1, len(a)):
            s.append(sum(j * a[j] * c[k - j] for j in range(1, k + 1)) / k)
            c.append(-sum(j * a[j] * s[k - j] for j in range(1, k + 1)) / k)
        return Jet(s), Jet(c)

    def sin(self) -> Jet:
        return self.sin_cos()[0]

    def cos(self) -> Jet:
        return self.sin_cos()[1]

    def exp(self) -> Jet:
        a, e = self.c, [math.exp(self.c[0])]
        for k in range(1, len(a)):
            e.append(sum(j * a[j] * e[k - j] for j in range(1, k + 1)) / k)
        return Jet(e)

    def log(self) -> Jet:
        a = self.c
        if a[0] <= 0.0:
            raise ValueError("jet log of a non-positive value")
        out = [math.log(a[0])]
        for k in range(1, len(a)):
            acc = a[k] - sum(j * out[j] * a[k - j] for j in range(1, k)) / k
            out.append(acc / a[0])
        return Jet(out)

    def sqrt(self) -> Jet:
        return self**0.5

    def tanh(self) -> Jet:
        a = self.c
        t = [math.tanh(a[0])]
        w = [1.0 - t[0] * t[0]]  # w = 1 - tanh^2, built alongside
        for k in range(1, len(a)):
            t.append(sum(j * a[j] * w[k - j] for j in range(1, k + 1)) / k)
            w.append(-sum(t[i] * t[k - i] for i in range(k + 1)))
        return Jet(t)

    def arctan(self) -> Jet:
        return self._integrate(math.atan(self.c[0]), 1.0 / (1.0 + self * self))

    # -- NumPy interoperability --------------------------------------------
    _UFUNCS: ClassVar[dict[str, Callable[..., Any]]] = {
        "add": lambda a, b: a + b,
        "subtract": lambda a, b: a - b,
        "multiply": lambda a, b: a * b,
        "true_divide": lambda a, b: a / b,
        "divide": lambda a, b: a / b,
        "power": lambda a, b: a**b,
        "negative": lambda a: -a,
        "positive": lambda a: a,
        "square": lambda a: a * a,
        "sin": lambda a: a.sin(),
        "cos": lambda a: a.cos(),
        "exp": lambda a: a.exp(),
        "log": lambda a: a.log(),
        "sqrt": lambda a: a.sqrt(),
        "tanh": lambda a: a.tanh(),
        "arctan": lambda a: a.arctan(),
    }

    def __array_ufunc__(self, ufunc: Any, method: str, *inputs: Any, **kwargs: Any) -> Any:
        fn = self._UFUNCS.get(ufunc.__name__)
        if method != "__call__" or fn is None or kwargs:
            return NotImplemented
        args = [self._lift(v) if not isinstance(v, Jet) else v for v in inputs]
        return fn(*args)


def sin(a: Any) -> Any:
    return a.sin() if isinstance(a, Jet) else math.sin(a)


def cos(a: Any) -> Any:
    return a.cos() if isinstance(a, Jet) else math.cos(a)


def tanh(a: Any) -> Any:
    return a.tanh() if isinstance(a, Jet) else math.tanh(a)


def as_scalar(value: Any) -> Any:
    """Unwrap 0-d arrays and NumPy scalars; keep jets."""
    if isinstance(value, Jet):
        return value
    if isinstance(value, np.ndarray) and value.shape == ():
        return as_scalar(value.item())
    return float(value)
