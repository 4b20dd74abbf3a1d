"""A plant written once: :class:`Model`, its rows in strict-feedback form
evaluated on floats, on NumPy arrays (one column per member of a family) and on
jets (exact derivatives), and :class:`PhysicalPlant`, one member of a model.

A model's ``derive(p)`` turns its parameters (floats, or arrays of the
members' values) into the constants its rows use, once; ``terms(t, x, c)``
returns the rows ``(g_i, f_i)`` at time ``t`` and state ``x`` with those
constants. Written with operators and NumPy ufuncs (no ``math``, no ``if`` on
values), the same two functions serve the scalar simulator, the lockstep
simulator of families and the Taylor method of the exact derivatives, so a
family cannot compute another plant than its members.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from famcc.plants.base import is_real
from famcc.plants.strict import StrictForm

__all__ = ["Model", "PhysicalPlant"]

Terms = Callable[[Any, Any, Mapping[str, Any]], Sequence[tuple[Any, Any]]]


@dataclass(frozen=True)
class Model:
    """A strict-feedback plant's dynamics and data, written once.

    Attributes
    ----------
    name : str
        The plant's name (``"dc-motor"``).
    order : int
        Relative degree = number of states.
    params : dict of str to float
        Parameters and their nominal values.
    x0 : tuple of float
        Nominal initial state.
    derive : callable
        ``derive(p) -> dict``: the constants of the rows from the parameters
        (floats or arrays, elementwise).
    terms : callable
        ``terms(t, x, c) -> [(g_1, f_1), ..., (g_n, f_n)]``.
    output, input : (str, str)
        Name and unit of the output ``y = x[0]`` and of the input.
    gain, hold : callable
        ``gain(p)``: the nominal input gain ``G`` of ``y^(n) = G u + F`` (the
        largest over the operating range); ``hold(p)``: a bound on ``|F/G|`` at
        rest, the input that holds the largest static load.
    positive : tuple of str
        Parameters that must be > 0.
    description : str
        One line for reports.
    """

    name: str
    order: int
    params: dict[str, float]
    x0: tuple[float, ...]
    derive: Callable[[Mapping[str, Any]], dict[str, Any]]
    terms: Terms
    output: tuple[str, str]
    input: tuple[str, str]
    gain: Callable[[Mapping[str, Any]], float]
    hold: Callable[[Mapping[str, Any]], float]
    positive: tuple[str, ...] = ()
    description: str = ""

    def check(self, p: Mapping[str, Any]) -> dict[str, Any]:
        """The nominal parameters updated with ``p``, checked (ValueError names the bad one)."""
        out: dict[str, Any] = dict(self.params)
        for key, value in p.items():
            if key not in out:
                raise ValueError(
                    f"{self.name} has no parameter {key!r}; its parameters are "
                    f"{', '.join(self.params)}"
                )
            out[key] = value
        for key in self.positive:
            if not np.all(np.asarray(out[key]) > 0):
                raise ValueError(f"{key} must be > 0, got {out[key]!r}")
        return out

    def rates(self, t: Any, x: Any, u: Any, c: Mapping[str, Any]) -> list[Any]:
        """``x_i' = g_i x_{i+1} + f_i`` (``x_{n+1} = u``) with the constants ``c``."""
        n = self.order
        return [
            g * (x[i + 1] if i + 1 < n else u) + f for i, (g, f) in enumerate(self.terms(t, x, c))
        ]

    def rhs(self, t: Any, x: Any, u: Any, p: Mapping[str, Any]) -> list[Any]:
        """The right-hand side with the parameters ``p`` (floats or arrays)."""
        return self.rates(t, x, u, self.derive(self.check(p)))


class PhysicalPlant(StrictForm):
    """One member of a :class:`Model`: the model at one set of parameters.

    Attributes
    ----------
    model : Model
    params : dict
        The physical parameters.
    output, input : famcc.Signal
        Name and unit of the output ``y = x[0]`` and of the input ``u``.
    gain : float
        The nominal input gain ``G`` of ``y^(n) = G u + F`` (units of
        ``y/s^n`` per input unit); the largest value over the operating range.
    """

    def __init__(self, model: Model, x0: Sequence[float] | None = None, **params: float) -> None:
        full = model.check(params)
        for key, value in full.items():
            if not (is_real(value) and math.isfinite(value)):
                raise ValueError(f"{key} must be a finite number, got {value!r}")
        start = model.x0 if x0 is None else x0
        super().__init__(
            model.order, start, name=model.name, output=model.output, input=model.input
        )
        if self._x0.shape != (model.order,):
            raise ValueError(f"x0 must have length {model.order}, got {self._x0.shape[0]}")
        self.model = model
        self.params = {k: float(v) for k, v in full.items()}
        self._c = model.derive(self.params)
        self.gain = float(model.gain(self.params))
        self._hold = float(model.hold(self.params))

    def rows(self, t: Any, x: Any) -> Sequence[tuple[Any, Any]]:
        return self.model.terms(t, x, self._c)

    def hold_input(self) -> float:
        """A bound on ``|F/G|`` at rest: the input that holds the largest static load."""
        return self._hold

    def rhs_fast(self, t: float, x: Sequence[float], u: float) -> tuple[float, ...]:
        """:meth:`rhs` on plain floats (the simulator's fast path)."""
        return tuple(float(r) for r in self.model.rates(t, x, u, self._c))

    def __repr__(self) -> str:
        p = ", ".join(f"{k}={v:g}" for k, v in self.params.items())
        return f"{self.name}({p})"
