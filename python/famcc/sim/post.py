"""What a run's record adds after the loop: the true error vector ``z`` from the
plant's exact output derivatives, and ``-F/G`` (the input that holds
``dz_n/dt = 0``) from its gain and drift, for every kept sample.

A plant may offer ``derivatives_table(t, x) -> (derivatives, gain, drift)``
over all samples at once (the paper's plants: famcc-paper, compiled); else its
``output_derivatives(t, x)`` and ``gain_and_drift(t, x)`` are called sample by
sample. What a plant cannot compute is kept as the reason
(``SimResult.derivatives_error``, ``SimResult.neg_f_over_g_error``), never
silently dropped.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["PLANT_ERRORS", "plant_error", "true_errors"]

#: What a plant's ``output_derivatives`` / ``gain_and_drift`` may raise when it cannot
#: compute them: kept as the reason (``SimResult.*_error``), never silently dropped.
PLANT_ERRORS = (NotImplementedError, TypeError, ValueError, ArithmeticError)


def plant_error(exc: BaseException, t: float) -> str:
    """The reason text of a plant's failure at time ``t``."""
    text = str(exc) or type(exc).__name__
    if not isinstance(exc, NotImplementedError):
        text = f"{type(exc).__name__} at t = {t:.6g} s: {text}"
    return text


def true_errors(
    result: Any, plant: Any, table: np.ndarray, ref_order: int, full: int, record: bool
) -> None:
    """Fills ``result.z`` (columns 2..n) and ``result.neg_f_over_g`` for rows ``< full``.

    ``table`` holds the reference and its derivatives up to ``ref_order`` at
    the run's samples; ``-F/G`` needs ``y_d^(n)`` and ``record``.
    """
    n = result.z.shape[1]
    t, x, z = result.t, result.x, result.z
    derivs_error: str | None = None
    derivs_fn = getattr(plant, "output_derivatives", None)
    has_derivs = n > 1
    if n > 1 and not callable(derivs_fn):
        has_derivs, derivs_error = False, "the plant has no output_derivatives(t, x) method"
    fg_fn = getattr(plant, "gain_and_drift", None)
    fg_error: str | None = None
    has_fg = record and ref_order >= n
    if not record:
        fg_error = "not computed: simulate(record=False)"
    elif ref_order < n:
        fg_error = (
            f"the reference gives derivatives only up to order {ref_order}; -F/G needs "
            f"y_d^({n}) (pass n + 1 = {n + 1} callables, or reference(t, k))"
        )
    elif not callable(fg_fn):
        has_fg, fg_error = False, "the plant has no gain_and_drift(t, x) method"
    negfg = np.full(len(t), np.nan) if has_fg else None
    fast = getattr(plant, "derivatives_table", None)
    if callable(fast) and full > 0:
        d, gain, drift = fast(t[:full], x[:full])
        if has_derivs:
            z[:full] = d - table[:full, :n]
        if negfg is not None:
            negfg[:full] = -(drift - table[:full, n]) / gain
    else:
        for k in range(full):
            tk, xk, yd = float(t[k]), x[k], table[k]
            if has_derivs and derivs_fn is not None:
                try:
                    z[k] = np.asarray(derivs_fn(tk, xk), dtype=float) - yd[:n]
                except PLANT_ERRORS as exc:
                    has_derivs, derivs_error = False, plant_error(exc, tk)
            if has_fg and negfg is not None and fg_fn is not None:
                try:
                    gain, drift = fg_fn(tk, xk)
                    negfg[k] = -(drift - yd[n]) / gain
                except PLANT_ERRORS as exc:
                    has_fg, fg_error = False, plant_error(exc, tk)
                    negfg = None
    result.neg_f_over_g = negfg
    result.neg_f_over_g_error = fg_error
    result.derivatives_error = derivs_error
