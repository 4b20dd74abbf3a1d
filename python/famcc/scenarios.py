"""The paper's six simulation scenarios, with their parameters and claims.

Three examples, each unsaturated (limits +-100) and saturated:

========================  =====  ==============================================
name                      order  design
========================  =====  ==============================================
finite-time               2      LaMC, FiniteTime(k=1, p=0.5), eps_x = 0.1
finite-time-saturated     2      same, u in [-2.5, 3]
variable-exponent         2      LoMC, VariableExponent(1.5, 0.5, 2, 3) + SSMD
variable-exponent-sat...  2      same, u in [-2, 3]
rfc                       3      LoMC, two FixedTime stages + NSMD
rfc-saturated             3      same, u in [-7, 9]
========================  =====  ==============================================

``variant="paper"`` uses the numbers printed in the paper; ``variant="code"``
those of the authors' MATLAB code (second-order disturbance amplitude 3,
third-order x(0) = (1, 0.5, 4) and eps_y = 3, the authors' envelope latch);
see docs/design.md §6 and the README.

>>> import famcc
>>> sc = famcc.scenarios.paper("finite-time")
>>> sc.bound                                   # T_s + T_fn' (Corollary 1), s
3.0
>>> res = sc.run(t_end=2.0)
>>> res.settling_time(0.1) < sc.bound
True
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import famcc
from famcc import bounds, plants

__all__ = ["VARIANTS", "Scenario", "names", "paper"]

VARIANTS = ("paper", "code")

_NAMES = (
    "finite-time",
    "finite-time-saturated",
    "variable-exponent",
    "variable-exponent-saturated",
    "rfc",
    "rfc-saturated",
)

_LIMITS = {
    "finite-time": (-2.5, 3.0),
    "variable-exponent": (-2.0, 3.0),
    "rfc": (-7.0, 9.0),
}


@dataclass(frozen=True)
class Scenario:
    """One of the paper's simulations: plant, controller, limits, claims.

    Attributes
    ----------
    name, variant : str
        Scenario name (see :func:`names`) and ``"paper"`` or ``"code"``.
    example : int
        The paper's example number (1, 2 or 3).
    plant : famcc.plants.Plant
        The plant (with its initial state).
    controller_kwargs : dict
        Keyword arguments of :class:`famcc.Controller` (without ``dt``).
    u_limits : tuple of float
        Actuator limits (lo, hi).
    t_end : float
        Horizon, s (10 s in the paper).
    eps_z : float
        The output accuracy the corollary guarantees (0.1).
    t_prime : float
        The corollary's T' (s): T_fn', T_fxe' or T_fr'.
    settle_time : float
        The envelope's preset time T_s (s).
    paper_settling_time : float or None
        The settling time the paper reports (1.9 s for example 1, 1.2 s for
        example 3), None where it reports none.
    regains_accuracy : bool
        False only where the paper's own numbers do not regain eps_z after
        saturation within the horizon (rfc-saturated, variant "paper").
    """

    name: str
    variant: str
    example: int
    saturated: bool
    plant: Any
    controller_kwargs: dict = field(repr=False)
    u_limits: tuple
    t_end: float
    eps_z: float
    t_prime: float
    settle_time: float
    paper_settling_time: float | None
    regains_accuracy: bool
    description: str

    @property
    def bound(self) -> float:
        """T_s + T' (s): the corollary's bound on the settling time without saturation."""
        return self.settle_time + self.t_prime

    def controller(self, dt: float = 1e-3, **overrides: Any) -> famcc.Controller:
        """A fresh controller for this scenario at sample period ``dt`` (s)."""
        kw = dict(self.controller_kwargs)
        kw.update(overrides)
        order = kw.pop("order")
        return famcc.Controller(order, dt, **kw)

    def run(self, dt: float = 1e-3, t_end: float | None = None, substeps: int = 10,
            **overrides: Any):
        """Simulates the scenario; returns a :class:`famcc.SimResult`.

        ``overrides`` go to the controller (e.g. ``differentiator=...``).
        """
        from famcc.simulate import simulate

        return simulate(self.plant, self.controller(dt, **overrides),
                        self.t_end if t_end is None else t_end,
                        u_limits=self.u_limits, substeps=substeps)

    def recovery_bound(self, result) -> float:
        """max(T_e, T_s) + T' (s), with T_e the end of the last saturation episode."""
        t_e = result.last_saturation_end or 0.0
        return max(t_e, self.settle_time) + self.t_prime

    def check(self, result) -> list[str]:
        """The theoretical guarantees this run violates (empty when all hold).

        - |xi~| < 1 at every sample (Theorems 1-3) and no clamping;
        - u inside the actuator limits;
        - without saturation (all samples inside the limits): |z1| < eps_z from
          T_s + T' on (Corollaries 1-3);
        - with saturation: |z1| < eps_z regained by max(T_e, T_s) + T', unless the
          scenario is documented not to regain it (then only the invariants).
        """
        problems = []
        mx = result.max_abs_xi
        if mx is None or not mx < 1.0:
            problems.append(f"max |xi~| = {mx} is not < 1")
        if result.clamp_count:
            problems.append(f"xi~ was clamped {result.clamp_count} times")
        lo, hi = self.u_limits
        if result.u_min < lo or result.u_max > hi:
            problems.append(f"u left the limits [{lo}, {hi}]")
        ts = result.settling_time(self.eps_z)
        horizon = float(result.t[-1])
        if result.saturated_fraction == 0.0:
            if self.bound <= horizon and (ts is None or ts > self.bound):
                problems.append(f"settling time {ts} s exceeds the bound {self.bound:.3g} s")
        elif self.regains_accuracy:
            rb = self.recovery_bound(result)
            if rb <= horizon and (ts is None or ts > rb):
                problems.append(f"accuracy regained at {ts} s, after max(T_e, T_s) + T' = {rb:.3g} s")
        return problems


