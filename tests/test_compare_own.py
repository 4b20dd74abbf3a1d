"""famcc compare on a plant the project does not contain (``own_cases``), issue 32.

The cart is written as an engineer writes one: a negative input gain (the motor
wired backwards), ``np.tanh`` friction and a step load switched by an ``if``.
"""

from __future__ import annotations

import functools

import famcc
import numpy as np
import pytest
from famcc import compare as cmp


class Cart(famcc.plants.Plant):
    def __init__(self, m: float = 2.0, c: float = 0.5, load: float = 1.0) -> None:
        super().__init__(2, [0.0, 0.0], name="cart", output=("position", "m"))
        self.m, self.c, self.load = m, c, load

    def rhs(self, t, x, u):
        load = self.load if t >= 2.0 else 0.0
        return np.array([x[1], (-u - self.c * np.tanh(5.0 * x[1]) - load) / self.m])


CART = cmp.Case(
    "cart",
    "a cart, input reversed, tanh friction, step load at 2 s",
    2,
    1,
    (0.5,),
    4.0,
    0.01,
    ((-5.0, 5.0),),
    ((-2.0, 2.0),),
    (-0.5,),
    (1.5,),
    "finite-time",
    {"m": 2.0, "c": 0.5, "load": 1.0},
    "m",
    "N",
    factory=Cart,
)


@functools.cache
def result(jobs: int):
    return cmp.compare(quick=True, jobs=jobs, case_names=[], own_cases=[CART], dispersion_plants=2)


@pytest.mark.parametrize("jobs", [1, 2])
def test_compare_runs_an_own_plant_by_the_same_procedure(jobs):
    res = result(jobs)
    assert res["meta"]["cases"] == ["cart"]
    runs = res["runs"]["cart"]
    for kind in cmp.controllers():
        assert len(res["tuned"]["cart"][kind]["history"]) == res["meta"]["budget"]
        assert set(runs[kind]) == set(res["meta"]["conditions"])
    # the reversed input is handled by every controller that is told the gain
    for kind in ("famcc", "pid", "adrc"):
        m = runs[kind]["nominal"]
        assert not m["diverged"] and not m["never_settled"], (kind, m)
    # every controller runs on the reversed input (Case.as_positive): b0 = |G|
    assert res["tuned"]["cart"]["famcc"]["params"][0]["b0"] == 0.5


def test_the_processes_agree_with_one_process():
    a, b = result(1), result(2)
    for kind in cmp.controllers():
        assert a["tuned"]["cart"][kind]["u"] == b["tuned"]["cart"][kind]["u"]
        assert (
            a["runs"]["cart"][kind]["nominal"]["iae"] == b["runs"]["cart"][kind]["nominal"]["iae"]
        )


def test_the_report_covers_an_own_plant(tmp_path):
    md = cmp.write_report(result(1), tmp_path, figures=False).read_text()
    assert "## cart" in md and "a cart, input reversed" in md


def test_bad_own_cases_are_named():
    import dataclasses

    with pytest.raises(ValueError, match="factory"):
        cmp.compare(quick=True, case_names=[], own_cases=[dataclasses.replace(CART, factory=None)])
    with pytest.raises(ValueError, match="taken"):
        cmp.compare(quick=True, own_cases=[dataclasses.replace(CART, name="dc-motor")])
    with pytest.raises(ValueError, match="one entry per joint"):
        cmp.compare(quick=True, case_names=[], own_cases=[dataclasses.replace(CART, joints=2)])
    with pytest.raises(ValueError, match="no case"):
        cmp.compare(quick=True, case_names=[])


def test_a_negative_gain_reverses_the_input_for_every_controller():
    from famcc.compare.plants import _Bare

    seen = CART.as_positive()
    assert seen.gain == (0.5,) and seen.limits == ((-5.0, 5.0),)
    assert seen.saturated == ((-2.0, 2.0),) and seen.as_positive() is seen
    lopsided = cmp.Case(**{**CART.__dict__, "limits": ((-1.0, 3.0),)}).as_positive()
    assert lopsided.limits == ((-3.0, 1.0),)
    plant = Cart()
    x = np.array([0.1, -0.2])
    np.testing.assert_array_equal(_Bare(plant, True).rhs(2.5, x, 0.7), plant.rhs(2.5, x, -0.7))
    np.testing.assert_array_equal(_Bare(plant).rhs(2.5, x, 0.7), plant.rhs(2.5, x, 0.7))
    assert cmp.space("pid", CART).fixed["gain"] == 0.5
