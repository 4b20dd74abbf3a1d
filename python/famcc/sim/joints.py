"""Multi-input plants under one single-output controller per joint.

:func:`simulate_joints` closes one loop per joint of a plant such as
:func:`famcc.plants.two_link_arm` with independent single-output controllers
(decentralised control: the coupling acts on each loop as a disturbance), in
the one sample-and-hold loop of :func:`famcc.simulate` (a channel per joint),
and returns one :class:`famcc.SimResult` per joint.

>>> import famcc
>>> from famcc.plants import two_link_arm
>>> arm = two_link_arm()
>>> ctrls = [famcc.Controller(2, 1e-3, famcc.FiniteTime(k=2.0, p=0.5), constraint="lateral",
...                           eps=0.05, k_u=k) for k in (10.0, 3.0)]
>>> shoulder, elbow = simulate_joints(arm, ctrls, 3.0, references=[famcc.Constant(0.5)] * 2,
...                                   u_limits=[(-60.0, 60.0), (-20.0, 20.0)])
>>> shoulder.settling_time(0.05) < 3.0, elbow.output.name
(True, 'elbow angle')
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from famcc.plants.base import is_real
from famcc.signals import reference_table, source
from famcc.sim import engine
from famcc.sim.checks import check_limits, check_substeps, describe_controller_of
from famcc.sim.result import SimResult
from famcc.sim.simulate import SUBSTEPS

__all__ = ["simulate_joints"]


def simulate_joints(
    plant: Any,
    controllers: Sequence[Any],
    t_end: float,
    references: Sequence[Any],
    u_limits: Sequence[Sequence[float] | None] | None = None,
    substeps: int = SUBSTEPS,
    *,
    noise: float | Callable[[float], float] | None = None,
    seed: int | np.random.Generator | None = None,
    diverge_at: float | None = None,
) -> list[SimResult]:
    """One sampled-and-held loop per joint of a multi-input plant, integrated together.

    At ``t_k = k dt`` controller ``i`` reads its joint's error ``e_i = q_i + n_i -
    y_d,i`` and returns ``v_i``; ``u_i = clip(v_i, u_limits[i])`` is held until
    ``t_k+1`` while the plant is integrated with ``substeps`` RK4 steps, exactly
    as :func:`famcc.simulate` does for one loop.

    Parameters
    ----------
    plant : object
        ``joints``, ``order`` (per joint), ``x0`` (joint ``i``'s output and its
        derivatives at ``x[order i : order (i + 1)]``) and ``rhs(t, x, u)`` with a
        sequence ``u`` of inputs, e.g. :func:`famcc.plants.two_link_arm`.
    controllers : sequence
        One per joint, each with ``dt`` (all equal), ``order`` and ``step(e,
        applied=None)``.
    t_end : float
        Horizon, s.
    references : sequence
        One ``reference(t, k)`` per joint (:class:`famcc.Constant`, ...).
    u_limits : sequence of (lo, hi) or None
        Per joint.
    substeps : int
        RK4 steps per sample.
    noise, seed : see :func:`famcc.simulate`
        The same noise level on every joint, independent draws.
    diverge_at : float or None
        Stop when any joint's ``|e_i|`` exceeds it (or a value becomes
        non-finite); every result is then flagged ``diverged``.

    Returns
    -------
    list of SimResult
        One per joint (no controller diagnostics are recorded; ``x`` holds the
        joint's own states).
    """
    nj, n = int(plant.joints), int(plant.order)
    if len(controllers) != nj or len(references) != nj:
        raise ValueError(f"controllers and references need one entry per joint ({nj})")
    dt = float(controllers[0].dt)
    if any(not math.isclose(float(c.dt), dt) or int(c.order) != n for c in controllers):
        raise ValueError(f"every controller must have dt = {dt} and order = {n}")
    if not (is_real(t_end) and math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0, got {t_end!r}")
    substeps = check_substeps(substeps)
    given = list(u_limits) if u_limits is not None else [None] * nj
    if len(given) != nj:
        raise ValueError(f"u_limits needs one entry (or None) per joint ({nj})")
    limits = [check_limits(lim, f"u_limits[{i}]") for i, lim in enumerate(given)]
    K = round(t_end / dt) + 1
    t_arr = np.arange(K) * dt
    tables = [reference_table(r, n, t_arr)[0][:, :n] for r in references]
    rng = np.random.default_rng(seed)
    noise_fns = [source("noise", noise, rng) for _ in range(nj)]
    noise_k = None
    if noise_fns[0] is not None:
        noise_k = np.array([[float(fn(float(t))) for fn in noise_fns if fn] for t in t_arr])
    run = engine.start(
        ("list", plant.rhs),
        list(controllers),
        dt=dt,
        samples=K,
        substeps=substeps,
        x0=np.asarray(plant.x0, dtype=float)[:, None],
        outputs=[n * i for i in range(nj)],
        limits=limits,
        diverge_at=diverge_at,
        detail="none",
    )
    yd = np.stack([tab[:, 0] for tab in tables], axis=1)
    with np.errstate(over="ignore", invalid="ignore"):
        blk = run.block(yd, noise_k)
    stop = run.stops[0]
    if blk.plant_error is not None and not isinstance(blk.plant_error, ArithmeticError):
        raise blk.plant_error
    if stop is not None and diverge_at is None:
        raise FloatingPointError(
            f"the joints' loop stopped ({stop[1]}) after t = {float(t_arr[stop[0] - 1]):.6g} s"
        )
    keep = K if stop is None else stop[0]
    assert blk.x is not None
    out = []
    for i in range(nj):
        state = blk.x[:keep, n * i : n * (i + 1), 0]
        text, cfg = describe_controller_of(controllers[i])
        out.append(
            SimResult(
                t=t_arr[:keep],
                y=state[:, 0].copy(),
                y_d=tables[i][:keep, 0].copy(),
                x=state.copy(),
                z=state - tables[i][:keep],
                v=blk.v[:keep, i, 0].copy(),
                u=blk.u[:keep, i, 0].copy(),
                dt=dt,
                u_limits=limits[i],
                output=plant.outputs[i],
                input=plant.inputs[i],
                controller_repr=text,
                controller_config=cfg,
                reference_repr=repr(references[i]),
                neg_f_over_g_error="unknown for one joint of a coupled plant",
                z1_measured=None if noise_k is None else blk.e_measured[:keep, i, 0].copy(),
                diverged_at=None if stop is None else float(t_arr[stop[0] - 1]),
            )
        )
    return out