def names() -> list[str]:
    """The six scenario names."""
    return list(_NAMES)


def _design(example: int, variant: str) -> tuple[dict, float, str]:
    latch = "authors" if variant == "code" else "paper"
    if example == 1:
        kw = {"order": 2, "feedback": famcc.FiniteTime(k=1.0, p=0.5), "constraint": "lateral",
                  "eps": 0.1, "k_u": 5.0, "differentiator": famcc.HighGain(0.01, [4.0, 4.0])}
        t_prime = bounds.finite_time(1.0, 0.5, -1.0)
        desc = "LaMC finite-time PPC (Corollary 1)"
    elif example == 2:
        eps_s = 0.15 if variant == "paper" else 0.225
        kw = {"order": 2, "feedback": famcc.VariableExponent(k=1.5, r_b=0.5, r_1=2.0, r_t=3.0),
                  "skew": famcc.Smooth(eps_s=eps_s, eps_z=0.1), "constraint": "longitudinal",
                  "eps": 0.15, "k_u": 2.0, "differentiator": famcc.HighGain(0.01, [4.0, 4.0])}
        t_prime = bounds.variable_exponent(1.5, 0.5, 2.0, 3.0)
        desc = "LoMC + SSMD variable-exponent fixed-time PPC (Corollary 2)"
    else:
        eps_s1, eps_y = (0.2, 5.0) if variant == "paper" else (0.1, 3.0)
        kw = {"order": 3,
                  "feedback": [famcc.FixedTime(alpha=1.0, p=0.5, beta=0.5, q=2.0),
                            famcc.FixedTime(alpha=2.0, p=0.5, beta=1.0, q=2.0)],
                  "skew": [famcc.Nonsingular(eps_s=eps_s1, eps_z=0.1, k_pp=0.1),
                        famcc.Nonsingular(eps_s=eps_y, eps_z=0.2, k_pp=1.0)],
                  "constraint": "longitudinal", "eps": eps_y, "k_u": 30.0,
                  "differentiator": famcc.HighGain(0.01, [4.0, 6.0, 4.0])}
        t_prime = bounds.fixed_time([(1.0, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)])
        desc = "LoMC + NSMD recursive fixed-time control, RFC (Corollary 3)"
    kw.update(settle_time=1.0, k0=2.0, rho_e=0.01, gamma="log", latch=latch)
    return kw, t_prime, desc


def paper(name: str, variant: str = "code") -> Scenario:
    """The paper's scenario ``name`` (see :func:`names`) in ``variant`` "paper" or "code"."""
    if name not in _NAMES:
        raise ValueError(f"name must be one of {', '.join(_NAMES)} (got {name!r})")
    if variant not in VARIANTS:
        raise ValueError(f"variant must be one of 'paper', 'code' (got {variant!r})")
    base = name.replace("-saturated", "")
    saturated = name.endswith("-saturated")
    example = {"finite-time": 1, "variable-exponent": 2, "rfc": 3}[base]
    kw, t_prime, desc = _design(example, variant)
    plant = plants.second_order(variant) if example < 3 else plants.third_order(variant)
    return Scenario(
        name=name,
        variant=variant,
        example=example,
        saturated=saturated,
        plant=plant,
        controller_kwargs=kw,
        u_limits=_LIMITS[base] if saturated else (-100.0, 100.0),
        t_end=10.0,
        eps_z=0.1,
        t_prime=t_prime,
        settle_time=1.0,
        paper_settling_time={1: 1.9, 3: 1.2}.get(example) if not saturated else None,
        regains_accuracy=not (example == 3 and saturated and variant == "paper"),
        description=desc + (" with input saturation" if saturated else ""),
    )
