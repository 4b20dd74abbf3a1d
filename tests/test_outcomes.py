"""Measured closed-loop outcomes against committed values: a 10 % regression fails.

The paper-claim tests (test_invariants, test_verdicts) check the theorems' bounds,
which are 2-7x looser than what famcc measures, so a controller twice as slow would
still pass them. These tests pin what the runs *measure* -- settling time, first
entry, max nominal |xi|, the input range, the final error -- for the paper's six
scenarios in both variants and for a fixed suite of random plants of the paper's
class, against ``tests/outcomes.json``, with the tolerances of :data:`TOL`.

Regenerate the committed values after an intended change of behaviour (and say
why in the commit)::

    python tests/test_outcomes.py --update
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Any

import famcc
import numpy as np
import pytest
from famcc.simulation import Sine

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from runs import scenario_run
from test_invariants import make_plant

# random-4 stays expanded with headroom 73 % of the time (issue 13: rho_e = 0.01
# loses accuracy on random plants of the paper's class): its health warning is expected.
pytestmark = pytest.mark.filterwarnings("ignore:k_u too small:famcc.DesignWarning")

VALUES = HERE / "outcomes.json"

#: metric -> (relative, absolute) tolerance; a value passes when it is within either.
TOL: dict[str, tuple[float, float]] = {
    "horizon": (0.0, 1e-9),
    "settling_time": (0.05, 2e-3),  # 5 %, or two samples at 1 kHz
    "first_entry": (0.05, 2e-3),
    "max_abs_xi_nominal": (0.02, 1e-3),
    "u_min": (0.05, 0.05),
    "u_max": (0.05, 0.05),
    "final_abs_z1": (0.10, 2e-3),  # max |z1| over the last second
    "saturated_fraction": (0.0, 0.01),  # one percentage point
}

#: A fixed suite of random plants of the paper's class (strict feedback, gains in
#: [0.8, 1.2] x g0, bounded disturbances): seed, order, design, limits.
RANDOM_SUITE = [
    (1, 2, "finite-time", (-100.0, 100.0)),
    (2, 2, "finite-time", (-100.0, 100.0)),
    (3, 2, "variable-exponent", (-100.0, 100.0)),
    (4, 2, "variable-exponent", (-100.0, 100.0)),
    (5, 2, "finite-time", (-4.0, 4.0)),
    (6, 3, "rfc", (-100.0, 100.0)),
    (7, 3, "rfc", (-100.0, 100.0)),
]


def _random_case(seed: int, order: int) -> tuple[Any, Sine]:
    rng = np.random.default_rng(seed)
    stages = [
        {
            "g0": rng.uniform(0.5, 3.0),
            "ga": rng.uniform(0.0, 0.2),
            "gw": rng.uniform(0.2, 3.0),
            "gj": int(rng.integers(0, i + 1)),
            "damp": rng.uniform(0.1, 1.0),
            "da": rng.uniform(0.0, 2.0),
            "dw": rng.uniform(0.2, 3.0),
            "dp": rng.uniform(0.0, 2 * math.pi),
            "nl": rng.uniform(0.0, 0.3),
        }
        for i in range(order)
    ]
    x0 = list(rng.uniform(-1.5, 1.5, size=order))
    ref = Sine(rng.uniform(0.2, 1.5), rng.uniform(0.2, 2.0), rng.uniform(0.0, 2 * math.pi))
    return make_plant(stages, x0), ref


def _metrics(res: famcc.SimResult, eps: float) -> dict[str, float | None]:
    t = res.t
    return {
        "horizon": float(t[-1]),
        "settling_time": res.settling_time(eps),
        "first_entry": res.first_entry(eps),
        "max_abs_xi_nominal": res.max_abs_xi_nominal,
        "u_min": res.u_min,
        "u_max": res.u_max,
        "final_abs_z1": float(np.max(np.abs(res.z1[t >= t[-1] - 1.0]))),
        "saturated_fraction": res.saturated_fraction,
    }


def scenario_cases() -> list[str]:
    return [f"{n}/{v}" for v in ("code", "paper") for n in famcc.scenarios.names()]


def random_cases() -> list[str]:
    return [f"random-{seed}-order{order}-{name}" for seed, order, name, _ in RANDOM_SUITE]


def measure(case: str) -> dict[str, float | None]:
    if case.startswith("random-"):
        seed, order, name, limits = next(
            c for c in RANDOM_SUITE if case == f"random-{c[0]}-order{c[1]}-{c[2]}"
        )
        plant, ref = _random_case(seed, order)
        ctrl = famcc.scenarios.paper(name, "code").controller(dt=1e-3)
        reference = [(lambda t, k=k: ref(t, k)) for k in range(order)]
        res = famcc.simulate(plant, ctrl, 8.0, reference=reference, u_limits=limits, substeps=4)
        return _metrics(res, 0.1)
    name, variant = case.split("/")
    return _metrics(scenario_run(name, variant), famcc.scenarios.paper(name, variant).eps_z)


def _committed() -> dict[str, dict[str, float | None]]:
    data: dict[str, dict[str, float | None]] = json.loads(VALUES.read_text())["cases"]
    return data


def _close(metric: str, got: float | None, want: float | None) -> bool:
    if got is None or want is None:
        return got is None and want is None
    rel, tol = TOL[metric]
    return abs(got - want) <= max(tol, rel * abs(want))


@pytest.mark.parametrize("case", scenario_cases() + random_cases())
def test_measured_outcome_matches_the_committed_value(case):
    want = _committed()[case]
    got = measure(case)
    bad = {m: (got[m], want[m]) for m in TOL if not _close(m, got[m], want[m])}
    assert not bad, f"{case}: measured vs committed (tolerances {TOL}): {bad}"


def test_every_case_is_committed():
    assert sorted(_committed()) == sorted(scenario_cases() + random_cases())


def test_the_tolerance_would_catch_a_ten_percent_slower_loop():
    """The settling-time tolerance is below a 10 % regression for every settling case."""
    for case, values in _committed().items():
        ts = values["settling_time"]
        if ts is not None and ts > 0.1:
            assert not _close("settling_time", 1.1 * ts, ts), case


if __name__ == "__main__" and "--update" in sys.argv:
    cases = {c: measure(c) for c in scenario_cases() + random_cases()}
    VALUES.write_text(
        json.dumps({"tolerances": TOL, "cases": cases}, indent=1, sort_keys=True) + "\n"
    )
    print(f"wrote {len(cases)} cases to {VALUES}")
