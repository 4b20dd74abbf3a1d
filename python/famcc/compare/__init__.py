"""``famcc compare``: famcc against PID, ADRC and LMCC on every plant under real conditions.

Every controller (``famcc``, its special case ``lmcc``, ``pid`` and ``adrc``, see
:mod:`famcc.peers`) is tuned by the same procedure (:func:`tune_budget`: the same
number of closed-loop runs and the same objective on the nominal plant), then
evaluated unchanged under every condition: nominal; saturated (tighter input
limits); measurement noise at three levels; +-30 % parameter dispersion (N
seeded random plants); 200 Hz (the nominal runs at 1 kHz). :func:`compare`
returns the numbers, :func:`write_report` writes ``report.md`` with one table
and one radar chart per plant, time series of the telling cases and a section
"Where famcc loses" computed from the numbers (:func:`losses`).

The tuning procedure
--------------------
Each controller has documented parameter ranges (:func:`space`), scaled by the
plant's nominal input gain ``G`` and holding input ``H`` and by the accuracy
band. Of a budget of ``B`` closed-loop runs on the nominal plant, the first
``B/2`` are a seeded Latin hypercube over the ranges (log-uniform where the
range spans decades), the other ``B/2`` come in rounds around the best so far
(Gaussian steps in the unit cube, halved each round). The objective is
``J = IAE / (band T) + 0.01 sum TV(u) / H + 10 [never settled]`` (``T`` the
horizon, ``TV(u)`` the input's total variation per second), ``J = 10^6`` for
a diverged run: accuracy and a quiet actuator, on the same scale for every
controller.

>>> from famcc.compare import CONDITIONS, controllers
>>> controllers()
['famcc', 'lmcc', 'pid', 'adrc']
>>> [c for c in CONDITIONS]
['nominal', 'saturated', 'noise 1e-4', 'noise 1e-3', 'noise 1e-2', 'dispersion', '200 Hz']
"""

from __future__ import annotations

from famcc.compare.builders import build as build
from famcc.compare.comparison import compare as compare
from famcc.compare.comparison import total_runs as total_runs
from famcc.compare.conditions import CONDITIONS as CONDITIONS
from famcc.compare.conditions import DISPERSION as DISPERSION
from famcc.compare.conditions import DT as DT
from famcc.compare.conditions import DT_LOW as DT_LOW
from famcc.compare.conditions import NOISE as NOISE
from famcc.compare.conditions import QUICK_CONDITIONS as QUICK_CONDITIONS
from famcc.compare.conditions import RK4_STEP as RK4_STEP
from famcc.compare.conditions import condition_of as condition_of
from famcc.compare.findings import LOSS_FACTOR as LOSS_FACTOR
from famcc.compare.findings import LOSS_METRICS as LOSS_METRICS
from famcc.compare.findings import RADAR as RADAR
from famcc.compare.findings import loss_text as loss_text
from famcc.compare.findings import losses as losses
from famcc.compare.findings import radar_scores as radar_scores
from famcc.compare.plants import Case as Case
from famcc.compare.plants import cases as cases
from famcc.compare.plants import make_plant as make_plant
from famcc.compare.report import write_report as write_report
from famcc.compare.runs import TV_WEIGHT as TV_WEIGHT
from famcc.compare.runs import metrics as metrics
from famcc.compare.runs import run as run
from famcc.compare.spaces import PAPER_K_U as PAPER_K_U
from famcc.compare.spaces import Space as Space
from famcc.compare.spaces import controllers as controllers
from famcc.compare.spaces import famcc_candidates as famcc_candidates
from famcc.compare.spaces import space as space
from famcc.compare.tuning import tune_budget as tune_budget

__all__ = [
    "CONDITIONS",
    "Case",
    "Space",
    "cases",
    "compare",
    "controllers",
    "famcc_candidates",
    "losses",
    "radar_scores",
    "space",
    "write_report",
]
