"""Tests of famcc.plants: the paper's plants, exact output derivatives, G_a and F_a."""

from __future__ import annotations

import math

import numpy as np
import pytest
from famcc import plants
from famcc.plants.jets import Jet

PAPER_PLANTS = [
    pytest.param(plants.second_order, "paper", id="second-paper"),
    pytest.param(plants.second_order, "code", id="second-code"),
    pytest.param(plants.third_order, "paper", id="third-paper"),
    pytest.param(plants.third_order, "code", id="third-code"),
]


# -- helpers --------------------------------------------------------------------------


def rk4_trajectory(plant, x0, t0, u, h, steps):
    """Fine fixed-step RK4 with a constant input; returns times and states."""
    ts = t0 + h * np.arange(steps + 1)
    xs = np.empty((steps + 1, len(x0)))
    x = np.array(x0, dtype=float)
    xs[0] = x
    for j in range(steps):
        t = ts[j]
        k1 = plant.rhs(t, x, u)
        k2 = plant.rhs(t + h / 2, x + h / 2 * k1, u)
        k3 = plant.rhs(t + h / 2, x + h / 2 * k2, u)
        k4 = plant.rhs(t + h, x + h * k3, u)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        xs[j + 1] = x
    return ts, xs


def fd_weights(offsets, order):
    """Central finite-difference weights for the ``order``-th derivative (unit spacing)."""
    offsets = np.asarray(offsets, dtype=float)
    m = len(offsets)
    vander = np.vander(offsets, m, increasing=True).T  # row k: offsets**k
    rhs = np.zeros(m)
    rhs[order] = math.factorial(order)
    return np.linalg.solve(vander, rhs)


def fd_derivative(y, stride, h, order, half_width=4):
    """Derivative ``order`` of samples ``y[::stride]`` (spacing ``stride * h``) at interior points.

    Returns the indices (into ``y``) where it was evaluated and the values.
    """
    offsets = np.arange(-half_width, half_width + 1)
    w = fd_weights(offsets, order)
    spacing = stride * h
    centres = np.arange(half_width * stride, len(y) - half_width * stride, stride)
    vals = (
        np.array([sum(wj * y[c + oj * stride] for wj, oj in zip(w, offsets)) for c in centres])
        / spacing**order
    )
    return centres, vals


# -- paper plants: equations and variants -------------------------------------------------


def paper_second_rhs(t, x, u, amp):
    """Independent transcription of paper eq. System_sim (amp = 1 paper, 3 authors' code)."""
    x1, x2 = x
    return np.array(
        [
            (1 + 0.1 * np.cos(x1) + 0.1 * np.sin(t)) * x2 - x1 + np.sin(t),
            (2 + 0.2 * np.sin(x1 * x2) + 0.1 * np.cos(t)) * u
            - (x1**2 - 1) * x2
            + amp * np.sin(t)
            + amp * np.cos(2 * t),
        ]
    )


def paper_third_rhs(t, x, u):
    """Paper eq. System_sim3 with the factor x2 restored in x1'."""
    x1, x2, x3 = x
    return np.array(
        [
            (1 + 0.1 * np.sin(x1) + 0.1 * np.cos(t)) * x2 - x1 + np.cos(t),
            (1 + 0.1 * np.cos(x1 * x2) + 0.1 * np.sin(t)) * x3 - (x1**2 - 1) * x2 + np.sin(t),
            (2 + 0.2 * np.sin(x1 * x2 * x3) + 0.1 * np.cos(t)) * u
            - (x1**2 + x2) * x3
            + 10 * np.sin(t)
            + 10 * np.cos(2 * t),
        ]
    )


def test_second_order_matches_the_equations_of_both_variants():
    rng = np.random.default_rng(1)
    for variant, amp in (("paper", 1.0), ("code", 3.0)):
        plant = plants.second_order(variant)
        assert (plant.order, plant.name, plant.variant) == (2, "second-order", variant)
        np.testing.assert_array_equal(plant.x0, [-1.0, 0.5])
        for _ in range(20):
            t, x, u = rng.uniform(0, 10), rng.normal(size=2) * 2, rng.normal() * 5
            np.testing.assert_allclose(
                plant.rhs(t, x, u), paper_second_rhs(t, x, u, amp), rtol=1e-13, atol=1e-13
            )


