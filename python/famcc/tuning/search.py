"""Tuning by simulation: :func:`tune` refines a :func:`design` on the user's plant."""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

from famcc import _core, sim
from famcc._common import DesignWarning
from famcc.progress import Progress
from famcc.signals import Constant, reference_table
from famcc.tuning import measure, observed
from famcc.tuning.assess import assess
from famcc.tuning.rules import Design, Finding, Trial, design

#: The search grid of :func:`tune`: phase budgets (rad), envelope fractions of
#: the settling time, and differentiator time constants in samples.
BUDGETS = (0.5, 0.8, 1.1, 1.3, 1.5)
FRACTIONS = (0.3, 0.5, 0.7)
MU_SAMPLES = (10.0, 15.0, 22.0)
#: A feasible candidate has margin when it settles by ``MARGIN_TIME settle_time``
#: with the steady error below ``MARGIN_ERROR eps``; :func:`tune` prefers those.
MARGIN_TIME, MARGIN_ERROR = 0.85, 0.7
#: RK4 substeps per sample of the search's runs (the chosen candidate is confirmed
#: with the simulator's default 10), and how many candidates to confirm at most.
SEARCH_SUBSTEPS, CONFIRM = 2, 4
#: What :func:`tune` minimises among the candidates that meet the requirement.
OBJECTIVES = ("accuracy", "smooth", "effort")
_OBJECTIVE_TEXT = {
    "accuracy": "the least IAE",
    "smooth": "the least total variation of u, ripple penalised",
    "effort": "the least mean |u|",
}


class _Lean:
    """A plant seen without its exact output derivatives: tuning runs need only
    ``z1`` (the error), not the true error vector, and skip the jets."""

    def __init__(self, plant: Any) -> None:
        self._plant = plant
        self.order = plant.order
        self.rhs = plant.rhs
        for name in ("rhs_fast", "advance"):
            method = getattr(plant, name, None)
            if callable(method):
                setattr(self, name, method)

    @property
    def x0(self) -> Any:
        """The plant's initial state, read afresh for every run (a black box resets)."""
        return self._plant.x0

    def output_derivatives(self, t: float, x: Any) -> Any:
        raise NotImplementedError("not needed for tuning")

    def gain_and_drift(self, t: float, x: Any) -> Any:
        raise NotImplementedError("not needed for tuning")


def _derivatives_only(reference: Any, order: int) -> Any:
    """``y_d .. y_d^(n-1)`` as a sequence of callables: enough for the loop, and
    the simulator then skips ``-F/G``."""
    if isinstance(reference, (list, tuple)):
        return list(reference)[:order]
    return [(lambda t, k=k: reference(t, k)) for k in range(order)]


class _Noisy:
    """A controller seen through seeded white measurement noise on ``e``."""

    def __init__(self, ctrl: Any, std: float, seed: int) -> None:
        import numpy as np

        self.ctrl, self.std = ctrl, std
        self.rng = np.random.default_rng(seed)
        self.dt, self.order = ctrl.dt, ctrl.order

    def step(self, e: float, applied: float | None = None) -> float:
        return float(
            self.ctrl.step(e + self.std * float(self.rng.standard_normal()), applied=applied)
        )

    @property
    def diagnostics(self) -> Any:
        return self.ctrl.diagnostics


