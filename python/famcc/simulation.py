"""Deprecated home of the simulator: use :mod:`famcc.sim` (``famcc.simulate``) and
:mod:`famcc.signals` (``famcc.Sine``, ``famcc.Constant``).

Kept so that existing imports work.
"""

from famcc.signals import Constant, Sine
from famcc.sim.result import SimResult
from famcc.sim.simulate import simulate
from famcc.summary import Summary

__all__ = ["Constant", "SimResult", "Sine", "Summary", "simulate"]
