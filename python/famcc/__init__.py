"""famcc: fully actuated manifold constraint control.

A model-free output-feedback controller (Mu, Hua, Li, Chen, Wei) that drives
the tracking error of an unknown strict-feedback plant to a preset accuracy
within a preset time and keeps working when the actuator saturates. The law
runs in a compiled, allocation-free Rust core (``famcc._core``). Requires
CPython >= 3.11; ``famcc.__version__`` (``famcc --version``) is the installed
version. The documentation site (``mkdocs serve``; ``docs/getting-started.md``)
has a getting-started guide and the API reference.

>>> import famcc
>>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
...                         constraint="lateral", eps=0.1, k_u=5.0)
>>> round(ctrl.step(-1.0), 4)
5.4931

Any run can be seen and explained: ``famcc.simulate(...)`` returns a
:class:`SimResult` whose ``plot()`` draws the figure of ``famcc reproduce``,
whose ``summary()`` gives the metrics in plain words, and
``famcc.report(results, out=DIR)`` writes a markdown report for a list of runs.
``famcc.campaign(...)`` runs a Monte Carlo robustness campaign over a dispersed plant
family (:mod:`famcc.campaigns`) and judges every case.
"""

from famcc import bounds, envelope, plants, scenarios, transition
from famcc._common import DefaultReferenceWarning, DesignWarning, FamccWarning, Signal
from famcc._core import (
    MAX_ORDER,
    ConfigError,
    Controller,
    ControllerBank,
    Diagnostics,
    FiniteTime,
    FixedTime,
    HighGain,
    Linear,
    MoulayDiscontinuous,
    Nonsingular,
    Observer,
    Skewed,
    Smooth,
    StepError,
    VariableExponent,
    __version__,
    manifold,
    skewed,
)
from famcc.campaigns import CampaignResult, campaign
from famcc.reporting import report, reproduce
from famcc.signals import Constant, Sine
from famcc.sim import SimResult, simulate
from famcc.summary import Summary
from famcc.tuning import Design, Finding, design, tune

__all__ = [
    "MAX_ORDER",
    "CampaignResult",
    "ConfigError",
    "Constant",
    "Controller",
    "ControllerBank",
    "DefaultReferenceWarning",
    "Design",
    "DesignWarning",
    "Diagnostics",
    "FamccWarning",
    "Finding",
    "FiniteTime",
    "FixedTime",
    "HighGain",
    "Linear",
    "MoulayDiscontinuous",
    "Nonsingular",
    "Observer",
    "Signal",
    "SimResult",
    "Sine",
    "Skewed",
    "Smooth",
    "StepError",
    "Summary",
    "VariableExponent",
    "__version__",
    "bounds",
    "campaign",
    "design",
    "envelope",
    "manifold",
    "plants",
    "report",
    "reproduce",
    "scenarios",
    "simulate",
    "skewed",
    "transition",
    "tune",
]


def __getattr__(name: str) -> object:
    # Heavier submodules load on first use: famcc.plot, famcc.interop, famcc.compare, ...
    import importlib

    if name in {"plot", "interop", "cli", "compare", "peers", "joints"}:
        return importlib.import_module(f"famcc.{name}")
    raise AttributeError(f"module 'famcc' has no attribute {name!r}")