def test_second_order_variants_differ_only_by_the_disturbance_amplitude():
    paper, code = plants.second_order("paper"), plants.second_order("code")
    rng = np.random.default_rng(2)
    for _ in range(20):
        t, x, u = rng.uniform(0, 10), rng.normal(size=2), rng.normal()
        diff = code.rhs(t, x, u) - paper.rhs(t, x, u)
        expected = [0.0, 2 * math.sin(t) + 2 * math.cos(2 * t)]
        np.testing.assert_allclose(diff, expected, atol=1e-12)
    np.testing.assert_array_equal(paper.x0, code.x0)


def test_third_order_matches_the_equations_and_variants_differ_only_in_x0():
    paper, code = plants.third_order("paper"), plants.third_order("code")
    np.testing.assert_array_equal(paper.x0, [1.0, -0.2, 0.4])
    np.testing.assert_array_equal(code.x0, [1.0, 0.5, 4.0])
    assert (paper.order, paper.name) == (3, "third-order")
    rng = np.random.default_rng(3)
    for _ in range(20):
        t, x, u = rng.uniform(0, 10), rng.normal(size=3), rng.normal() * 5
        np.testing.assert_allclose(
            paper.rhs(t, x, u), paper_third_rhs(t, x, u), rtol=1e-13, atol=1e-12
        )
        np.testing.assert_array_equal(paper.rhs(t, x, u), code.rhs(t, x, u))


def test_third_order_restores_the_x2_gain_so_the_plant_is_controllable():
    plant = plants.third_order()
    t, x = 0.7, np.array([0.3, 0.0, 0.0])
    # with x2 = 0 the gain term vanishes; d x1'/d x2 = g1 > 0
    assert plant.rhs(t, x, 0.0)[0] == pytest.approx(-0.3 + math.cos(t))
    slope = plant.rhs(t, x + [0, 1, 0], 0.0)[0] - plant.rhs(t, x, 0.0)[0]
    assert slope == pytest.approx(1 + 0.1 * math.sin(0.3) + 0.1 * math.cos(t))


@pytest.mark.parametrize("factory", [plants.second_order, plants.third_order])
@pytest.mark.parametrize("bad", ["Paper", "authors", "", "matlab"])
def test_unknown_variant_raises_naming_the_allowed_values(factory, bad):
    with pytest.raises(ValueError, match="variant") as info:
        factory(bad)
    assert "'paper'" in str(info.value) and "'code'" in str(info.value)


def test_default_variant_is_code():
    assert plants.second_order().variant == "code"
    assert plants.third_order().variant == "code"


def test_x0_is_a_fresh_float_copy():
    plant = plants.third_order()
    x0 = plant.x0
    assert x0.dtype == np.float64
    x0[:] = 99.0
    np.testing.assert_array_equal(plant.x0, [1.0, 0.5, 4.0])


def test_repr_names_plant_and_variant():
    text = repr(plants.second_order("paper"))
    assert "second-order" in text and "paper" in text


# -- exact derivatives against finite differences of a fine simulation ---------------------


@pytest.mark.parametrize(("factory", "variant"), PAPER_PLANTS)
def test_output_derivatives_match_finite_differences_of_a_trajectory(factory, variant):
    plant = factory(variant)
    n = plant.order
    h, stride = 1e-4, 50  # RK4 step; finite differences on a 5 ms grid
    ts, xs = rk4_trajectory(plant, plant.x0, 0.3, 0.4, h, 2000)
    exact = np.array([plant.output_derivatives(t, x) for t, x in zip(ts, xs)])
    np.testing.assert_array_equal(exact[:, 0], xs[:, 0])
    for k in range(1, n):
        idx, approx = fd_derivative(xs[:, 0], stride, h, k)
        scale = 1.0 + np.max(np.abs(exact[idx, k]))
        err = np.max(np.abs(approx - exact[idx, k])) / scale
        assert err < 1e-10, (k, err)  # measured <= 1e-11


