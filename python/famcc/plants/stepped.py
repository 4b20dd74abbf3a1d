"""Plants that advance themselves: a simulator with its own integrator, or a
black box you can only reset and step.

:func:`famcc.simulate` integrates a :class:`~famcc.plants.Plant`'s
``rhs(t, x, u)`` with RK4. A plant that cannot give a right-hand side offers
``advance(t, x, u, dt) -> x_next`` instead: the states at ``t + dt`` when the
input ``u`` is held from ``t`` (the sample-and-hold loop calls it once per
sample period and never asks for ``rhs``). Two forms:

- :class:`Stepped`, the base class: the loop keeps the state vector (so runs
  restart from ``x0``, and many candidates or lanes can share one plant);
  :class:`famcc.plants.MuJoCo` is one.
- :class:`BlackBox`, an adapter for an object that keeps its own state and
  offers ``reset() -> y0`` and ``step(u, dt) -> y`` (a Python class, an FMU or
  a Simulink export wrapped that way). The loop's state is the output alone;
  each run begins with ``reset()``.

Examples
--------
>>> import famcc
>>> class Cart:                              # keeps its own state
...     def reset(self):
...         self.p, self.v = 1.0, 0.0
...         return self.p
...     def step(self, u, dt):
...         self.p += self.v * dt + 0.5 * u * dt * dt
...         self.v += u * dt
...         return self.p
>>> plant = famcc.plants.BlackBox(Cart(), order=2, name="cart")
>>> ctrl = famcc.design(2, 1e-3, u_limits=(-5, 5), eps=0.02, settle_time=3.0,
...                     hold_input=4.5, gain=1.0).controller()
>>> res = famcc.simulate(plant, ctrl, 4.0, reference=famcc.Constant(0.0), u_limits=(-5, 5))
>>> bool(abs(res.z[-1, 0]) < 0.02)
True
"""

from __future__ import annotations

from typing import Any

import numpy as np

from famcc.plants.base import Plant, is_real

__all__ = ["BlackBox", "Stepped"]


class Stepped(Plant):
    """Base class of plants that advance themselves over a sample period.

    Subclasses implement :meth:`advance`; ``x0`` may hold more states than the
    order (the output is ``x[0]``). :meth:`output_derivatives` and
    :meth:`gain_and_drift` are optional, as for every :class:`Plant`.

    Examples
    --------
    >>> class Exact(Stepped):                # y'' = u, advanced exactly
    ...     def advance(self, t, x, u, dt):
    ...         return np.array([x[0] + x[1] * dt + 0.5 * u * dt * dt, x[1] + u * dt])
    >>> Exact(2, [0.0, 1.0]).advance(0.0, np.array([0.0, 1.0]), 2.0, 0.5)
    array([0.75, 2.  ])
    """

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        raise NotImplementedError(
            f"{type(self).__name__} advances itself (advance(t, x, u, dt)); it has no rhs"
        )

    def advance(self, t: float, x: np.ndarray, u: Any, dt: float) -> np.ndarray:
        """The states at ``t + dt`` from ``x`` at ``t`` with ``u`` held.

        ``x`` has shape ``(states,)`` and ``u`` is a float for one lane; for
        several lanes ``x`` is ``(states, lanes)`` and ``u`` is ``(lanes,)``.
        """
        raise NotImplementedError(f"{type(self).__name__} does not define advance")


class BlackBox(Stepped):
    """A plant that keeps its own state: ``reset() -> y0``, ``step(u, dt) -> y``.

    Parameters
    ----------
    box : object
        ``reset()`` puts it at its initial state and returns the output there;
        ``step(u, dt)`` holds the input ``u`` for ``dt`` seconds and returns
        the output at the end. Both outputs are real numbers.
    order : int
        The relative degree from ``u`` to ``y`` (the controller's order).
    name, output, input
        As for :class:`Plant`.

    Notes
    -----
    The loop's state is ``[y]``: reading ``x0`` calls ``reset()``, so every
    :func:`famcc.simulate` (and every run of :func:`famcc.tune`) starts from the
    box's initial state. One box runs one lane at a time; it has no exact
    output derivatives, so a run's ``z`` holds the error only.
    """

    def __init__(
        self,
        box: Any,
        order: int,
        *,
        name: str = "black box",
        output: Any = None,
        input: Any = None,
    ) -> None:
        for method in ("reset", "step"):
            if not callable(getattr(box, method, None)):
                raise TypeError(
                    f"box must have a {method}() method (reset() -> y0, step(u, dt) -> y); "
                    f"{type(box).__name__} has none"
                )
        self.box = box
        super().__init__(
            order, [self._output(box.reset(), "reset()")], name, output=output, input=input
        )

    @staticmethod
    def _output(y: Any, where: str) -> float:
        value = y.item() if isinstance(y, np.ndarray) and y.size == 1 else y
        if not is_real(value) or not np.isfinite(value):
            raise ValueError(f"the box's {where} must return a finite real output, got {y!r}")
        return float(value)

    @property
    def x0(self) -> np.ndarray:
        """``[y0]`` from a fresh ``reset()`` (each run starts from there)."""
        return np.array([self._output(self.box.reset(), "reset()")])

    def advance(self, t: float, x: np.ndarray, u: Any, dt: float) -> np.ndarray:
        if np.ndim(u) != 0:
            raise ValueError("a BlackBox holds one state and runs one lane; build one box per lane")
        y = self.box.step(float(u), float(dt))
        value = y.item() if isinstance(y, np.ndarray) and y.size == 1 else y
        if not is_real(value):
            raise ValueError(f"the box's step(u, dt) must return a real output, got {y!r}")
        return np.array([float(value)])


def lanes_of(x: np.ndarray, u: Any) -> tuple[np.ndarray, np.ndarray, bool]:
    """``x`` as ``(states, lanes)`` and ``u`` as ``(lanes,)``, and whether the
    call was for one lane (``x`` one-dimensional)."""
    x = np.asarray(x, dtype=np.float64)
    one = x.ndim == 1
    xs = x[:, None] if one else x
    us = np.broadcast_to(np.asarray(u, dtype=np.float64).reshape(-1), (xs.shape[1],))
    return xs, us, one
