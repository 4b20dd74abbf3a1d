"""One chunk of a campaign: its cases as the lanes of the one loop (famcc-sim),
tallied block by block (:class:`Tally`)."""

from __future__ import annotations

import ctypes
import os
import sys
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from famcc import _core
from famcc.campaigns.controller import _controller
from famcc.campaigns.noise import noise_keys, standard_normal
from famcc.plants.family import Family
from famcc.sim import engine
from famcc.verdicts import STARTUP

__all__ = ["Tally", "run_chunk"]


@dataclass
class _Chunk:
    """Everything a worker needs for cases ``start .. stop - 1``."""

    start: int
    stop: int
    family: Family
    controller: _core.ControllerSpec
    values: dict[str, np.ndarray]
    dt: float
    steps: int
    substeps: int
    u_limits: tuple[float, float] | None
    eps: float
    reference: str
    reference_params: dict[str, float]
    state_bound: float
    noise_seed: int


class Tally:
    """Per-case counters of a campaign, accumulated block by block over the
    recorded samples (NaN rows: the case had stopped), from which
    :class:`famcc.CampaignResult` judges every case: the last sample outside
    ``|z1| < eps``, the first inside, the last saturated one, the saturated
    samples (and those after the start-up), the samples expanded with
    headroom (and after the start-up) and ``max |xi|`` of the nominal
    constraint variable.
    """

    NAMES = (
        "last_out",
        "first_in",
        "last_sat",
        "sat_count",
        "sat_late",
        "exp_unsat",
        "exp_unsat_late",
        "max_xi_nominal",
    )

    def __init__(self, m: int, eps: float, limits: tuple[float, float] | None, diag: bool) -> None:
        self.eps, self.limits, self.diag = eps, limits, diag
        self.last_out = np.full(m, -1, dtype=np.int64)
        self.first_in = np.full(m, -1, dtype=np.int64)
        self.last_sat = np.full(m, -1, dtype=np.int64)
        self.sat_count = np.zeros(m, dtype=np.int64)
        self.sat_late = np.zeros(m, dtype=np.int64)
        self.exp_unsat = np.zeros(m, dtype=np.int64)
        self.exp_unsat_late = np.zeros(m, dtype=np.int64)
        self.max_xi_nominal = np.zeros(m) if diag else np.full(m, np.nan)

    @staticmethod
    def _last(mask: np.ndarray, k0: int, prev: np.ndarray) -> np.ndarray:
        rows = mask.shape[0]
        any_ = mask.any(axis=0)
        last = rows - 1 - np.argmax(mask[::-1], axis=0)
        return np.where(any_, k0 + last, prev)

    def add(self, blk: engine.Block, k0: int, t: np.ndarray) -> None:
        """Adds the block's rows (samples ``k0 ..``, times ``t``)."""
        e = blk.e[:, 0, :]
        kept = ~np.isnan(e)
        a = np.abs(e)
        self.last_out = self._last(kept & ~(a < self.eps), k0, self.last_out)
        inside = kept & (a < self.eps)
        new = (self.first_in < 0) & inside.any(axis=0)
        self.first_in = np.where(new, k0 + np.argmax(inside, axis=0), self.first_in)
        late = (t >= STARTUP)[:, None]
        v = blk.v[:, 0, :]
        if self.limits is not None:
            sat = kept & ((v < self.limits[0]) | (v > self.limits[1]))
            self.sat_count += sat.sum(axis=0)
            self.sat_late += (sat & late).sum(axis=0)
            self.last_sat = self._last(sat, k0, self.last_sat)
        else:
            sat = np.zeros_like(kept)
        if self.diag:
            xin = np.where(kept, np.abs(blk.diag["xi_nominal"][:, 0, :]), 0.0)
            np.maximum(self.max_xi_nominal, xin.max(axis=0), out=self.max_xi_nominal)
            expd = kept & (blk.diag["expansion"][:, 0, :] > 1.0) & ~sat
            self.exp_unsat += expd.sum(axis=0)
            self.exp_unsat_late += (expd & late).sum(axis=0)

    def counters(self) -> dict[str, np.ndarray]:
        """The counters by name."""
        return {name: getattr(self, name) for name in self.NAMES}


_MALLOC_TUNED = False