@pytest.mark.parametrize(("factory", "variant"), PAPER_PLANTS)
def test_gain_and_drift_predict_the_nth_derivative_for_two_inputs(factory, variant):
    plant = factory(variant)
    n = plant.order
    h, stride = 1e-4, 50
    for u in (-2.0, 3.0):
        ts, xs = rk4_trajectory(plant, plant.x0, 1.1, u, h, 2000)
        idx, approx = fd_derivative(xs[:, 0], stride, h, n)
        predicted = []
        for i in idx:
            gain, drift = plant.gain_and_drift(ts[i], xs[i])
            predicted.append(gain * u + drift)
        predicted = np.array(predicted)
        err = np.max(np.abs(approx - predicted)) / (1.0 + np.max(np.abs(predicted)))
        assert err < 5e-8, (u, err)  # measured <= 7e-9


def paper_oracle(order, gain, amp):
    """The paper's equations restated here, as the generic strict-feedback plant: an
    independent oracle for famcc-paper's closed forms (eq. System_sim, System_sim3 with
    the factor x2 restored)."""
    sin, cos, b, a = np.sin, np.cos, gain, amp
    if order == 2:
        g = [
            lambda x, t: 1.0 + 0.1 * cos(x[0]) + 0.1 * sin(t),
            lambda x, t: b * (2.0 + 0.2 * sin(x[0] * x[1]) + 0.1 * cos(t)),
        ]
        f = [
            lambda x, t: -x[0] + sin(t),
            lambda x, t: -(x[0] * x[0] - 1.0) * x[1] + a * sin(t) + a * cos(2.0 * t),
        ]
    else:
        g = [
            lambda x, t: 1.0 + 0.1 * sin(x[0]) + 0.1 * cos(t),
            lambda x, t: 1.0 + 0.1 * cos(x[0] * x[1]) + 0.1 * sin(t),
            lambda x, t: b * (2.0 + 0.2 * sin(x[0] * x[1] * x[2]) + 0.1 * cos(t)),
        ]
        f = [
            lambda x, t: -x[0] + cos(t),
            lambda x, t: -(x[0] * x[0] - 1.0) * x[1] + sin(t),
            lambda x, t: -(x[0] * x[0] + x[1]) * x[2] + a * sin(t) + a * cos(2.0 * t),
        ]
    return plants.StrictFeedback(g, f, np.zeros(order))


@pytest.mark.parametrize(("factory", "variant"), PAPER_PLANTS)
def test_closed_forms_agree_with_the_generic_jet_computation(factory, variant):
    rng = np.random.default_rng(4)
    for _ in range(25):
        gain, amp = rng.uniform(0.5, 2.0), rng.uniform(0.0, 12.0)
        plant = factory(variant, gain=gain, amp=amp)
        oracle = paper_oracle(plant.order, gain, amp)
        t, x = rng.uniform(0, 10), rng.normal(size=plant.order) * 2
        np.testing.assert_allclose(
            plant.output_derivatives(t, x), oracle.output_derivatives(t, x), rtol=1e-12, atol=1e-12
        )
        np.testing.assert_allclose(
            plant.gain_and_drift(t, x), oracle.gain_and_drift(t, x), rtol=1e-12, atol=1e-11
        )
        np.testing.assert_allclose(
            plant.rhs(t, x, 0.7), oracle.rhs(t, x, 0.7), rtol=1e-13, atol=1e-13
        )


@pytest.mark.parametrize(("factory", "variant"), PAPER_PLANTS)
def test_total_gain_is_the_product_of_the_gains(factory, variant):
    plant = factory(variant)
    oracle = paper_oracle(plant.order, 1.0, plant.params["amp"])
    t, x = 0.4, plant.x0
    gain, _ = plant.gain_and_drift(t, x)
    expected = np.prod([g(x, t) for g in oracle.g])
    assert gain == pytest.approx(expected, rel=1e-14)
    assert gain > 0


