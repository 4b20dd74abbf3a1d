"""The campaign itself: resolving the arguments, the draw, and the run (local, futures, Dask)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from famcc import _core
from famcc.campaigns.controller import _corollary_time, _preset_accuracy
from famcc.campaigns.dispersion import _finite, distribution
from famcc.campaigns.executors import _execute
from famcc.campaigns.plan import Campaign, _draw
from famcc.campaigns.result import CRITERIA, CampaignResult
from famcc.plants import Family, family
from famcc.plants.base import is_real as _is_number
from famcc.signals import Constant, Sine

#: Default state bound: a case whose ``|x_i|`` exceeds it counts as diverged.
STATE_BOUND = 1e6

_REFERENCE_KEYS = {"sine": ("amplitude", "omega", "phase"), "constant": ("value",)}
_CONTROLLER_KEYS = ("eps", "k_u", "settle_time", "k0", "rho_e")


def _resolve_family(fam: Any, variant: str | None) -> Family:
    if isinstance(fam, Family):
        if variant is not None:
            raise ValueError("variant only applies to a family given by name")
        return fam
    if isinstance(fam, str):
        return family(fam, variant)
    raise ValueError(
        f"family must be a famcc.plants.Family or a name such as 'second-order', got {fam!r}"
    )


def _resolve_controller(controller: Any) -> tuple[dict[str, Any], _core.ControllerSpec]:
    """The controller's configuration (data, for reports and the fingerprint) and its spec
    (what the chunks copy)."""
    if hasattr(controller, "config") and hasattr(controller, "step"):
        ctrl = controller
    elif callable(getattr(controller, "controller", None)):
        ctrl = controller.controller()  # a famcc.Design, or anything that builds one
    else:
        raise ValueError(
            "controller must be a famcc.Controller or an object whose controller() builds "
            f"one (a famcc.Design), got {controller!r}"
        )
    cfg = ctrl.config()
    if not isinstance(cfg, dict) or "order" not in cfg or "dt" not in cfg:
        raise ValueError("controller.config() must give the famcc.Controller configuration")
    spec = getattr(ctrl, "spec", None)
    if not isinstance(spec, _core.ControllerSpec):
        spec = _core.ControllerSpec.from_config(dict(cfg))
    return dict(cfg), spec


def _check_keys(fam: Family, dispersion: Mapping[str, Any], reference: Any) -> None:
    kind = "sine" if isinstance(reference, Sine) else "constant"
    states = {f"x{i + 1}(0)" for i in range(fam.order)}
    for key in dispersion:
        if key in fam.params or key in states or key == "noise.sigma":
            continue
        head, _, tail = key.partition(".")
        if head == "reference" and tail in _REFERENCE_KEYS[kind]:
            continue
        if head == "controller" and tail in _CONTROLLER_KEYS:
            continue
        raise ValueError(
            f"unknown dispersion key {key!r}: use a parameter of {fam.name} "
            f"({', '.join(fam.params) or 'none'}), an initial state "
            f"({', '.join(sorted(states))}), reference.{' / reference.'.join(_REFERENCE_KEYS[kind])}"
            f", noise.sigma or controller.{' / controller.'.join(_CONTROLLER_KEYS)}"
        )


def campaign(
    family: Family | str,
    controller: Any,
    *,
    cases: int,
    t_end: float,
    reference: Sine | Constant,
    u_limits: Sequence[float] | None = None,
    dispersion: Mapping[str, Any] | None = None,
    eps: float | None = None,
    settle_by: float | str | None = None,
    substeps: int = 1,
    noise: float = 0.0,
    seed: int = 0,
    chunk_size: int = 2000,
    executor: Any = None,
    jobs: int | None = None,
    out: str | Path | None = None,
    progress: Any = True,
    state_bound: float = STATE_BOUND,
    require: Sequence[str] = ("settled", "bounded"),
    confidence: float = 0.95,
    variant: str | None = None,
    name: str = "campaign",
) -> CampaignResult:
    """Run a Monte Carlo robustness campaign; returns a :class:`CampaignResult`.

    Parameters
    ----------
    family : famcc.plants.Family or str
        The plant family, or the name of a ready-made one
        (:func:`famcc.families.names`).
    controller : famcc.Controller or object with ``controller()``
        The design: its configuration is used (every case starts from a fresh
        controller with it), its state is not. A ``famcc.Design`` works too.
    cases : int
        Number of random cases (>= 1).
    t_end : float
        Horizon, s (rounded to whole samples as in :func:`famcc.simulate`).
    reference : famcc.Sine or famcc.Constant
        The nominal reference; ``reference.amplitude``, ``reference.omega``,
        ``reference.phase`` (or ``reference.value``) can be dispersed.
    u_limits : (lo, hi), optional
        Actuator limits; None means none.
    dispersion : dict, optional
        Key -> :class:`Uniform`, :class:`Normal`, :class:`LogUniform`,
        :class:`Choice`, a number or a table (:func:`distribution`). Keys: the
        family's parameters (``"J"``, ``"gain"``), initial states ``"x1(0)"`` ..
        ``"xn(0)"``, ``"reference.amplitude"`` / ``"reference.omega"`` /
        ``"reference.phase"`` / ``"reference.value"``, ``"noise.sigma"`` and
        controller settings ``"controller.k_u"``, ``"controller.eps"``,
        ``"controller.settle_time"``, ``"controller.k0"``, ``"controller.rho_e"``
        (each distinct setting in a chunk is its own bank: prefer :class:`Choice`).
        Undispersed quantities stay nominal.
    eps : float, optional
        Accuracy of ``|z1|`` for the settling time. Default: the controller's
        preset output accuracy (:attr:`famcc.SimResult.accuracy`); a design
        that presets none needs it.
    settle_by : float, "bound" or None
        The ``settled`` criterion's deadline: seconds; ``"bound"`` for the
        paper's corollary bound ``max(T_e, T_s) + T'`` (``T_e`` the end of the
        case's last saturation episode, ``T'`` from the laws and, for the
        finite-time law, the case's ``z1(0)``); None for "settled by the end of
        the horizon". A deadline beyond the horizon leaves the case untested.
    substeps : int
        RK4 steps per sample, as :func:`famcc.simulate`'s ``substeps`` (that
        defaults to 10; at 1 kHz one step already integrates the paper's
        plants to about 1e-10, benches/README.md "Campaign").
    noise : float
        Standard deviation of white sensor noise added to the measured error
        (in the output's unit); each case draws its own sequence.
    seed : int
        Seeds every draw: the same seed gives the same cases and results on
        every executor and for every ``chunk_size``.
    chunk_size : int
        Cases integrated together by one worker (default 2000; 10^4 is the
        fastest per case, smaller chunks balance and resume better).
    executor : None, "serial", concurrent.futures.Executor, distributed.Client or str
        Where chunks run: None for a :class:`~concurrent.futures.ProcessPoolExecutor`
        on the local cores (``jobs`` workers), ``"serial"`` for this process,
        any executor, a Dask ``distributed.Client``, or a scheduler address
        (``"tcp://host:8786"``; needs ``pip install 'famcc[cluster]'``).
    jobs : int, optional
        Worker processes of the default pool (default: the CPU count).
    out : path, optional
        Folder for finished chunks (``out/chunks/``): a rerun with the same
        configuration skips them (resume after an interruption).
    progress : bool or object with ``step(label, seconds)``
        A progress bar on stderr (:class:`famcc.reporting.Progress`) by default.
    state_bound : float
        A case whose state leaves ``|x_i| <= state_bound`` (or turns non-finite)
        is diverged: it fails every criterion, and its metrics stop there.
    require : sequence of str
        The criteria whose conjunction is a case's success (:data:`CRITERIA`).
    confidence : float
        Of the Clopper-Pearson intervals.
    variant : str, optional
        The variant of a paper family given by name.
    name : str
        Label for reports.

    Returns
    -------
    CampaignResult

    Raises
    ------
    ValueError
        For a bad argument (the message names it), or an ``out`` folder that
        holds another campaign.

    Examples
    --------
    Ten DC motors with dispersed inertia and load under one design, in this
    process:

    >>> import famcc
    >>> from famcc.campaigns import Uniform
    >>> ctrl = famcc.Controller(2, 1e-3, famcc.Linear(4.0), constraint="lateral",
    ...                         eps=0.02, k_u=20.0, settle_time=0.5)
    >>> res = campaign("dc-motor", ctrl, cases=10, t_end=2.0, u_limits=(-12.0, 12.0),
    ...                reference=famcc.Constant(0.5), settle_by=1.5, executor="serial",
    ...                dispersion={"J": Uniform(0.005, 0.02), "load": Uniform(0.0, 2.0)},
    ...                progress=False)
    >>> r = res.rate()
    >>> r.held + r.failed, r.lo <= r.rate <= r.hi
    (10, True)
    """
    fam = _resolve_family(family, variant)
    cfg, ctrl_spec = _resolve_controller(controller)
    if cfg["order"] != fam.order:
        raise ValueError(
            f"the controller's order ({cfg['order']}) must equal the family's ({fam.order})"
        )
    if not isinstance(cases, (int, np.integer)) or isinstance(cases, bool) or cases < 1:
        raise ValueError(f"cases must be an integer >= 1, got {cases!r}")
    dt = float(cfg["dt"])
    t_end = _finite("t_end", t_end)
    steps = round(t_end / dt)
    if not t_end > 0 or steps < 1:
        raise ValueError(f"t_end must be at least half a sample period dt ({dt}), got {t_end!r}")
    if not isinstance(reference, (Sine, Constant)):
        raise ValueError(  # noqa: TRY004 - bad arguments raise ValueError throughout
            "reference must be famcc.Sine(...) or famcc.Constant(...) (campaigns "
            f"disperse their parameters), got {reference!r}"
        )
    limits: tuple[float, float] | None = None
    if u_limits is not None:
        try:
            lo, hi = (float(v) for v in u_limits)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"u_limits must be None or a pair (lo, hi), got {u_limits!r}") from exc
        if not lo < hi:
            raise ValueError(f"u_limits must satisfy lo < hi, got {u_limits!r}")
        limits = (lo, hi)
    if not isinstance(substeps, (int, np.integer)) or isinstance(substeps, bool) or substeps < 1:
        raise ValueError(f"substeps must be an integer >= 1, got {substeps!r}")
    if not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size must be an integer >= 1, got {chunk_size!r}")
    if not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    noise = _finite("noise", noise)
    if noise < 0:
        raise ValueError(f"noise must be >= 0, got {noise!r}")
    state_bound = _finite("state_bound", state_bound)
    if not state_bound > 0:
        raise ValueError(f"state_bound must be > 0, got {state_bound!r}")
    req = tuple(require)
    bad = [c for c in req if c not in CRITERIA]
    if bad or not req:
        raise ValueError(f"require must name some of {', '.join(CRITERIA)}, got {list(require)!r}")
    if eps is None:
        eps = _preset_accuracy(cfg)
        if eps is None:
            raise ValueError("this controller presets no output accuracy: pass eps=")
    eps = _finite("eps", eps)
    if not eps > 0:
        raise ValueError(f"eps must be > 0, got {eps!r}")
    if not (settle_by is None or settle_by == "bound" or _is_number(settle_by)):
        raise ValueError(f"settle_by must be seconds, 'bound' or None, got {settle_by!r}")
    if settle_by == "bound":
        _corollary_time(ctrl_spec, np.zeros(1))  # raises for a design without a bound
    disp = {str(k): distribution(v) for k, v in (dispersion or {}).items()}
    _check_keys(fam, disp, reference)
    spec = Campaign(
        family=fam,
        controller=cfg,
        controller_spec=ctrl_spec,
        cases=int(cases),
        t_end=t_end,
        dt=dt,
        steps=steps,
        substeps=int(substeps),
        u_limits=limits,
        eps=eps,
        settle_by=settle_by,
        reference=reference,
        noise=noise,
        dispersion=disp,
        seed=int(seed),
        chunk_size=int(chunk_size),
        state_bound=state_bound,
        require=req,
        confidence=float(confidence),
        name=name,
        values=_draw(disp, int(seed), int(cases)),
    )
    raw = _execute(spec, executor, jobs, None if out is None else Path(out), progress)
    return CampaignResult(spec, raw)
