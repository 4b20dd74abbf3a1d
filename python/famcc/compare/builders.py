"""Each compared controller built from its parameters (a point of its :class:`Space`)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from famcc._common import DesignWarning
from famcc.compare.spaces import _KINDS
from famcc.peers import ADRCPeer, PIDPeer, lmcc
from famcc.tuning.space import observer_controller


@contextmanager
def _design_warnings_silenced() -> Iterator[None]:
    """famcc's :class:`famcc.DesignWarning` ignored inside: the comparison measures its cost."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DesignWarning)
        yield


@_design_warnings_silenced()
def build(kind: str, p: dict[str, Any], dt: float, u_limits: tuple[float, float]) -> Any:
    """The controller of ``kind`` with parameters ``p`` at sample period ``dt``.

    famcc's construction-time findings (:class:`famcc.DesignWarning`, e.g. a
    differentiator too fast for a 200 Hz loop) are silenced here: the comparison
    evaluates every candidate as tuned, and the measured runs show the cost.
    """
    n = int(p["order"])
    if kind == "pid":
        w, g = p["w"], p["gain"]
        return PIDPeer(
            dt,
            n,
            kp=p["cp"] * w**n / g,
            ki=p["ci"] * w ** (n + 1) / g,
            kd=p["cd"] * w ** (n - 1) / g,
            tf=p["ctf"] / w,
            u_limits=u_limits,
        )
    if kind == "adrc":
        return ADRCPeer(dt, n, b0=p["b0"], w_cl=p["w_cl"], k_eso=p["k_eso"], u_limits=u_limits)
    if kind == "lmcc":
        eps = p["eps_factor"] * p["band"] * p["k"] ** (n - 1)
        return lmcc(
            n, dt, k=p["k"], eps=eps, settle_time=p["settle_time"], k_u=p["k_u"], mu=p["mu"]
        )
    if kind != "famcc":
        raise ValueError(f"kind must be one of {', '.join(_KINDS)}, got {kind!r}")
    return observer_controller(p, dt, u_limits)