def test_fast_rhs_equals_rhs():
    for plant in (plants.second_order(), plants.third_order("paper")):
        x = plant.x0 + 0.3
        assert tuple(plant.rhs(1.3, x, -0.8)) == plant.rhs_fast(1.3, list(x), -0.8)


# -- the generic strict-feedback plant ------------------------------------------------------


def jet_friendly_fourth_order():
    """A 4th-order strict-feedback plant written with NumPy ufuncs (accepts jets)."""
    g = [
        lambda x, t: 1.0 + 0.2 * np.tanh(x[0]) + 0.1 * np.sin(t),
        lambda x, t: 2.0 + np.cos(x[0] * x[1]) * 0.3,
        lambda x, t: np.exp(0.1 * np.sin(x[2] + t)),
        lambda x, t: 1.5 + 0.1 * np.arctan(x[3] * x[0]),
    ]
    f = [
        lambda x, t: -x[0] + np.sqrt(1.0 + x[0] ** 2) * 0.1,
        lambda x, t: -(x[0] ** 2) * x[1] / (2.0 + np.cos(t)),
        lambda x, t: np.log(2.0 + x[1] ** 2) - x[2],
        lambda x, t: -x[3] + 2.0 * np.sin(2.0 * t) + x[0] * x[2],
    ]
    return plants.StrictFeedback(g, f, [0.3, -0.2, 0.5, 0.1], name="toy4")


def test_generic_plant_exact_derivatives_of_order_four():
    plant = jet_friendly_fourth_order()
    h, stride = 1e-4, 100  # a 1e-2 grid keeps the 4th difference above round-off
    ts, xs = rk4_trajectory(plant, plant.x0, 0.0, 0.5, h, 3000)
    exact = np.array([plant.output_derivatives(t, x) for t, x in zip(ts, xs)])
    for k in range(1, 4):
        idx, approx = fd_derivative(xs[:, 0], stride, h, k)
        err = np.max(np.abs(approx - exact[idx, k])) / (1 + np.max(np.abs(exact[idx, k])))
        assert err < 3e-9, (k, err)  # measured <= 3e-10
    idx, approx = fd_derivative(xs[:, 0], stride, h, 4)
    pred = np.array([np.dot(plant.gain_and_drift(ts[i], xs[i]), (0.5, 1.0)) for i in idx])
    # measured 4e-8: the 4th difference is near its round-off floor
    assert np.max(np.abs(approx - pred)) / (1 + np.max(np.abs(pred))) < 4e-7


def test_generic_plant_with_float_only_callables_supports_order_two():
    g = [lambda x, t: 1.0 + 0.1 * math.cos(x[0]), lambda x, t: 2.0]
    f = [lambda x, t: -x[0] + math.sin(t), lambda x, t: -x[1]]
    plant = plants.StrictFeedback(g, f, [0.2, 0.1])
    t, x = 0.5, np.array([0.2, 0.1])
    np.testing.assert_allclose(
        plant.output_derivatives(t, x), [0.2, (1 + 0.1 * math.cos(0.2)) * 0.1 - 0.2 + math.sin(0.5)]
    )
    with pytest.raises(NotImplementedError, match="jets"):
        plant.gain_and_drift(t, x)


def test_generic_plant_with_float_only_callables_of_order_three_says_what_is_missing():
    g = [lambda x, t: 1.0, lambda x, t: 1.0, lambda x, t: 1.0 + 0.5 * math.cos(x[0])]
    f = [lambda x, t: math.sin(x[0]), lambda x, t: 0.0, lambda x, t: 0.0]
    plant = plants.StrictFeedback(g, f, [0.0, 0.0, 0.0])
    with pytest.raises(NotImplementedError, match="np.sin"):
        plant.output_derivatives(0.0, plant.x0)
    assert plant.rhs(0.0, np.array([0.0, 1.0, 2.0]), 4.0).tolist() == [1.0, 2.0, 6.0]