def tune(
    plant: Any,
    *,
    dt: float,
    u_limits: Sequence[float],
    eps: float,
    settle_time: float,
    reference: Any = None,
    noise_std: float = 0.0,
    t_end: float | None = None,
    hold_input: float | None = None,
    gain: float | None = None,
    integral: bool | None = None,
    seed: int = 0,
    progress: bool = True,
    objective: str = "accuracy",
) -> Design:
    """A design that meets the requirements on ``plant``, found by simulation.

    It starts from :func:`design` and measures the plant by experiments
    (:mod:`famcc.tuning.measure`), unless ``gain`` and ``hold_input`` are given
    or a :class:`famcc.plants.PhysicalPlant` knows them:

    - the input gain ``G`` at ``x0``, with its sign, from ``gain_and_drift``
      where the plant has it and from input pulses where it does not (a plant
      with an ``if`` in its load, a table, a simulator, a black box); it sets
      the control direction and designs a first, measuring run;
    - the signed gain of largest ``|G|`` along that run, and the holding input
      at the reference in steady state: the plant's equilibrium on a constant
      set point (Newton on its ``rhs`` or ``advance``), else the input over the
      run's settled stretch (a second run if the first did not settle, and a
      warning if neither did). Each is taken 20 % over the measured value.

    A gain that is zero at ``x0`` or changes sign along the run, or a
    measuring run that diverges, is a :class:`famcc.ConfigError` naming
    ``gain`` that says what to give instead. It then simulates a grid of
    candidates from the rules (phase budget x envelope fraction x
    differentiator speed) and searches famcc with the extended observer
    beyond them (:mod:`famcc.tuning.observed`), and keeps the feasible
    candidate best by ``objective``, preferring those with margin. A candidate
    is feasible when :func:`famcc.tuning.assess` finds that its run settles to
    ``eps`` within ``settle_time`` and stays there, the bounds never expand
    while the actuator has headroom after settling, and the input's steady
    oscillation is at most 5 % of the input range.

    Parameters
    ----------
    plant : famcc.plants.Plant
        Any plant :func:`famcc.simulate` takes (``rhs`` or ``advance``, a
        :class:`famcc.plants.BlackBox`); nothing more is needed.
    dt, u_limits, eps, settle_time, noise_std
        As for :func:`design`.
    reference : optional
        As for :func:`famcc.simulate` (default: hold the initial output,
        ``famcc.Constant(y(0))``).
    t_end : float, optional
        Horizon of each run (default ``2 settle_time + 1`` s).
    hold_input, gain : float, optional
        Override the measured values (``gain`` with its sign: negative for a
        plant whose output falls as its input rises).
    integral : bool, optional
        As for :func:`design`.
    seed : int
        Seed of the measurement noise.
    progress : bool
        Show a progress bar on stderr.
    objective : {"accuracy", "smooth", "effort"}
        What the choice minimises among the candidates that meet the
        requirement: IAE, the total variation of ``u`` (ripple penalised) or
        the mean ``|u|``.

    Returns
    -------
    Design
        With ``trials`` (every :class:`Trial`, in order) and ``choice`` (why this
        one) set; its ``checks`` gain a finding ``tune`` that fails when no
        candidate met every requirement.
    """
    import numpy as np

    lo, hi = (float(v) for v in u_limits)
    horizon = float(t_end) if t_end is not None else 2.0 * float(settle_time) + 1.0
    if reference is None:
        reference = Constant(float(np.asarray(plant.x0, dtype=float)[0]))
    order = int(plant.order)

    lean, lean_ref = _Lean(plant), _derivatives_only(reference, order)
    max_error = _max_error(plant, reference, order, horizon)

    def run(d: Design, measure: bool = False, substeps: int = SEARCH_SUBSTEPS) -> Any:
        with warnings.catch_warnings():  # a candidate's health warnings are its verdict's
            warnings.simplefilter("ignore", DesignWarning)
            ctrl: Any = d.controller()
            if noise_std:
                ctrl = _Noisy(ctrl, noise_std, seed)
            try:
                if measure:  # the first run measures G and -F/G along the trajectory
                    return sim.simulate(
                        plant, ctrl, horizon, reference=reference, u_limits=(lo, hi)
                    )
                return sim.simulate(
                    lean, ctrl, horizon, reference=lean_ref, u_limits=(lo, hi), substeps=substeps
                )
            except (FloatingPointError, ValueError, OverflowError):
                return None

    limits = (lo, hi)
    g = gain if gain is not None else getattr(plant, "gain", None)
    h = (
        hold_input
        if hold_input is not None
        else (plant.hold_input() if hasattr(plant, "hold_input") else None)
    )
    hold_warning = None
    if g is None or h is None:
        g, h, hold_warning = measure.measure(
            plant,
            g,
            h,
            run,
            limits,
            dt,
            order,
            eps,
            settle_time,
            noise_std,
            integral,
            max_error,
            reference,
            horizon,
        )
    if hold_warning:
        warnings.warn(hold_warning, DesignWarning, stacklevel=2)
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be one of {', '.join(OBJECTIVES)}, got {objective!r}")
    knobs = [(b, f, m) for b in BUDGETS for f in FRACTIONS for m in MU_SAMPLES[:1]]
    total = len(knobs) + 2 * (len(MU_SAMPLES) - 1) + observed.BUDGET
    bar = Progress(total, "famcc.tune") if progress else None
    trials: list[tuple[Trial, Design]] = []

    def attempt(b: float, f: float, m: float) -> None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DesignWarning)
            d = design(
                order,
                dt,
                u_limits=(lo, hi),
                eps=eps,
                settle_time=settle_time,
                hold_input=float(h),
                gain=float(g),
                noise_std=noise_std,
                integral=integral,
                max_error=max_error,
                phase_budget=b,
                settle_fraction=f,
                mu_per_dt=m,
            )
        res = run(d)
        trial = _judge(
            res,
            {"phase_budget": b, "settle_fraction": f, "mu_per_dt": m},
            eps,
            settle_time,
            (lo, hi),
        )
        trials.append((trial, d))
        if bar is not None:
            bar.step(
                f"B={b:g} T_s={f:g} mu={m:g}dt: " + ("ok" if trial.feasible else trial.reason[:40])
            )

    for b, f, m in knobs:
        attempt(b, f, m)
    ranked = sorted(trials, key=lambda td: _score(td[0], objective))
    for trial, _ in ranked[:2]:
        for m in MU_SAMPLES[1:]:
            attempt(trial.knobs["phase_budget"], trial.knobs["settle_fraction"], m)
    start = ranked[0][1]
    b0 = float(g) if gain is not None or hasattr(plant, "gain") else float(g) / measure.MARGIN

    def observe(p: dict[str, Any]) -> tuple[float, float]:
        try:
            with warnings.catch_warnings():  # its lint findings are the run's to judge
                warnings.simplefilter("ignore", DesignWarning)
                d = observed.candidate(start, p, dt, limits)
        except (_core.ConfigError, ValueError):
            return (math.inf, math.inf)
        knobs = {k: float(v) for k, v in p.items() if isinstance(v, (int, float))}
        trial = _judge(run(d), {**knobs, "observer": 1.0}, eps, settle_time, limits)
        trials.append((trial, d))
        if bar is not None:
            bar.step(f"observer k={p['k']:.3g}: " + ("ok" if trial.feasible else trial.reason[:40]))
        return _score(trial, objective)

    space = observed.requirement_space(order, dt, eps, settle_time, b0, float(h), limits)
    observed.search(space, observe, seed)
    feasible = [t for t, _ in trials if t.feasible]
    roomy = [td for td in trials if _has_margin(td[0], eps, settle_time)]
    # The search integrates coarsely (SEARCH_SUBSTEPS); the choice is confirmed with
    # the simulator's default integration, falling back to the next candidates.
    confirmed = 0
    for trial, cand in sorted(roomy or trials, key=lambda td: _score(td[0], objective))[:CONFIRM]:
        full = _judge(run(cand, substeps=10), trial.knobs, eps, settle_time, (lo, hi))
        confirmed += 1
        if full.feasible or not trial.feasible:
            break
    best_trial, best = full, cand
    why = (
        f"{len(feasible)} of {len(trials)} candidates met every requirement, {len(roomy)} "
        f"with margin (settled by {MARGIN_TIME:g} settle_time, steady error below "
        f"{MARGIN_ERROR:g} eps); chose the best by objective {objective!r} ("
        + _OBJECTIVE_TEXT[objective]
        + ") among "
        + ("those with margin" if roomy else "the feasible ones")
        + ": "
        + (
            "famcc with the extended observer"
            if best_trial.knobs.get("observer")
            else "the rules' design"
        )
        + f", IAE {best_trial.metrics['iae']:.4g}, total variation of u {best_trial.metrics['effort']:.3g}"
        f"/s, ripple {100 * best_trial.metrics['ripple']:.2f} % of the range; confirmed "
        f"by a finely integrated run ({confirmed} tried)"
        if best_trial.feasible
        else f"no candidate of {len(trials)} met every requirement; chose the closest: "
        f"{best_trial.reason}"
    )
    finding = Finding(
        "tune",
        "ok" if best_trial.feasible else "fail",
        "a simulated candidate meets every requirement",
        float(len(feasible)),
        float(len(trials)),
        math.nan,
        why,
    )
    if not best_trial.feasible:
        warnings.warn(f"famcc.tune: {why}", DesignWarning, stacklevel=2)
    return Design(
        {**best.requirements, "measured_gain": g, "measured_hold_input": h},
        best.parameters,
        (*best.checks, finding),
        tuple(t for t, _ in trials),
        why,
        spec=best.spec,
    )


