"""The conditions of ``famcc compare``: the sample rates, the limits, the noise, the dispersion."""

from __future__ import annotations

from typing import Any

#: The conditions, in table order (``"1 kHz"`` is the nominal column: the design rate).
CONDITIONS = (
    "nominal",
    "saturated",
    "noise 1e-4",
    "noise 1e-3",
    "noise 1e-2",
    "dispersion",
    "200 Hz",
)
QUICK_CONDITIONS = ("nominal", "saturated", "noise 1e-3", "dispersion", "200 Hz")
NOISE = {"noise 1e-4": 1e-4, "noise 1e-3": 1e-3, "noise 1e-2": 1e-2}
#: The nominal sample period (1 kHz) and the low rate of the "200 Hz" condition, s.
DT, DT_LOW = 1e-3, 5e-3
#: Largest RK4 step of the plant integration (s): 2 substeps per sample at 1 kHz.
RK4_STEP = 5e-4
#: Parameter dispersion: every physical parameter times U(1 - D, 1 + D).
DISPERSION = 0.3


def condition_of(name: str) -> dict[str, Any]:
    """``dt``, which limits and the noise level of a condition (dispersion is per plant)."""
    if name not in CONDITIONS:
        raise ValueError(f"condition must be one of {', '.join(CONDITIONS)}, got {name!r}")
    return {
        "dt": DT_LOW if name == "200 Hz" else DT,
        "limits": "saturated" if name == "saturated" else "limits",
        "noise": NOISE.get(name, 0.0),
    }
