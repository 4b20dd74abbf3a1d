"""Verdicts on a closed-loop run: claims of the paper's theorems that a run can fail.

Every function here looks at a :class:`famcc.SimResult` and returns a
:class:`Verdict` whose status is ``"held"``, ``"failed"`` or ``"untested"``.
A claim is *untested* when the run cannot decide it, for instance when its
bound lies beyond the horizon; it is never reported as held then
(docs/design.md §8).

``|xi~| < 1`` is deliberately not a verdict: once the flexible boundary has
expanded it holds by construction (``xi~ = d / (d + rho_e)``). What can fail
is the *nominal* constraint: the bounds staying nominal while the actuator had
headroom, and the accuracy being regained after saturation.

The claims (Theorems 1-3 and Corollaries 1-3 of the paper), with ``T_s`` the
envelope's preset time, ``T'`` the corollary's convergence time, ``eps`` the
output accuracy and ``T_e`` the end of a saturation episode:

``settling`` (a run designed without saturation)
    ``|z1| < eps`` for good from ``max(T_e, T_s) + T'`` on, where ``T_e`` is
    the end of the last saturation episode (0 when the actuator never
    saturated; the start-up peaking of the differentiator may saturate it
    for a few milliseconds).
``unsaturated``
    the commanded ``v`` stays inside the limits after the start-up window.
``nominal``
    the bounds stay nominal (no flexible expansion) after the start-up
    window: the state stays inside the nominal constraint set, which is what
    Theorems 1-3 promise without saturation.
``settles`` (a run with saturation)
    settled by the paper's horizon (10 s): ``|z1| < eps`` from some time on
    until then, as the paper's saturated figures show. A run still saturated
    or outside the band at that time fails.
``recovery``
    after every saturation episode whose recovery bound
    ``max(T_e, T_s) + T'`` comes before the next episode (or the end of the
    run), ``|z1| < eps`` holds from that bound until the next episode.
``nominal-again``
    in the same windows, the bounds are nominal again.

A user's run carries none of these claims; :func:`requirements` judges it
against the user's own accuracy and time (:func:`settled_by`, :func:`settles`).

>>> import numpy as np, famcc
>>> from famcc import verdicts
>>> t = np.arange(0, 5.001, 0.01)
>>> z1 = np.where(t < 2.0, 1.0, 0.01)          # settles at 2 s
>>> r = famcc.SimResult(t=t, y=z1, y_d=0 * t, x=z1[:, None], z=z1[:, None],
...                     v=0 * t, u=0 * t, dt=0.01)
>>> [str(verdicts.settling(r, eps=0.1, settle_time=1.0, t_prime=tp).status)
...  for tp in (2.0, 0.5, 9.0)]
['held', 'failed', 'untested']
"""

from __future__ import annotations

from famcc.verdicts.claims import (
    nominal,
    nominal_again,
    recovery,
    requirements,
    settled_by,
    settles,
    settling,
    unsaturated,
)
from famcc.verdicts.status import STATUSES, Status, combine, combine_codes
from famcc.verdicts.verdict import STARTUP, Verdict, count, recovery_windows

__all__ = [
    "STARTUP",
    "STATUSES",
    "Status",
    "Verdict",
    "combine",
    "combine_codes",
    "count",
    "nominal",
    "nominal_again",
    "recovery",
    "recovery_windows",
    "requirements",
    "settled_by",
    "settles",
    "settling",
    "unsaturated",
]
