"""Interoperability with other control libraries.

:func:`to_nlsys` wraps a famcc controller as a discrete-time nonlinear
input/output system of the `python-control <https://python-control.org>`_
library (``control.NonlinearIOSystem``), so it can be interconnected with
plants, summing junctions and other blocks and simulated with
``control.input_output_response``.

python-control is an optional dependency (``pip install control``); it is
imported only when :func:`to_nlsys` is called.

Examples
--------
>>> import numpy as np
>>> import famcc
>>> from famcc.interop import to_nlsys
>>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
...                         constraint="lateral", eps=0.1, k_u=5.0)
>>> import control                                            # doctest: +SKIP
>>> sys = to_nlsys(ctrl)                                      # doctest: +SKIP
>>> t = np.arange(5) * ctrl.dt
>>> resp = control.input_output_response(
...     sys, t, -np.ones(5), initial_state=ctrl.state())     # doctest: +SKIP
>>> resp.outputs.tolist() == [ctrl.step(-1.0) for _ in t]    # doctest: +SKIP
True
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from famcc._core import STATE_FIELDS

if TYPE_CHECKING:
    from famcc._core import Controller

__all__ = ["state_labels", "to_nlsys"]

#: Names of the leading entries of ``Controller.state()``; the estimate
#: ``z_hat[0..n-1]`` follows.
_STATE_HEAD = STATE_FIELDS


def _import_control() -> Any:
    try:
        import control  # type: ignore[import-untyped, unused-ignore]
    except ImportError as exc:  # pragma: no cover - exercised with a stubbed import
        raise ImportError(
            "famcc.interop.to_nlsys needs the optional dependency python-control: "
            "install it with `pip install control` (or `pip install famcc[test]`)"
        ) from exc
    return control


def state_labels(controller: Controller, prefix: str = "") -> list[str]:
    """Labels of the entries of ``controller.state()`` (``prefix`` prepended).

    >>> import famcc
    >>> c = famcc.Controller(2, 1e-3, famcc.Linear(1.0), eps=0.1, k_u=1.0)
    >>> state_labels(c)[-4:]
    ['filtered', 'lhat', 'z_hat[0]', 'z_hat[1]']
    """
    names = list(_STATE_HEAD) + [f"z_hat[{i}]" for i in range(controller.order)]
    return [prefix + s for s in names]


def _as_names(value: Sequence[str] | str, what: str) -> list[str]:
    names = [value] if isinstance(value, str) else list(value)
    if len(names) != 1 or not all(isinstance(s, str) for s in names):
        raise ValueError(
            f"{what} must name exactly one signal (a controller is SISO), got {value!r}"
        )
    return names


def to_nlsys(
    controller: Controller,
    *,
    name: str = "famcc",
    inputs: Sequence[str] | str = ("e",),
    outputs: Sequence[str] | str = ("v",),
) -> Any:
    """The controller as a discrete-time ``control.NonlinearIOSystem``.

    Parameters
    ----------
    controller : famcc.Controller
        The controller; it is copied, so later use of ``controller`` does not
        affect the system. Its configuration (order, laws, ``dt``, ...) is fixed
        in the system; its *state* is the system's state.
    name : str
        System name (python-control uses it to label signals).
    inputs, outputs : sequence of one str
        Names of the input (the output error ``e = y - y_d``) and the output
        (the control ``v``).

    Returns
    -------
    control.NonlinearIOSystem
        Sampling period ``dt = controller.dt``, ``len(STATE_FIELDS) + order`` states (the
        vector of :meth:`famcc.Controller.state`, labelled by
        :func:`state_labels`), one input, one output. The update and output
        functions are pure functions of ``(t, x, u, params)``: each one copies
        the controller, loads ``x`` with ``set_state`` and takes one step with
        ``e = u[0]``; the output function returns ``v[k]`` (computed from
        ``x[k]`` and ``u[k]``, exactly what ``controller.step(e[k])`` returns)
        and the update function the next state ``x[k+1]``. ``t`` and ``params``
        are ignored: the controller's clock is part of its state.

    Notes
    -----
    The initial state is *not* zero: pass ``initial_state=controller.state()``
    (or, for an interconnection, that vector at the controller's place in the
    concatenated state) to ``control.input_output_response``.

    The controller's output at a sample depends on the error at that sample
    only through the first step (the differentiator's estimate is built from
    earlier samples), so closed loops with plants without feedthrough have no
    algebraic loop.

    Raises
    ------
    ImportError
        When python-control is not installed.
    ValueError
        When ``inputs`` or ``outputs`` does not name exactly one signal.
    """
    control = _import_control()
    template = copy.copy(controller)
    in_names = _as_names(inputs, "inputs")
    out_names = _as_names(outputs, "outputs")
    n_states = len(_STATE_HEAD) + template.order

    # One-entry memo: python-control calls the output and the update function
    # with the same (x, u) at every sample; both need the same step.
    memo_key: bytes | None = None
    memo_value: tuple[float, np.ndarray] = (0.0, np.empty(0))

    def step(x: Any, u: Any) -> tuple[float, np.ndarray]:
        nonlocal memo_key, memo_value
        xv = np.ascontiguousarray(np.asarray(x, dtype=np.float64).reshape(-1))
        uv = np.asarray(u, dtype=np.float64).reshape(-1)
        if xv.shape != (n_states,):
            raise ValueError(f"{name}: the state must have {n_states} entries, got {xv.size}")
        if uv.shape != (1,):
            raise ValueError(f"{name}: the input must have 1 entry, got {uv.size}")
        key = xv.tobytes() + uv.tobytes()
        if memo_key == key:
            return memo_value
        work = copy.copy(template)
        try:
            work.set_state(xv)
        except ValueError as exc:
            raise ValueError(
                f"{name}: {exc} (a famcc controller's initial state is not the zero vector: "
                "pass initial_state=controller.state() to control.input_output_response)"
            ) from exc
        v = work.step(float(uv[0]))
        memo_key, memo_value = key, (v, work.state())
        return memo_value

    def updfcn(t: float, x: Any, u: Any, params: Any) -> np.ndarray:
        return step(x, u)[1].copy()

    def outfcn(t: float, x: Any, u: Any, params: Any) -> np.ndarray:
        return np.array([step(x, u)[0]])

    return control.nlsys(
        updfcn,
        outfcn,
        name=name,
        inputs=in_names,
        outputs=out_names,
        states=state_labels(template),
        dt=template.dt,
    )