def test_generic_plant_of_order_one():
    plant = plants.StrictFeedback([lambda x, t: 2.0 + math.sin(t)], [lambda x, t: -x[0]], [1.5])
    assert plant.output_derivatives(0.0, plant.x0).tolist() == [1.5]
    assert plant.gain_and_drift(0.0, plant.x0) == (2.0, -1.5)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"g": [], "f": [], "x0": []}, "g and f"),
        ({"g": [lambda x, t: 1.0], "f": [], "x0": [0.0]}, "g and f"),
        ({"g": [1.0], "f": [lambda x, t: 0.0], "x0": [0.0]}, "callable"),
        ({"g": [lambda x, t: 1.0], "f": [lambda x, t: 0.0], "x0": [0.0, 1.0]}, "x0"),
        ({"g": [lambda x, t: 1.0], "f": [lambda x, t: 0.0], "x0": [math.nan]}, "x0"),
    ],
)
def test_generic_plant_rejects_bad_arguments(kwargs, match):
    with pytest.raises(ValueError, match=match):
        plants.StrictFeedback(**kwargs)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"g": lambda x, t: 1.0, "f": [lambda x, t: 0.0]}, "g"),
        ({"g": [lambda x, t: 1.0], "f": lambda x, t: 0.0}, "f"),
        ({"g": 2.0, "f": [lambda x, t: 0.0]}, "g"),
        ({"g": [lambda x, t: 1.0], "f": "x**2"}, "f"),
    ],
)
def test_generic_plant_asks_for_one_callable_per_state(kwargs, name):
    # A single callable (or a number or a string) where a sequence is meant:
    # the error names the argument and shows the expected form.
    with pytest.raises(TypeError, match=rf"^{name} must be a sequence of callables, one per state"):
        plants.StrictFeedback(x0=[0.0], **kwargs)


def test_base_plant_reports_what_it_cannot_do():
    plant = plants.Plant(1, [0.0], name="bare")
    with pytest.raises(NotImplementedError):
        plant.rhs(0.0, plant.x0, 0.0)
    with pytest.raises(NotImplementedError):
        plant.output_derivatives(0.0, plant.x0)
    with pytest.raises(NotImplementedError):
        plant.gain_and_drift(0.0, plant.x0)


# -- jets -------------------------------------------------------------------------------


def test_jet_derivatives_of_elementary_functions():
    jet = Jet
    t0 = 0.4
    t = jet([t0, 1.0, 0.0, 0.0, 0.0])

    def fun(s):
        return (
            np.exp(np.sin(s)) * np.sqrt(1.0 + s * s) / (2.0 + np.cos(s))
            + np.tanh(s) ** 3
            + np.arctan(s)
            - np.log(1.0 + s * s)
            + s**2.5
            - 3.0 / s
        )

    derivs = fun(t).derivatives()
    assert derivs[0] == pytest.approx(fun(t0), rel=1e-14)
    h = 1e-2
    samples = np.array([fun(t0 + k * h) for k in range(-4, 5)])
    for k in range(1, 5):
        approx = fd_weights(np.arange(-4, 5), k) @ samples / h**k
        assert approx == pytest.approx(derivs[k], rel=1e-5, abs=1e-6), k


def test_jet_sin_of_square_has_the_textbook_derivatives():
    t0 = 0.7
    d = np.sin(Jet([t0, 1.0, 0.0, 0.0]) ** 2).derivatives()
    s, c = math.sin(t0**2), math.cos(t0**2)
    expected = [s, 2 * t0 * c, 2 * c - 4 * t0**2 * s, -12 * t0 * s - 8 * t0**3 * c]
    np.testing.assert_allclose(d, expected, rtol=1e-13)


def test_jets_refuse_silent_conversion_to_float():
    with pytest.raises(TypeError):
        math.sin(Jet([0.1, 1.0]))
    with pytest.raises(TypeError):
        np.sign(Jet([0.1, 1.0]))
