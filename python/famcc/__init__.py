"""famcc: fully actuated manifold constraint control.

A model-free output-feedback controller (Mu, Hua, Li, Chen, Wei) that drives
the tracking error of an unknown strict-feedback plant to a preset accuracy
within a preset time and keeps working when the actuator saturates. The law
runs in a compiled, allocation-free Rust core (``famcc._core``).

>>> import famcc
>>> ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5),
...                         constraint="lateral", eps=0.1, k_u=5.0)
>>> round(ctrl.step(-1.0), 4)
5.4931
"""

from famcc import bounds, envelope, plants, scenarios, transition
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
    Skewed,
    Smooth,
    StepError,
    VariableExponent,
    __version__,
    manifold,
    skewed,
)
from famcc.simulate import SimResult, simulate

__all__ = [
    "MAX_ORDER",
    "ConfigError",
    "Controller",
    "ControllerBank",
    "Diagnostics",
    "FiniteTime",
    "FixedTime",
    "HighGain",
    "Linear",
    "MoulayDiscontinuous",
    "Nonsingular",
    "SimResult",
    "Skewed",
    "Smooth",
    "StepError",
    "VariableExponent",
    "__version__",
    "bounds",
    "envelope",
    "manifold",
    "plants",
    "scenarios",
    "simulate",
    "skewed",
    "transition",
]


def __getattr__(name: str):
    # Heavier submodules load on first use: famcc.plot, famcc.interop.
    import importlib

    if name in {"plot", "interop", "reference", "cli"}:
        return importlib.import_module(f"famcc.{name}")
    raise AttributeError(f"module 'famcc' has no attribute {name!r}")
