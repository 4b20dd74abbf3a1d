"""Plant families: N plants of one definition, evaluated at once with NumPy.

A :class:`Family` is a plant whose parameters are arrays: ``rhs(t, x, u, p)``
takes the states of N plants as an ``(n, N)`` array, their held inputs as an
``(N,)`` array and a dict of parameters (each a float or an ``(N,)`` array), and
returns ``dx/dt`` as an ``(n, N)`` array. :func:`famcc.campaigns.campaign`
integrates such families in lockstep for robustness campaigns;
:meth:`Family.plant` builds the ordinary (scalar) plant of one member, which
:func:`famcc.simulate` runs. The ready-made families are
:func:`famcc.plants.family` (:mod:`famcc.plants.catalog`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from famcc._common import Signal
from famcc.plants.base import is_real

__all__ = ["Family", "FamilyPlant", "stack"]

#: ``rhs(t, x, u, p)``: time, states ``(n, N)``, inputs ``(N,)``, parameters.
VectorRHS = Callable[[float, np.ndarray, np.ndarray, Mapping[str, Any]], Any]
#: ``plant(x0, **params)``: the scalar plant of one member.
PlantFactory = Callable[..., Any]


def stack(out: Any, shape: tuple[int, int]) -> np.ndarray:
    """A right-hand side's value as a C-contiguous ``(n, N)`` float64 array
    (entries may be scalars, broadcast over the members)."""
    if isinstance(out, np.ndarray) and out.shape == shape and out.dtype == np.float64:
        return np.ascontiguousarray(out)
    try:
        arr = np.asarray(out, dtype=np.float64)
    except ValueError:  # ragged: some entries are scalars
        arr = np.empty(0)
    if arr.shape == shape:
        return np.ascontiguousarray(arr)
    if len(out) != shape[0]:
        raise ValueError(f"the family's rhs must return {shape[0]} rows, got {len(out)}")
    return np.array([np.broadcast_to(np.asarray(c, dtype=np.float64), shape[1:]) for c in out])


class Family:
    """A plant family evaluated for N members at once.

    Parameters
    ----------
    name : str
        Label for reports.
    order : int
        Number of states (the relative degree for strict-feedback plants).
    rhs : callable
        ``rhs(t, x, u, p)`` with ``t`` a float, ``x`` the states as an ``(n, N)``
        array, ``u`` the held inputs as an ``(N,)`` array and ``p`` a dict of
        parameters (every name of ``params``, each a float or an ``(N,)``
        array); returns ``dx/dt`` as an ``(n, N)`` array or a sequence of ``n``
        arrays. Write it with NumPy ufuncs (``np.sin``), not :mod:`math`.
    params : dict of str to float
        The parameters and their nominal values.
    x0 : sequence of float
        The nominal initial state.
    plant : callable, optional
        ``plant(x0=..., **params)`` returning the scalar plant of one member
        (a :class:`famcc.plants.Plant`). Default: a :class:`FamilyPlant` that
        evaluates ``rhs`` on one member.
    output, input : (name, unit), name, :class:`famcc.Signal` or None
        What ``y = x[0]`` and ``u`` are.
    description : str
        One line for reports.

    Notes
    -----
    Ready-made families (:func:`family`) and their scalar plants compute the
    same operations in the same order, so a campaign's per-case numbers and
    :func:`famcc.simulate` agree sample for sample. A family of your own
    agrees with its default :class:`FamilyPlant` in the same way; with a
    ``plant`` factory of your own, keep the arithmetic identical (floating
    point is not associative). For process pools the family must pickle:
    define ``rhs`` and ``plant`` at module level, not as lambdas.

    Examples
    --------
    A family of damped oscillators ``y'' = b u - c y'`` with dispersed ``b, c``:

    >>> import numpy as np
    >>> def rhs(t, x, u, p):
    ...     return (x[1], p["b"] * u - p["c"] * x[1])
    >>> osc = Family("oscillator", 2, rhs, {"b": 2.0, "c": 0.5}, [1.0, 0.0])
    >>> osc.rhs(0.0, np.array([[1.0, 1.0], [0.0, 2.0]]), np.ones(2), {"c": np.array([0.5, 1.0])})
    array([[0., 2.],
           [2., 0.]])
    >>> osc.plant(b=4.0).rhs(0.0, np.array([1.0, 0.0]), 1.0)
    array([0., 4.])
    """

    def __init__(
        self,
        name: str,
        order: int,
        rhs: VectorRHS,
        params: Mapping[str, float],
        x0: Sequence[float],
        plant: PlantFactory | None = None,
        *,
        output: Any = None,
        input: Any = None,
        description: str = "",
        compiled: Callable[[Mapping[str, Any], int], Any] | None = None,
    ) -> None:
        if not isinstance(order, (int, np.integer)) or isinstance(order, bool) or order < 1:
            raise ValueError(f"order must be an integer >= 1, got {order!r}")
        if not callable(rhs):
            raise ValueError("rhs must be callable as rhs(t, x, u, p)")  # noqa: TRY004
        if plant is not None and not callable(plant):
            raise ValueError("plant must be None or callable as plant(x0=..., **params)")
        x0_arr = np.array(x0, dtype=np.float64).reshape(-1)
        if x0_arr.shape != (order,) or not np.all(np.isfinite(x0_arr)):
            raise ValueError(f"x0 must be {order} finite numbers, got {list(x0)!r}")
        nominal: dict[str, float] = {}
        for key, value in dict(params).items():
            if not isinstance(key, str) or not key.isidentifier():
                raise ValueError(f"parameter names must be identifiers, got {key!r}")
            if not is_real(value) or not math.isfinite(value):
                raise ValueError(f"parameter {key!r} must be a finite number, got {value!r}")
            nominal[key] = float(value)
        self.name = str(name)
        self.order = int(order)
        self._rhs = rhs
        self.params = nominal
        self._x0 = x0_arr
        self._plant = plant
        self.output = Signal.of(output, "y")
        self.input = Signal.of(input, "u")
        self.description = description
        self._compiled = compiled

    @property
    def x0(self) -> np.ndarray:
        """The nominal initial state (a fresh copy)."""
        return self._x0.copy()

    def full_params(self, p: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """The nominal parameters updated with ``p`` (unknown names raise ValueError)."""
        out: dict[str, Any] = dict(self.params)
        for key, value in (p or {}).items():
            if key not in out:
                raise ValueError(
                    f"{self.name} has no parameter {key!r}; its parameters are "
                    f"{', '.join(self.params) or 'none'}"
                )
            out[key] = value
        return out

    def rhs(
        self, t: float, x: np.ndarray, u: np.ndarray, p: Mapping[str, Any] | None = None
    ) -> np.ndarray:
        """``dx/dt`` of every member, shape ``(n, N)``; missing parameters are nominal."""
        return np.asarray(self._rhs(t, x, u, self.full_params(p)), dtype=np.float64)

    def plant(self, x0: Sequence[float] | None = None, **params: float) -> Any:
        """The scalar plant of one member: the nominal one updated with ``params``.

        Parameters
        ----------
        x0 : sequence of float, optional
            Initial state (default: the family's nominal ``x0``).
        **params : float
            Parameter values (default: nominal).
        """
        full = self.full_params(params)
        start = self.x0 if x0 is None else np.array(x0, dtype=np.float64).reshape(-1)
        if self._plant is not None:
            return self._plant(x0=tuple(float(v) for v in start), **full)
        return FamilyPlant(self, start, full)

    def lanes(self, p: Mapping[str, Any], n: int) -> Any:
        """The simulator's plant for ``n`` members with the parameters ``p``.

        A compiled one (the paper's families: ``famcc._core.PaperLanes``), or
        ``("lanes", rhs)`` with ``rhs(t, x, u)`` the vectorised right-hand side
        returning a C-contiguous ``(n_states, n)`` float64 array.
        """
        full = self.full_params(p)
        if self._compiled is not None:
            return self._compiled(full, n)
        vec = {k: np.broadcast_to(np.asarray(v, dtype=np.float64), (n,)) for k, v in full.items()}
        shape, rhs = (self.order, n), self._rhs

        def lanes_rhs(t: float, x: np.ndarray, u: np.ndarray) -> np.ndarray:
            return stack(rhs(t, x, u, vec), shape)

        return ("lanes", lanes_rhs)

    def __repr__(self) -> str:
        p = ", ".join(f"{k}={v:g}" for k, v in self.params.items())
        return f"Family({self.name!r}, order={self.order}, {p})"


class FamilyPlant:
    """One member of a :class:`Family` as an ordinary plant (``rhs(t, x, u)``).

    It evaluates the family's vectorised ``rhs`` on a single member, so it
    computes exactly what a campaign computes for that member. It knows no
    output derivatives or ``-F/G`` (:func:`famcc.simulate` then records only
    ``z1``).

    Examples
    --------
    >>> import numpy as np
    >>> osc = Family("osc", 1, lambda t, x, u, p: (p["a"] * u,), {"a": 2.0}, [0.0])
    >>> FamilyPlant(osc, [0.0], {"a": 3.0}).rhs(0.0, np.zeros(1), 1.0)
    array([3.])
    """

    def __init__(
        self, fam: Family, x0: Sequence[float] | np.ndarray, params: Mapping[str, float]
    ) -> None:
        self.family = fam
        self.order = fam.order
        self._x0 = np.array(x0, dtype=np.float64).reshape(-1)
        if self._x0.shape != (fam.order,):
            raise ValueError(f"x0 must have length {fam.order}, got {self._x0.shape[0]}")
        self.params = {k: float(v) for k, v in fam.full_params(params).items()}
        self._p1 = {k: np.array([v]) for k, v in self.params.items()}
        self.name = fam.name
        self.variant = ""
        self.output = fam.output
        self.input = fam.input

    @property
    def x0(self) -> np.ndarray:
        """Initial state (a fresh copy)."""
        return self._x0.copy()

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        """``dx/dt`` of this member."""
        xs = np.asarray(x, dtype=np.float64).reshape(self.order, 1)
        out = self.family._rhs(t, xs, np.array([float(u)]), self._p1)
        return np.asarray(out, dtype=np.float64).reshape(self.order, -1)[:, 0]

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        """Not known for a generic family member."""
        raise NotImplementedError(
            f"a member of the family {self.family.name!r} reports no output derivatives"
        )

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        """Not known for a generic family member."""
        raise NotImplementedError(
            f"a member of the family {self.family.name!r} reports no gain and drift"
        )

    def __repr__(self) -> str:
        p = ", ".join(f"{k}={v:g}" for k, v in self.params.items())
        return f"{self.name}({p})"