def _roomy_malloc() -> None:
    """Undo, in a Dask worker, the nanny's ``MALLOC_TRIM_THRESHOLD_`` for this process.

    Dask's nanny starts its workers with ``MALLOC_TRIM_THRESHOLD_=65536``, which
    also fixes glibc's mmap threshold at 128 KiB: every temporary array of a
    chunk (80-320 KiB) then costs an mmap, a munmap and its page faults, and
    a chunk ran 1.3-2x slower than in a plain process (benches/README.md,
    "Campaign"). This sets the trim threshold to 64 MiB and the mmap threshold to
    16 MiB in the worker, once, on Linux with glibc; elsewhere it does nothing.
    """
    global _MALLOC_TUNED
    if _MALLOC_TUNED:
        return
    _MALLOC_TUNED = True
    if not sys.platform.startswith("linux") or "MALLOC_TRIM_THRESHOLD_" not in os.environ:
        return
    worker = sys.modules.get("distributed")
    try:
        if worker is None or worker.get_worker() is None:
            return
    except ValueError:  # not inside a Dask worker
        return
    try:
        libc = ctypes.CDLL("libc.so.6")
        libc.mallopt(-1, 64 << 20)  # M_TRIM_THRESHOLD
        libc.mallopt(-3, 16 << 20)  # M_MMAP_THRESHOLD
    except (OSError, AttributeError):
        return


def _banks(chunk: _Chunk, values: dict[str, np.ndarray], m: int) -> tuple[list[Any], np.ndarray]:
    """One bank per distinct controller setting, and the lane order that makes
    every bank's lanes contiguous (``order[j]``: the case of lane ``j``)."""
    ckeys = [k for k in values if k.startswith("controller.")]
    if not ckeys:
        return [_core.ControllerBank(_controller(chunk.controller, {}), m)], np.arange(m)
    table = np.column_stack([values[k] for k in ckeys])
    uniq, inverse = np.unique(table, axis=0, return_inverse=True)
    inverse = np.asarray(inverse).reshape(-1)
    order = np.argsort(inverse, kind="stable")
    banks = []
    for g, row in enumerate(uniq):
        over = {k.split(".", 1)[1]: float(v) for k, v in zip(ckeys, row)}
        banks.append(
            _core.ControllerBank(_controller(chunk.controller, over), int(np.sum(inverse == g)))
        )
    return banks, order


def run_chunk(chunk: _Chunk) -> dict[str, np.ndarray]:
    """Integrates one chunk in lockstep; returns its raw per-case counters.

    Public for executors that need an importable function; call
    :func:`campaign` instead.
    """
    _roomy_malloc()
    started = time.perf_counter()
    m = chunk.stop - chunk.start
    n = chunk.family.order
    banks, order = _banks(chunk, chunk.values, m)
    values = {k: v[order] for k, v in chunk.values.items()}
    params = chunk.family.full_params({k: v for k, v in values.items() if k in chunk.family.params})
    x0 = np.empty((n, m))
    nominal_x0 = chunk.family.x0
    for i in range(n):
        x0[i] = values.get(f"x{i + 1}(0)", nominal_x0[i])
    ref: dict[str, Any] = dict(chunk.reference_params)
    ref.update({k.split(".", 1)[1]: v for k, v in values.items() if k.startswith("reference.")})
    sigma = values.get("noise.sigma")
    keys = noise_keys(chunk.noise_seed, np.arange(chunk.start, chunk.stop)[order])
    K, dt = chunk.steps + 1, chunk.dt
    run = engine.start(
        chunk.family.lanes(params, m),
        banks,
        dt=dt,
        samples=K,
        substeps=chunk.substeps,
        x0=x0,
        outputs=[0],
        limits=[chunk.u_limits],
        state_bound=chunk.state_bound,
        detail="campaign",
        keep_states=False,
    )
    tally = Tally(m, chunk.eps, chunk.u_limits, diag=True)
    with np.errstate(all="ignore"):
        while not run.done:
            k0 = run.sim.sample
            ks = np.arange(k0, min(K, k0 + run.block_rows))
            t = ks * dt
            if chunk.reference == "sine":
                yd = ref["amplitude"] * np.sin(
                    np.multiply.outer(t, np.broadcast_to(ref["omega"], (m,))) + ref["phase"]
                )
            else:
                yd = np.broadcast_to(np.asarray(ref["value"], dtype=np.float64), (len(ks), m))
            noise = None
            if sigma is not None:
                noise = np.stack([sigma * standard_normal(keys, int(k)) for k in ks])
            blk = run.block(yd[:, None, :], None if noise is None else noise[:, None, :])
            if blk.plant_error is not None:
                raise blk.plant_error
            tally.add(blk, k0, t)
    diverged_at = np.array([-1 if s is None else s[0] for s in run.stops], dtype=np.int64)
    back = np.empty(m, dtype=np.int64)
    back[order] = np.arange(m)
    out = {name: arr[back] for name, arr in tally.counters().items()}
    out["diverged_at"] = diverged_at[back]
    out["overflows"] = np.array([int(run.sim.held)])
    out["has_diagnostics"] = np.array([True])
    out["seconds"] = np.array([time.perf_counter() - started])
    return out
