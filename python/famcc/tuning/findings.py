"""A design's findings in words: the rules and the messages of :class:`Finding`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

_RULES = {
    "hold-input": "the actuator can hold the load: hold_input < max(|u_min|, |u_max|)",
    "settle-time": "the manifold rate lambda >= (ln 5 + 1.5 (n_law - 1)) / (settle_time - T_s)",
    "sampled-loop": "the linearized sampled loop (chain of n integrators, gain G) is stable: "
    "spectral radius < 1",
    "accuracy": "without integral action the offset under the hold input, "
    "eps_s tanh(hold / 2 k_u) / lambda^(n-1), stays below eps",
    "noise": "noise in s below 0.15 eps_s, and 4 sigma of the input noise within the headroom "
    "the hold input leaves on the nearer limit (prefilter mu / 2 at orders 2-3)",
    "gain-unknown": "the input gain G is known, so the loop rate can be set and checked",
    "estimate-limits": "at order >= 4 the estimates are limited (4 max_error loop_rate^(i-1)), "
    "which keeps the differentiator's start-up peaking out of the law",
}


@dataclass(frozen=True)
class Finding:
    """One named finding of a design.

    Attributes
    ----------
    name : str
        The rule's name (``"sampled-loop"``, ``"settle-time"``, ...).
    level : str
        ``"ok"``, ``"warn"`` or ``"fail"``.
    rule : str
        The rule in words.
    value, limit : float
        The measured quantity and the bound it is compared with (NaN when not
        applicable).
    suggestion : float
        A value that would satisfy the rule (NaN when there is none).
    message : str
        The finding in plain words, with the numbers and the cure.
    """

    name: str
    level: str
    rule: str
    value: float
    limit: float
    suggestion: float
    message: str

    def __str__(self) -> str:
        return f"[{self.level}] {self.name}: {self.message}"


def _message(
    name: str,
    level: str,
    value: float,
    limit: float,
    suggestion: float,
    p: dict[str, Any],
    req: dict[str, Any],
) -> str:
    dt = req["dt"]
    if name == "hold-input":
        return f"hold_input = {value:.4g} against the limits' magnitude {limit:.4g}" + (
            ""
            if level == "ok"
            else ": the actuator cannot hold the load; use a stronger actuator or lower the load"
        )
    if name == "settle-time":
        text = (
            f"manifold rate lambda = {value:.4g} 1/s, needs {limit:.4g} 1/s for settle_time = "
            f"{req['settle_time']:g} s"
        )
        if level != "ok":
            text += (
                f": at dt = {dt:g} s the shortest feasible settle_time is about "
                f"{suggestion:.3g} s (or sample faster: the rate scales with 1/dt)"
            )
        return text
    if name == "sampled-loop":
        steps = 1.0 / max(1e-300, 1.0 - value) if value < 1 else math.inf
        if level == "ok":
            return (
                f"spectral radius {value:.6f} per sample (the slowest mode decays in about "
                f"{steps:.0f} samples)"
            )
        return (
            f"spectral radius {value:.6f} >= 1: the loop is {'marginal' if value < 1 else 'unstable'}"
            f"; lower k_u (now {p['k_u']:.4g}) or raise eps (now {p['eps_s']:.4g})"
        )
    if name == "accuracy":
        text = f"offset under the hold input {value:.4g} against eps = {limit:.4g}"
        if level != "ok":
            text += (
                f": without integral action eps >= {suggestion:.3g} is reachable; use "
                "integral=True (needs gain=) to carry the load in the integral"
            )
        return text
    if name == "noise":
        return (
            f"noise std in s is {value:.3g} of eps_s (limit {limit:g}) with mu = {p['mu']:.4g} s"
            + (
                ""
                if level == "ok"
                else ": even the slowest allowed differentiator "
                "(mu <= 0.05 settle_time) is too noisy; filter the sensor or relax eps"
            )
        )
    if name == "estimate-limits":
        if level == "ok":
            return (
                f"estimates limited: |z_hat_1| <= {value:.4g}, |z_hat_i| <= that times "
                "loop_rate^(i-1) (from max_error)"
            )
        return (
            "no estimate limits: at order >= 4 the differentiator's start-up peaking can "
            "drive the law far outside its bounds; pass max_error= (the largest error to "
            "recover from, e.g. the set-point step) or use famcc.tune(plant), which measures it"
        )
    if name == "gain-unknown":
        return (
            "the input gain G of y^(n) = G u + F was not given: k_u and eps are set from "
            "hold_input and eps, but the sampled loop's stability is not checked; pass "
            "gain= (a bound on |G|) or use famcc.tune(plant), which measures it"
        )
    return f"value {value:.4g}, limit {limit:.4g}"
