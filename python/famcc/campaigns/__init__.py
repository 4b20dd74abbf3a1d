"""Monte Carlo robustness campaigns: thousands of dispersed plants, in lockstep.

:func:`campaign` draws ``cases`` random members of a plant family
(:class:`famcc.plants.Family`), initial states, references, sensor noise and,
optionally, controller settings; it integrates them in chunks, each chunk a
:class:`famcc.ControllerBank` and a vectorised RK4 with exactly the
sample-and-hold of :func:`famcc.simulate`, on the local cores, any
:class:`concurrent.futures.Executor` or a Dask cluster. The
:class:`CampaignResult` holds one row per case and judges each case on the
claims a run can fail (docs/design.md §8): ``settled`` (within the deadline),
``bounded`` (did not diverge), ``nominal`` (no flexible expansion while the
actuator had headroom) and ``unsaturated``; it gives the success rates with
Clopper-Pearson intervals, the worst cases, figures and a report, and
:meth:`CampaignResult.case` rebuilds any case for :func:`famcc.simulate`.

Semantics, per case and sample ``t_k = k dt`` (``k = 0..K-1``, ``K = round(t_end
/ dt) + 1``), the same as :func:`famcc.simulate`: the controller reads ``e_k =
y(t_k) - y_d(t_k)`` (plus the sensor noise ``n_k``, when there is noise), returns
``v_k``; ``u_k = clip(v_k, u_limits)`` is held over ``[t_k, t_k + dt)`` while
the plant is integrated with ``substeps`` classical RK4 steps. Metrics use the
true error ``z1 = y - y_d``, never the noisy measurement.

Examples
--------
>>> import famcc
>>> from famcc.campaigns import Uniform, campaign
>>> ctrl = famcc.scenarios.paper("finite-time").controller()
>>> res = campaign("second-order", ctrl, cases=40, t_end=4.0, u_limits=(-100, 100),
...                reference=famcc.Sine(), eps=0.1, settle_by="bound",
...                dispersion={"gain": Uniform(0.7, 1.3), "x1(0)": Uniform(-1.5, 0.5)},
...                executor="serial", chunk_size=20, progress=False)
>>> res.rate("settled").tested, res.rate("bounded").held
(40, 40)
>>> row = res.row(3)
>>> sim = res.case(3).simulate()
>>> sim.settling_time(0.1) == row["settling_time"], sim.saturated_fraction == row["saturated_fraction"]
(True, True)
"""

from __future__ import annotations

from famcc.campaigns.chunk import run_chunk
from famcc.campaigns.dispersion import (
    Choice,
    Distribution,
    Fixed,
    LogUniform,
    Normal,
    Uniform,
    distribution,
)
from famcc.campaigns.noise import NoisySensor, noise_keys, standard_normal
from famcc.campaigns.plan import Campaign
from famcc.campaigns.result import CRITERIA, CampaignResult, Case
from famcc.campaigns.run import STATE_BOUND, campaign
from famcc.campaigns.spec import load_spec, run_spec
from famcc.campaigns.stats import Rate, beta_cdf, beta_ppf, clopper_pearson

__all__ = [
    "CRITERIA",
    "STATE_BOUND",
    "Campaign",
    "CampaignResult",
    "Case",
    "Choice",
    "Distribution",
    "Fixed",
    "LogUniform",
    "NoisySensor",
    "Normal",
    "Rate",
    "Uniform",
    "beta_cdf",
    "beta_ppf",
    "campaign",
    "clopper_pearson",
    "distribution",
    "load_spec",
    "noise_keys",
    "run_chunk",
    "run_spec",
    "standard_normal",
]
