"""The design rules in words: :func:`design`, :class:`Design` and its findings."""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from famcc import _core
from famcc._common import DesignWarning
from famcc.tuning.findings import _RULES, Finding, _message

if TYPE_CHECKING:
    from famcc._core import Controller, ControllerSpec

__all__ = ["Design", "Finding", "Trial", "design"]

# Keyword arguments of Controller that ControllerSpec.replace cannot change.
_SHAPE_KEYS = frozenset({"order", "constraint", "integral"})


@dataclass(frozen=True)
class Trial:
    """One candidate that :func:`tune` simulated, with its metrics and verdict.

    Attributes
    ----------
    knobs : dict
        ``phase_budget``, ``settle_fraction``, ``mu_per_dt`` for the rules'
        grid; the numeric parameters of the point and ``observer = 1`` for
        the observer search (:mod:`famcc.tuning.observed`).
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
    spec : famcc._core.ControllerSpec or None
        The controller's configuration as the core parsed it, which
        :meth:`controller` builds without keyword arguments or text (None for
        a Design made by hand: :meth:`controller` then goes through
        :meth:`controller_kwargs`).
    """

    requirements: dict[str, Any]
    parameters: dict[str, Any]
    checks: tuple[Finding, ...] = field(default=())
    trials: tuple[Trial, ...] = field(default=(), repr=False)
    choice: str = ""
    spec: ControllerSpec | None = field(default=None, repr=False, compare=False)

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
        p, r = self.parameters, self.requirements
        if "observer_candidate" in p and self.spec is not None:
            return dict(self.spec.config())  # a point of tune's observer search
        n = r["order"]
        stages = p["law_order"] - 1
        kw: dict[str, Any] = {
            "order": n,
            "dt": r["dt"],
            "feedback": [_core.Linear(p["lambda"])] * stages if stages else None,
            "constraint": "longitudinal",
            "eps": p["eps_s"],
            "settle_time": p["settle_time"],
            "k0": p["k0"],
            "k_u": p["k_u"],
            "rho_e": p["rho_e"],
            "gamma": "log",
            "differentiator": (
                _core.HighGain(
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
        if p["direction"] != "positive":
            kw["direction"] = p["direction"]
        return kw

    def controller(self, **overrides: Any) -> Controller:
        """A fresh :class:`famcc.Controller` for this design.

        Parameters
        ----------
        **overrides
            Keyword arguments of :class:`famcc.Controller` that replace the
            design's, e.g. ``dtype="float32"``.

        Returns
        -------
        famcc.Controller
            Built from :attr:`spec` (``spec.replace(**overrides).build()``);
            equal to ``Controller(**{**controller_kwargs(), **overrides})``,
            which is the way taken for ``order``, ``constraint`` or
            ``integral`` overrides and when there is no spec.
        """
        if self.spec is not None and not _SHAPE_KEYS.intersection(overrides):
            return self.spec.replace(**overrides).build()
        kw = self.controller_kwargs()
        kw.update(overrides)
        return _core.Controller(kw.pop("order"), kw.pop("dt"), **kw)

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
        if "observer_candidate" in p:
            return "\n".join([*lines, _observed_text(p["observer_candidate"], r)])
        if p["direction"] == "negative":
            lines.append(
                "- control direction: negative (gain < 0: the output falls as the input "
                "rises), so the law's sign is reversed, v = +k_u Gamma(xi); the rules use |gain|."
            )
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
        per ``s^n`` per input unit), with the sign of ``G``: negative for a plant
        whose output falls as its input rises, which gives a controller with
        ``direction='negative'`` (the rules use ``|G|``). It sets the loop's rate
        and lets the design check the sampled loop; without it the design warns
        and the direction is the paper's (``G > 0``).
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
    params = {k: v for k, v in raw.items() if k not in ("checks", "controller")}
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
    return Design(req, params, checks, spec=raw["controller"])


def _observed_text(c: dict[str, Any], r: dict[str, Any]) -> str:
    """The lines of a Design found by tune's observer search (famcc.tuning.observed)."""
    law = (
        f"FiniteTime(k = {c['k']:.4g} 1/s, p = {c['p']:.3g}) on the lateral constraint"
        if c["family"] == "finite-time"
        else f"Linear(k = {c['k']:.4g} 1/s) stages on the longitudinal constraint"
    )
    mu = c["obs_mu"] if "obs_mu" in c else 1.0 / (c["obs_ratio"] * c["k"])
    direction = "negative (b0 < 0)" if c["b0"] < 0 else "positive"
    found = (
        "- found by famcc.tune's observer search (beyond the paper, docs/observer.md): "
        f"{law}, envelope eps = {c['eps']:.4g} reached by T_s = {c['settle_time']:.4g} s."
    )
    observer = (
        f"- extended observer: mu = {mu:.4g} s, nominal gain b0 = {c['b0']:.4g} (the "
        "measured or given gain); it estimates the lumped term and the law cancels it "
        "within the actuator's range, so a load is carried without an offset; control "
        f"direction {direction}."
    )
    verdict = (
        f"- no rules' findings apply to it: its verdict is its own run at {1 / r['dt']:g} Hz "
        "(Design.checks, finding 'tune')."
    )
    return f"{found}\n{observer}\n{verdict}"