def _judge(
    res: Any, knobs: dict[str, float], eps: float, settle_time: float, limits: tuple[float, float]
) -> Trial:
    import numpy as np

    a = assess(res, eps=eps, settle_time=settle_time, u_limits=limits)
    m = a.metrics()
    if res is None:
        m["iae"], m["mean_abs_u"] = math.inf, math.inf
    else:  # the objectives: IAE, and the mean |u| (the input spent)
        m["iae"] = float(np.sum(np.abs(np.asarray(res.z1)))) * float(res.dt)
        m["mean_abs_u"] = float(np.mean(np.abs(np.asarray(res.u))))
    return Trial(knobs, m, a.ok, "; ".join(a.failures))


def _has_margin(t: Trial, eps: float, settle_time: float) -> bool:
    ts = t.metrics.get("settling_time")
    return (
        t.feasible
        and ts is not None
        and ts <= MARGIN_TIME * settle_time
        and t.metrics["steady_error"] < MARGIN_ERROR * eps
    )


def _max_error(plant: Any, reference: Any, order: int, horizon: float) -> float:
    """The largest ``|y(0) - y_d(t)|`` over the horizon: the error if the plant stood
    still, a bound on what the loop must recover from (floored at a tiny value)."""
    import numpy as np

    y0 = float(np.asarray(plant.x0, dtype=float)[0])
    table, _ = reference_table(reference, order, np.linspace(0.0, horizon, 201))
    return max(float(np.max(np.abs(y0 - table[:, 0]))), 1e-9)


def _score(t: Trial, objective: str = "accuracy") -> tuple[float, float]:
    """Feasible first (0), else the number of failed requirements; then the
    objective: IAE (``"accuracy"``), TV(u) with a ripple penalty
    (``"smooth"``) or the mean ``|u|`` (``"effort"``)."""
    m = t.metrics
    if objective == "accuracy":
        value = m.get("iae", math.inf)
    elif objective == "smooth":
        value = m.get("effort", math.inf) * (1.0 + 10.0 * m.get("ripple", 0.0))
    else:
        value = m.get("mean_abs_u", math.inf)
    if t.feasible:
        return (0.0, value)
    return (float(t.reason.count(";") + 1), value)
