"""One chunk of a campaign: a ControllerBank and a vectorised RK4 in lockstep."""

from __future__ import annotations

import ctypes
import os
import sys
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from famcc.campaigns.controller import _controller
from famcc.campaigns.noise import noise_keys, standard_normal
from famcc.families import Family
from famcc.verdicts import STARTUP


@dataclass
class _Chunk:
    """Everything a worker needs for cases ``start .. stop - 1``."""

    start: int
    stop: int
    family: Family
    controller: dict[str, Any]
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


def _stack(out: Any, shape: tuple[int, int]) -> np.ndarray:
    """A right-hand side's value as an ``(n, N)`` float64 array (entries may be scalars)."""
    if isinstance(out, np.ndarray) and out.shape == shape and out.dtype == np.float64:
        return out
    try:
        arr = np.asarray(out, dtype=np.float64)
    except ValueError:  # ragged: some entries are scalars
        arr = np.empty(0)
    if arr.shape == shape:
        return arr
    if len(out) != shape[0]:
        raise ValueError(f"the family's rhs must return {shape[0]} rows, got {len(out)}")
    return np.array([np.broadcast_to(np.asarray(c, dtype=np.float64), shape[1:]) for c in out])


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


def run_chunk(chunk: _Chunk) -> dict[str, np.ndarray]:
    """Integrates one chunk in lockstep; returns its raw per-case counters.

    Public for executors that need an importable function; call
    :func:`campaign` instead.
    """
    import famcc

    _roomy_malloc()
    started = time.perf_counter()
    m = chunk.stop - chunk.start
    n = chunk.family.order
    values = chunk.values
    params = chunk.family.full_params({k: v for k, v in values.items() if k in chunk.family.params})
    x = np.empty((n, m))
    nominal_x0 = chunk.family.x0
    for i in range(n):
        x[i] = values.get(f"x{i + 1}(0)", nominal_x0[i])

    # one bank per distinct controller setting in the chunk
    ckeys = [k for k in values if k.startswith("controller.")]
    groups: list[tuple[Any, np.ndarray | None]] = []
    if ckeys:
        table = np.column_stack([values[k] for k in ckeys])
        uniq, inverse = np.unique(table, axis=0, return_inverse=True)
        inverse = np.asarray(inverse).reshape(-1)
        for g, row in enumerate(uniq):
            idx = np.flatnonzero(inverse == g)
            over = {k.split(".", 1)[1]: float(v) for k, v in zip(ckeys, row)}
            ctrl = _controller(chunk.controller, over)
            groups.append((famcc.ControllerBank(ctrl, len(idx)), idx))
        if len(groups) == 1:
            groups = [(groups[0][0], None)]
    else:
        groups.append((famcc.ControllerBank(_controller(chunk.controller, {}), m), None))
    has_diag = all(hasattr(b, "xi_nominal") and hasattr(b, "expansion") for b, _ in groups)

    # reference: per-case arrays where dispersed, else the nominal object
    rkind = chunk.reference
    ref_vals: dict[str, Any] = dict(chunk.reference_params)
    ref_vals.update(
        {k.split(".", 1)[1]: v for k, v in values.items() if k.startswith("reference.")}
    )
    sigma = values.get("noise.sigma")
    keys = noise_keys(chunk.noise_seed, np.arange(chunk.start, chunk.stop))

    K = chunk.steps + 1
    dt, lims, eps = chunk.dt, chunk.u_limits, chunk.eps
    h = dt / chunk.substeps
    half = 0.5 * h
    sixth = h / 6.0
    rhs = chunk.family._rhs
    shape = (n, m)

    last_out = np.full(m, -1, dtype=np.int64)
    first_in = np.full(m, -1, dtype=np.int64)
    last_sat = np.full(m, -1, dtype=np.int64)
    sat_count = np.zeros(m, dtype=np.int64)
    sat_late = np.zeros(m, dtype=np.int64)
    exp_unsat = np.zeros(m, dtype=np.int64)
    exp_unsat_late = np.zeros(m, dtype=np.int64)
    max_xi_nom = np.zeros(m) if has_diag else np.full(m, np.nan)
    diverged_at = np.full(m, -1, dtype=np.int64)
    alive = np.ones(m, dtype=bool)
    any_dead = False
    pending_first = m
    frozen: dict[str, np.ndarray] = {}
    counters = {
        "last_out": last_out,
        "first_in": first_in,
        "last_sat": last_sat,
        "sat_count": sat_count,
        "sat_late": sat_late,
        "exp_unsat": exp_unsat,
        "exp_unsat_late": exp_unsat_late,
        "max_xi_nominal": max_xi_nom,
    }
    v = np.empty(m)
    xin = np.empty(m)
    fac = np.empty(m)
    overflows = 0
    amp: Any = ref_vals.get("amplitude")
    omega: Any = ref_vals.get("omega")
    phase: Any = ref_vals.get("phase")
    const: Any = ref_vals.get("value")

    with np.errstate(all="ignore"):
        for k in range(K):
            t = k * dt
            if rkind == "sine":
                yd: Any = amp * np.sin(omega * t + phase)
            else:
                yd = const
            e = x[0] - yd
            a = np.abs(e)
            np.copyto(last_out, k, where=~(a < eps))
            if pending_first:
                newly = (a < eps) & (first_in < 0)
                if newly.any():
                    first_in[newly] = k
                    pending_first -= int(newly.sum())
            if sigma is not None:
                e = e + sigma * standard_normal(keys, k)
            if any_dead:
                e = np.where(alive, e, 0.0)
            e = np.ascontiguousarray(e, dtype=np.float64)
            for bank, lanes in groups:
                if lanes is None:
                    v = bank.step(e)
                    overflows += bank.overflows
                    if has_diag:
                        xin = bank.xi_nominal
                        fac = bank.expansion
                else:
                    v[lanes] = bank.step(np.ascontiguousarray(e[lanes]))
                    overflows += bank.overflows
                    if has_diag:
                        xin[lanes] = bank.xi_nominal
                        fac[lanes] = bank.expansion
            if lims is not None:
                sat = (v < lims[0]) | (v > lims[1])
                u = np.minimum(np.maximum(v, lims[0]), lims[1])
                sat_count += sat
                np.copyto(last_sat, k, where=sat)
                if t >= STARTUP:
                    sat_late += sat
            else:
                sat = None
                u = v
            if has_diag:
                np.maximum(max_xi_nom, np.abs(xin), out=max_xi_nom)
                expd = fac > 1.0
                if sat is not None:
                    expd &= ~sat
                exp_unsat += expd
                if t >= STARTUP:
                    exp_unsat_late += expd
            if k == K - 1:
                break
            for j in range(chunk.substeps):
                tj = t + j * h
                k1 = _stack(rhs(tj, x, u, params), shape)
                k2 = _stack(rhs(tj + half, x + half * k1, u, params), shape)
                k3 = _stack(rhs(tj + half, x + half * k2, u, params), shape)
                k4 = _stack(rhs(tj + h, x + h * k3, u, params), shape)
                x = x + sixth * (k1 + 2.0 * (k2 + k3) + k4)
            bad = ~np.all(np.abs(x) <= chunk.state_bound, axis=0)
            if any_dead:
                bad &= alive
            if bad.any():
                idx_bad = np.flatnonzero(bad)
                for name, arr in counters.items():
                    frozen.setdefault(name, arr.copy())[idx_bad] = arr[idx_bad]
                diverged_at[idx_bad] = k + 1
                alive[idx_bad] = False
                any_dead = True
                x[:, idx_bad] = 0.0
    dead = ~alive
    out = {
        name: np.where(dead, frozen[name], arr) if name in frozen else arr
        for name, arr in counters.items()
    }
    out["diverged_at"] = diverged_at
    out["overflows"] = np.array([overflows])
    out["has_diagnostics"] = np.array([has_diag])
    out["seconds"] = np.array([time.perf_counter() - started])
    return out
