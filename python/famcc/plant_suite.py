"""Deprecated home of the physical plant suite: use :mod:`famcc.plants`.

Kept so that existing imports work; every name is :mod:`famcc.plants.suite`'.
"""

from famcc.plants.model import PhysicalPlant
from famcc.plants.suite import (
    G0,
    dc_motor,
    flexible_joint,
    pendulum,
    quadrotor_altitude,
    smooth_step,
)

__all__ = [
    "G0",
    "PhysicalPlant",
    "dc_motor",
    "flexible_joint",
    "pendulum",
    "quadrotor_altitude",
    "smooth_step",
]
