"""A family is N plants of one definition (issue 31): for every ready-made family and
every dispersible parameter, the family's right-hand side, the simulator's lanes and the
scalar plant of each member compute the same numbers, and the parameter acts.

Each parameter is moved on its own, away from its nominal value (an offset where the
nominal value is 0, so a parameter that one path drops cannot hide behind a zero), at
random states, inputs and times that cover the loads' switching times.
"""

from __future__ import annotations

import math

import famcc
import numpy as np
import pytest
from famcc.campaigns import Uniform, campaign
from famcc.plants import family, names

#: Times from 0 to 10 s, past every nominal and moved switching time.
TIMES = np.linspace(0.0, 10.0, 81)


def _moved(nominal: float, rng: np.random.Generator, m: int) -> np.ndarray:
    """``m`` values away from ``nominal`` (never equal to it), of its sign."""
    if nominal == 0.0:
        return rng.uniform(0.5, 3.0, size=m)
    return nominal * rng.uniform(1.3, 2.0, size=m)


def _lanes_rhs(lanes, t, x, u):
    if isinstance(lanes, tuple):
        kind, fn = lanes
        assert kind == "lanes"
        return np.asarray(fn(t, x, u))
    return np.asarray(lanes.rhs(t, x, u))


@pytest.mark.parametrize("name", names())
def test_every_dispersible_parameter_reaches_the_family_lanes_and_plant(name):
    fam = family(name)
    rng = np.random.default_rng(31)
    n, m = fam.order, 8
    assert fam.params, name
    # Every parameter away from nominal (a load's switching time acts only with a load),
    # then each one moved further on its own.
    base = {k: float(_moved(v, rng, 1)[0]) for k, v in fam.params.items()}
    for key, value in base.items():
        values = _moved(value, rng, m)
        p = {**base, key: values}
        x = rng.uniform(-1.5, 1.5, size=(n, m))
        u = rng.uniform(-4.0, 4.0, size=m)
        lanes = fam.lanes(p, m)
        acts = False
        for t in TIMES:
            dx = fam.rhs(t, x, u, p)
            np.testing.assert_array_equal(_lanes_rhs(lanes, t, x, u), dx, err_msg=f"{key} t={t}")
            acts |= not np.array_equal(dx, fam.rhs(t, x, u, base))
            for i in range(0, m, 3):
                plant = fam.plant(x0=x[:, i], **{**base, key: float(values[i])})
                scalar = plant.rhs_fast(t, x[:, i].tolist(), float(u[i]))
                assert np.array_equal(dx[:, i], np.array(scalar)), (name, key, t, i)
        assert acts, f"{name}: parameter {key} changes nothing (dropped?)"


def test_dc_motor_load_step_acts_in_the_family_as_in_the_plant():
    """The regression of issue 31: the vectorised dc-motor ignored load_step."""
    motors = family("dc-motor")
    x, u = np.array([[0.1], [0.2]]), np.array([1.0])
    base = motors.rhs(4.0, x, u)[1, 0]
    stepped = motors.rhs(4.0, x, u, {"load_step": np.array([8.0])})[1, 0]
    plant = motors.plant(load_step=8.0).rhs(4.0, np.array([0.1, 0.2]), 1.0)[1]
    assert stepped == plant
    # 8 N m more load on J = 0.01 kg m^2: 800 rad/s^2 less acceleration.
    assert stepped == pytest.approx(base - 8.0 / motors.params["J"], rel=1e-12)


def test_a_campaign_with_a_load_step_reproduces_its_case():
    """The campaign row and ``res.case(0).simulate()`` agree with a load step (they did
    not: the row said 0.0 % saturated, settled at 2.758 s; the case 39.7 %, never)."""
    motor = famcc.Controller(
        2, 1e-3, famcc.Linear(4.0), constraint="lateral", eps=0.02, k_u=20.0, settle_time=0.5
    )
    res = campaign(
        "dc-motor",
        motor,
        cases=3,
        t_end=5.0,
        u_limits=(-12.0, 12.0),
        reference=famcc.Constant(0.5),
        executor="serial",
        progress=False,
        dispersion={"load_step": Uniform(7.0, 9.0), "t_step": Uniform(2.0, 3.0)},
        seed=3,
    )
    for i in range(res.n):
        row = res.row(i)
        sim = res.case(i).simulate()
        assert sim.saturated_fraction == row["saturated_fraction"], i
        st = sim.settling_time(res.spec.eps)
        assert (math.nan if st is None else st) == pytest.approx(
            row["settling_time"], nan_ok=True, abs=0.0
        ), i
        assert row["saturated_fraction"] > 0.05, i  # 8 N m needs about 32 V: the limits bite
