"""The one sample-and-hold loop, seen from Python: ``famcc._core.Lockstep``
(famcc-sim) and the arrays it records.

:func:`famcc.simulate` (one lane, one channel), :func:`famcc.joints.simulate_joints`
(one lane, a channel per joint) and campaigns (a lane per case) all run
through :func:`start` and :meth:`Engine.block`. The semantics are famcc-sim's
(docs/architecture.md): at ``t_k = k dt`` each controller gets ``e_k = y(t_k)
- y_d(t_k)`` plus noise and returns ``v_k``, told the input applied at the
previous sample; ``u_k = clip(v_k)`` plus the disturbance is held while the
plant is integrated with ``substeps`` RK4 steps; a lane stops at a sample with
``|e| > diverge_at``, a non-finite output, or after an integration that left
the state non-finite or outside ``state_bound``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from famcc import _core

__all__ = ["Block", "Engine", "plant_of", "start"]

#: Values per recorded column and block: long runs and wide campaigns are
#: recorded in blocks of at most this many (samples x channels x lanes).
BLOCK_VALUES = 1 << 20


def plant_of(plant: Any) -> Any:
    """What the loop integrates for a scalar plant: its compiled lanes when it
    has them (the paper's plants), its ``advance(t, x, u, dt)`` when it advances
    itself (:class:`famcc.plants.Stepped`), else its ``rhs_fast`` on lists, else
    its ``rhs`` on NumPy vectors."""
    compiled = getattr(plant, "compiled", None)
    if callable(compiled):
        return compiled()
    advance = getattr(plant, "advance", None)
    if callable(advance):
        return ("step", advance)
    fast = getattr(plant, "rhs_fast", None)
    if callable(fast):
        return ("list", fast)
    return ("array", plant.rhs)


@dataclass
class Block:
    """The samples of one block; arrays are ``(rows, channels, lanes)`` unless said.

    Attributes
    ----------
    rows : int
    e, e_measured, v, u, d : ndarray
        True error, measured error, output, applied input, disturbance (NaN
        where a lane had stopped).
    x : ndarray or None
        ``(rows, states, lanes)``.
    diag : dict of str to ndarray
        The diagnostics columns; ``"z_hat"`` is ``(rows, channels, lanes, n)``.
    plant_error : BaseException or None
        The exception the plant's right-hand side raised (the block ends there).
    """

    rows: int
    e: np.ndarray
    e_measured: np.ndarray
    v: np.ndarray
    u: np.ndarray
    d: np.ndarray
    x: np.ndarray | None
    diag: dict[str, np.ndarray]
    plant_error: BaseException | None


class Engine:
    """A run in progress: the compiled loop and its layout."""

    def __init__(self, sim: Any, channels: int, lanes: int, states: int, keep_states: bool) -> None:
        self.sim, self.channels, self.lanes, self.states = sim, channels, lanes, states
        self.keep_states = keep_states

    @property
    def block_rows(self) -> int:
        """Samples per block."""
        return max(1, BLOCK_VALUES // (self.channels * max(self.lanes, self.states)))

    def block(
        self, yd: np.ndarray, noise: np.ndarray | None = None, disturbance: np.ndarray | None = None
    ) -> Block:
        """Runs the next samples: the reference ``yd`` and the optional noise and
        disturbance as ``(rows,)``, ``(rows, channels)`` or ``(rows, channels, lanes)``."""
        shape = (-1, self.channels, self.lanes)

        def flat(a: np.ndarray | None) -> np.ndarray | None:
            # (rows,) per sample, (rows, channels) per channel, (rows, channels, lanes) in full
            if a is None:
                return None
            a = np.asarray(a, dtype=np.float64)
            a = a.reshape((*a.shape, *([1] * (3 - a.ndim))))
            full = np.broadcast_to(a, (a.shape[0], self.channels, self.lanes))
            return np.ascontiguousarray(full).ravel()

        out = self.sim.run(flat(yd), flat(noise), flat(disturbance))
        rows, width = int(out["rows"]), int(out["width"])
        cols = self.sim.diag_columns
        diag: dict[str, np.ndarray] = {}
        if width:
            d = out["diag"].reshape(rows, self.channels, self.lanes, width)
            for i, name in enumerate(cols):
                diag[name] = d[..., i]
            if width > len(cols):
                diag["z_hat"] = d[..., len(cols) :]
        x = out["x"].reshape(rows, self.states, self.lanes) if self.keep_states else None
        return Block(
            rows,
            out["e"].reshape(shape),
            out["e_measured"].reshape(shape),
            out["v"].reshape(shape),
            out["u"].reshape(shape),
            out["d"].reshape(shape),
            x,
            diag,
            out.get("plant_error"),
        )

    @property
    def stops(self) -> list[tuple[int, str] | None]:
        """Per lane, ``(samples kept, reason)`` of a lane that stopped."""
        return list(self.sim.stops)

    @property
    def done(self) -> bool:
        """Every lane stopped, or the last sample was run."""
        return bool(self.sim.done)

    @property
    def state(self) -> np.ndarray:
        """The plant's states now, ``(states, lanes)``."""
        return np.asarray(self.sim.state).reshape(self.states, self.lanes)


def start(
    plant: Any,
    controllers: Sequence[Any],
    *,
    dt: float,
    samples: int,
    substeps: int,
    x0: np.ndarray,
    outputs: Sequence[int],
    limits: Sequence[tuple[float, float] | None],
    diverge_at: float | None = None,
    state_bound: float | None = None,
    detail: str = "full",
    keep_states: bool = True,
) -> Engine:
    """A run from the states ``x0`` (``(states, lanes)``): see :class:`Engine`."""
    x0 = np.asarray(x0, dtype=np.float64)
    states, lanes = x0.shape
    sim = _core.Lockstep(
        plant,
        list(controllers),
        dt=float(dt),
        samples=int(samples),
        substeps=int(substeps),
        states=states,
        x0=x0.ravel().tolist(),
        outputs=list(outputs),
        limits=list(limits),
        diverge_at=diverge_at,
        state_bound=state_bound,
        detail=detail,
        keep_states=keep_states,
    )
    return Engine(sim, len(outputs), lanes, states, keep_states)
