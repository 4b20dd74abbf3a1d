"""Campaigns from TOML specs (``famcc campaign SPEC.toml``)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from famcc import _core, scenarios
from famcc.campaigns.result import CampaignResult
from famcc.campaigns.run import campaign
from famcc.signals import Constant, Sine


def _law(spec: Any, kind: str) -> Any:
    if not isinstance(spec, Mapping) or kind not in spec:
        raise ValueError(
            f"a {kind} must be a table with {kind} = NAME and its parameters, got {spec!r}"
        )
    rest = dict(spec)
    name = rest.pop(kind)
    allowed = {
        "law": ("Linear", "FiniteTime", "FixedTime", "VariableExponent"),
        "skew": ("Smooth", "Nonsingular"),
    }[kind]
    if name not in allowed:
        raise ValueError(f"{kind} must be one of {', '.join(allowed)}, got {name!r}")
    return getattr(_core, name)(**rest)


def _controller_from_spec(spec: Mapping[str, Any], dt: float) -> Any:
    kw = dict(spec)
    scenario = kw.pop("scenario", None)
    variant = kw.pop("variant", "code")
    if "feedback" in kw:
        fb = kw["feedback"]
        kw["feedback"] = [_law(f, "law") for f in fb] if isinstance(fb, list) else _law(fb, "law")
    if "skew" in kw:
        sk = kw["skew"]
        kw["skew"] = [_law(f, "skew") for f in sk] if isinstance(sk, list) else _law(sk, "skew")
    if isinstance(kw.get("differentiator"), Mapping):
        kw["differentiator"] = _core.HighGain(**kw["differentiator"])
    if "eps" in kw and isinstance(kw["eps"], list):
        kw["eps"] = tuple(kw["eps"])
    if scenario is not None:
        return scenarios.paper(scenario, variant).controller(dt, **kw)
    if "order" not in kw:
        raise ValueError("[controller] needs scenario = NAME or order and the design's settings")
    order = kw.pop("order")
    return _core.Controller(order, dt, **kw)


def load_spec(path: str | Path) -> dict[str, Any]:
    """Reads a campaign spec (TOML) into the keyword arguments of :func:`campaign`.

    The format (``examples/campaigns/*.toml``; every table but ``[plant]`` and
    ``[controller]`` is optional)::

        name = "rfc-saturated"
        cases = 10000
        seed = 3
        t_end = 10.0
        dt = 0.001
        substeps = 1
        u_limits = [-7.0, 9.0]
        chunk_size = 2500

        [plant]
        family = "third-order"
        variant = "code"

        [controller]              # a paper scenario's design, with overrides,
        scenario = "rfc-saturated"  # or order = 2, feedback = {law = "FiniteTime", k = 1,
        variant = "code"            # p = 0.5}, constraint = ..., eps = ..., k_u = ...

        [criteria]
        eps = 0.1
        settle_by = "horizon"     # seconds, "bound" or "horizon"
        require = ["settled", "bounded"]

        [reference]
        kind = "sine"             # amplitude, omega, phase; or kind = "constant", value
        amplitude = 1.0

        [noise]
        sigma = 0.0

        [dispersion.plant]        # the family's parameters
        gain = {uniform = [0.8, 1.2]}
        [dispersion.x0]           # initial states x1, x2, ...
        x1 = {uniform = [0.5, 1.5]}
        [dispersion.reference]    # amplitude, omega, phase or value
        omega = {uniform = [0.8, 1.2]}
        [dispersion.controller]   # eps, k_u, settle_time, k0, rho_e
        k_u = {choice = [25.0, 30.0]}
        [dispersion.noise]
        sigma = {uniform = [0.0, 0.001]}

    Raises
    ------
    ValueError
        For an unknown key or a bad value (naming it).
    """
    import tomllib

    path = Path(path)
    try:
        doc = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML: {exc}") from exc
    top = {
        "name",
        "description",
        "cases",
        "seed",
        "t_end",
        "dt",
        "substeps",
        "u_limits",
        "chunk_size",
        "state_bound",
        "confidence",
        "plant",
        "controller",
        "criteria",
        "reference",
        "noise",
        "dispersion",
    }
    unknown = sorted(set(doc) - top)
    if unknown:
        raise ValueError(f"{path}: unknown keys {unknown}; known: {sorted(top)}")
    for need in ("cases", "t_end", "plant", "controller"):
        if need not in doc:
            raise ValueError(f"{path}: missing {need!r}")
    plant = dict(doc["plant"])
    fam = plant.pop("family", None)
    if fam is None:
        raise ValueError(f"{path}: [plant] needs family = NAME")
    variant = plant.pop("variant", None)
    if plant:
        raise ValueError(f"{path}: unknown keys {sorted(plant)} in [plant]")
    dt = float(doc.get("dt", 1e-3))
    ctrl = _controller_from_spec(doc["controller"], dt)
    crit = dict(doc.get("criteria", {}))
    settle_by = crit.pop("settle_by", "horizon")
    settle_by = None if settle_by == "horizon" else settle_by
    kw: dict[str, Any] = {
        "family": fam,
        "variant": variant,
        "controller": ctrl,
        "cases": doc["cases"],
        "t_end": doc["t_end"],
        "name": doc.get("name", path.stem),
        "eps": crit.pop("eps", None),
        "settle_by": settle_by,
        "require": tuple(crit.pop("require", ("settled", "bounded"))),
    }
    if crit:
        raise ValueError(f"{path}: unknown keys {sorted(crit)} in [criteria]")
    for key in ("seed", "substeps", "chunk_size", "state_bound", "confidence"):
        if key in doc:
            kw[key] = doc[key]
    if "u_limits" in doc:
        kw["u_limits"] = tuple(doc["u_limits"])
    ref = dict(doc.get("reference", {"kind": "sine"}))
    kind = ref.pop("kind", "sine")
    if kind == "sine":
        kw["reference"] = Sine(**ref)
    elif kind == "constant":
        kw["reference"] = Constant(**ref)
    else:
        raise ValueError(f"{path}: [reference] kind must be 'sine' or 'constant', got {kind!r}")
    noise = dict(doc.get("noise", {}))
    kw["noise"] = float(noise.pop("sigma", 0.0))
    if noise:
        raise ValueError(f"{path}: unknown keys {sorted(noise)} in [noise]")
    disp: dict[str, Any] = {}
    for group, table in dict(doc.get("dispersion", {})).items():
        if not isinstance(table, Mapping):
            raise ValueError(f"{path}: [dispersion.{group}] must be a table")  # noqa: TRY004
        for key, value in table.items():
            if group == "plant":
                disp[key] = value
            elif group == "x0":
                if not (key.startswith("x") and key[1:].isdigit()):
                    raise ValueError(f"{path}: [dispersion.x0] keys are x1, x2, ..., got {key!r}")
                disp[f"{key}(0)"] = value
            elif group in ("reference", "controller", "noise"):
                disp[f"{group}.{key}"] = value
            else:
                raise ValueError(
                    f"{path}: unknown table [dispersion.{group}] (plant, x0, "
                    "reference, controller, noise)"
                )
    kw["dispersion"] = disp
    return kw


def run_spec(
    path: str | Path,
    out: str | Path,
    *,
    executor: Any = None,
    jobs: int | None = None,
    progress: Any = True,
    figures: bool = True,
) -> tuple[CampaignResult, Path]:
    """Runs a TOML spec (:func:`load_spec`) with its chunks in ``out/``; writes the report.

    Returns the result and the path of ``out/report.md``.
    """
    kw = load_spec(path)
    res = campaign(executor=executor, jobs=jobs, out=out, progress=progress, **kw)
    return res, res.write(out, figures=figures)
