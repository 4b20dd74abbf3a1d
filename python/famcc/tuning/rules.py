"""The design rules in words: :func:`design`, :class:`Design` and its findings."""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from famcc._common import DesignWarning

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


@dataclass(frozen=True)
class Trial:
    """One candidate that :func:`tune` simulated, with its metrics and verdict.

    Attributes
    ----------
    knobs : dict
        ``phase_budget``, ``settle_fraction``, ``mu_per_dt``.
    metrics : dict
        :meth:`famcc.tuning.Assessment.metrics` of the candidate's run.
    feasible : bool
        Whether every requirement held.
    reason : str
        Why not, in words (empty when feasible).
    """

    knobs: dict[str, float]
    metrics: dict[str, Any]
    feasible: bool
    reason: str


@dataclass(frozen=True)
class Design:
    """A controller designed from requirements; :meth:`controller` builds it.

    Attributes
    ----------
    requirements : dict
        The inputs of :func:`design`.
    parameters : dict
        The chosen numbers: ``law_order``, ``integral``, ``mu``, ``a``,
        ``discretization``, ``prefilter`` (the differentiator's low-pass
        prefilter time constant, s; 0: none), ``lambda`` (stage rate, 1/s), ``loop_rate``
        (``lambda_s``, 1/s), ``k_u``, ``eps_s`` (the constraint's final width on
        ``s``), ``rho_e``, ``k0``, ``settle_time`` (the envelope's ``T_s``).
    checks : tuple of Finding
        The named findings, each ok, warn or fail.
    trials : tuple of Trial
        The candidates :func:`tune` simulated (empty for :func:`design`).
    choice : str
        Why :func:`tune` chose this candidate (empty for :func:`design`).
    """

    requirements: dict[str, Any]
    parameters: dict[str, Any]
    checks: tuple[Finding, ...] = field(default=())
    trials: tuple[Trial, ...] = field(default=(), repr=False)
    choice: str = ""

    @property
    def ok(self) -> bool:
        """True when no finding failed."""
        return all(f.level != "fail" for f in self.checks)

    @property
    def integral(self) -> bool:
        """Integral action on (the law acts on the integral of the error too)."""
        return bool(self.parameters["integral"])

    @property
    def law_order(self) -> int:
        """Order of the law: the plant's order, plus one with integral action."""
        return int(self.parameters["law_order"])

    def controller_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of :class:`famcc.Controller` for this design."""
        import famcc

        p, r = self.parameters, self.requirements
        n = r["order"]
        stages = p["law_order"] - 1
        kw: dict[str, Any] = {
            "order": n,
            "dt": r["dt"],
            "feedback": [famcc.Linear(p["lambda"])] * stages if stages else None,
            "constraint": "longitudinal",
            "eps": p["eps_s"],
            "settle_time": p["settle_time"],
            "k0": p["k0"],
            "k_u": p["k_u"],
            "rho_e": p["rho_e"],
            "gamma": "log",
            "differentiator": (
                famcc.HighGain(
                    p["mu"],
                    list(p["a"]),
                    discretization=p["discretization"],
                    limits=p.get("estimate_limits"),
                    prefilter=p.get("prefilter", 0.0),
                )
                if n > 1
                else None
            ),
        }
        if p["integral"]:
            kw["integral"] = True
        return kw

    def controller(self, **overrides: Any) -> Any:
        """A fresh :class:`famcc.Controller` for this design (``overrides`` replace
        keyword arguments, e.g. ``dtype="float32"``)."""
        import famcc

        kw = self.controller_kwargs()
        kw.update(overrides)
        return famcc.Controller(kw.pop("order"), kw.pop("dt"), **kw)

    def __str__(self) -> str:
        p, r = self.parameters, self.requirements
        n, dt = r["order"], r["dt"]
        lines = [
            f"famcc.design for a plant of order {n} sampled at {1 / dt:g} Hz, u in "
            f"[{r['u_limits'][0]:g}, {r['u_limits'][1]:g}], |e| < {r['eps']:g} within "
            f"{r['settle_time']:g} s, hold input {r['hold_input']:g}"
            + (f", gain {r['gain']:g}" if r["gain"] is not None else ", gain unknown")
            + (f", noise std {r['noise_std']:g}" if r["noise_std"] else "")
            + ":",
        ]
        if p["integral"]:
            lines.append(
                f"- integral action: the law of order {p['law_order']} acts on (integral of e, "
                "e, e', ...), so a constant load is carried by the integral and e -> 0."
            )
        else:
            lines.append(
                "- no integral action: the load is carried by xi, at the cost of an "
                "offset (see the accuracy finding)."
            )
        if n > 1:
            lines.append(
                f"- differentiator: mu = {p['mu']:.4g} s ({p['mu'] / dt:.3g} samples"
                + (", slowed for the noise" if r["noise_std"] else "")
                + (
                    f", behind a low-pass prefilter of {p['prefilter']:.4g} s"
                    if p.get("prefilter")
                    else ""
                )
                + f"), coefficients "
                f"(s+2)^{n} = {tuple(round(a, 6) for a in p['a'])}, {p['discretization']} "
                "discretization"
                + (
                    " (the exact ZOH aliases at order >= 4)"
                    if p["discretization"] == "tustin"
                    else ""
                )
                + "."
            )
        lines.append(
            f"- time scales kept apart by one phase budget: differentiator 2/mu = "
            f"{2 / p['mu']:.4g} 1/s, loop rate {p['loop_rate']:.4g} 1/s, manifold rate lambda = "
            f"{p['lambda']:.4g} 1/s (stage laws Linear(lambda), linear near 0: no chatter)."
        )
        lines.append(
            f"- k_u = {p['k_u']:.4g}: the hold input is held at xi = 0.5, well inside the band; "
            f"eps = {p['eps_s']:.4g} on s makes the loop rate 2 k_u G / eps; rho_e = "
            f"{p['rho_e']:.3g} (the bounds expand only when the output is beyond the limits); "
            f"T_s = {p['settle_time']:g} s."
        )
        lines.append("Findings:")
        lines += [f"  {f}" for f in self.checks]
        return "\n".join(lines)

    def __repr__(self) -> str:
        bad = [f.name for f in self.checks if f.level != "ok"]
        return (
            f"<famcc.Design order {self.requirements['order']}, law order "
            f"{self.law_order}, integral {self.integral}, k_u {self.parameters['k_u']:.4g}, "
            f"eps {self.parameters['eps_s']:.4g}; "
            + ("all findings ok" if not bad else "not ok: " + ", ".join(bad))
            + ">"
        )


def design(
    order: int,
    dt: float,
    *,
    u_limits: Sequence[float],
    eps: float,
    settle_time: float,
    hold_input: float,
    gain: float | None = None,
    noise_std: float = 0.0,
    integral: bool | None = None,
    phase_budget: float | None = None,
    mu_per_dt: float | None = None,
    settle_fraction: float | None = None,
    max_error: float | None = None,
) -> Design:
    """A controller for the requirements, from rules (no simulation).

    Parameters
    ----------
    order : int
        System order ``n``: the relative degree of the output (1 to 8).
    dt : float
        Sample period, s.
    u_limits : (lo, hi)
        Actuator limits, input units (``lo < hi``).
    eps : float
        Required accuracy ``|y - y_d| < eps`` after settling, output units.
    settle_time : float
        Required settling time, s.
    hold_input : float
        A bound on ``|F/G|``: the input that holds the error still along the
        reference, e.g. the voltage that holds a motor's load. The one piece of
        plant knowledge the law's gain needs.
    gain : float, optional
        A bound on the input gain ``|G|`` of ``y^(n) = G u + F`` (output units
        per ``s^n`` per input unit). It sets the loop's rate and lets the design
        check the sampled loop; without it the design warns.
    noise_std : float
        Standard deviation of the measurement noise on ``y``.
    integral : bool, optional
        Integral action; None chooses it (on when ``gain`` is known and the law
        order ``n + 1`` fits in 8).
    phase_budget : float, optional
        The phase budget of the linearized sampled loop, rad (default 0.8, about
        45 degrees of margin): larger is faster and less damped. A tuning knob
        of :func:`tune`.
    mu_per_dt : float, optional
        The smallest differentiator time constant in samples (default 10).
    settle_fraction : float, optional
        The envelope's preset time as a fraction of ``settle_time`` (default 0.5).
    max_error : float, optional
        The largest error ``|y - y_d|`` to recover from (e.g. a set-point step),
        output units. At order >= 4 it sets the estimate limits; without it the
        design warns.

    Returns
    -------
    Design
        Emits a :class:`DesignWarning` for every finding that is not ok.

    Raises
    ------
    famcc.ConfigError
        For an invalid requirement (the message names it).
    """
    from famcc import _core

    lo, hi = (float(v) for v in u_limits)
    raw = _core.design_rules(
        int(order),
        float(dt),
        (lo, hi),
        float(eps),
        float(settle_time),
        float(hold_input),
        None if gain is None else float(gain),
        float(noise_std),
        integral,
        phase_budget,
        mu_per_dt,
        settle_fraction,
        None if max_error is None else float(max_error),
    )
    req = {
        "order": int(order),
        "dt": float(dt),
        "u_limits": (lo, hi),
        "eps": float(eps),
        "settle_time": float(settle_time),
        "hold_input": float(hold_input),
        "gain": None if gain is None else float(gain),
        "noise_std": float(noise_std),
        "integral": integral,
        "phase_budget": phase_budget,
        "mu_per_dt": mu_per_dt,
        "settle_fraction": settle_fraction,
        "max_error": None if max_error is None else float(max_error),
    }
    params = {k: v for k, v in raw.items() if k != "checks"}
    checks = tuple(
        Finding(
            name,
            level,
            _RULES[name],
            value,
            limit,
            suggestion,
            _message(name, level, value, limit, suggestion, params, req),
        )
        for name, level, value, limit, suggestion in raw["checks"]
    )
    for f in checks:
        if f.level != "ok":
            warnings.warn(f"famcc.design: {f.name}: {f.message}", DesignWarning, stacklevel=2)
    return Design(req, params, checks)
