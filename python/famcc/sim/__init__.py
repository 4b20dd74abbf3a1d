"""The one simulator: a sample-and-hold loop (famcc-sim, compiled) and its record.

=====================  ==================================================
module                 what it owns
=====================  ==================================================
:mod:`.engine`         the loop as seen from Python (``famcc._core.Lockstep``)
:mod:`.simulate`       :func:`simulate`: one plant, one controller
:mod:`.joints`         :func:`simulate_joints`: one controller per joint
:mod:`.post`           the true error vector and ``-F/G`` after the loop
:mod:`.result`         :class:`SimResult`: the record and its metrics
:mod:`.views`          its text, HTML, PNG and data frame
=====================  ==================================================
"""

from famcc.sim.result import SimResult
from famcc.sim.simulate import SUBSTEPS, simulate

__all__ = ["SUBSTEPS", "SimResult", "simulate"]
