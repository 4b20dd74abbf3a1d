"""Every bad input raises a clear error and leaves existing controllers usable.

Each case runs next to a controller that has already taken some steps and its
untouched twin: after the error the controller's state and diagnostics are
unchanged, and it keeps stepping exactly like the twin.

Configuration errors are ``famcc.ConfigError`` (a ``ValueError``) whose message
names the parameter; errors of a step are ``famcc.StepError`` (a ``ValueError``);
unknown keywords and values of the wrong Python type are ``TypeError`` naming the
keyword / argument (the argument's name is in the message or, on Python >= 3.11,
in the exception's notes, which tracebacks print).
"""

from __future__ import annotations

import copy
import math
import re

import famcc
import numpy as np
import pytest

NAN, INF = math.nan, math.inf
L = famcc.FiniteTime(k=1.0, p=0.5)
NS = famcc.Nonsingular(eps_s=0.1, eps_z=0.1, k_pp=0.1)
WARMUP = (-1.0, -0.98, -0.95, -0.9)


def _text(exc: BaseException) -> str:
    """The message plus any notes (pyo3 names the failing argument in a note)."""
    return " ".join([str(exc), *getattr(exc, "__notes__", [])])


def _warm(ctrl: famcc.Controller) -> famcc.Controller:
    for e in WARMUP:
        ctrl.step(e)
    return ctrl


@pytest.fixture(params=["finite-time", "rfc", "rfc-f32"])
def pair(request):
    """A controller that has taken some steps, and its twin."""
    name, _, f32 = request.param.partition("-f")
    kw = {"dtype": "float32"} if f32 else {}
    ctrl = _warm(famcc.scenarios.paper(name).controller(**kw))
    twin = copy.copy(ctrl)
    yield ctrl, twin
    assert_same(ctrl, twin)


def assert_same(ctrl: famcc.Controller, twin: famcc.Controller) -> None:
    """Same state and diagnostics now, and the same outputs from here on."""
    assert np.array_equal(ctrl.state(), twin.state())
    assert repr(ctrl.diagnostics) == repr(twin.diagnostics)
    assert ctrl.diagnostics.v == twin.diagnostics.v
    for e in (-0.85, -0.8, -0.7):
        assert ctrl.step(e) == twin.step(e)
    z = [0.1] * ctrl.order
    assert ctrl.step_state(z) == twin.step_state(z)
    assert np.array_equal(ctrl.state(), twin.state())


# -- step-time errors ------------------------------------------------------------

STEP_ERRORS = [
    ("step nan", lambda c: c.step(NAN), "finite"),
    ("step +inf", lambda c: c.step(INF), "finite"),
    ("step -inf", lambda c: c.step(-INF), "finite"),
    ("step applied nan", lambda c: c.step(0.1, applied=NAN), "applied"),
    ("step applied inf", lambda c: c.step(0.1, INF), "applied"),
    ("step_dt e nan", lambda c: c.step_dt(NAN, 1e-3), "finite"),
    ("step_dt dt 0", lambda c: c.step_dt(0.1, 0.0), "dt"),
    ("step_dt dt < 0", lambda c: c.step_dt(0.1, -1e-3), "dt"),
    ("step_dt dt nan", lambda c: c.step_dt(0.1, NAN), "dt"),
    ("step_dt dt inf", lambda c: c.step_dt(0.1, INF), "dt"),
    ("step_dt applied nan", lambda c: c.step_dt(0.1, 1e-3, applied=NAN), "applied"),
    ("step_state nan", lambda c: c.step_state([NAN] + [0.0] * (c.order - 1)), "finite"),
    ("step_state inf last", lambda c: c.step_state([0.0] * (c.order - 1) + [INF]), "finite"),
    ("step_state applied", lambda c: c.step_state([0.0] * c.order, applied=-INF), "applied"),
    (
        "step_state too short",
        lambda c: c.step_state([0.1] * (c.order - 1)),
        r"z must have \d entries",
    ),
    (
        "step_state too long",
        lambda c: c.step_state([0.1] * (c.order + 1)),
        r"z must have \d entries",
    ),
    ("step_state empty", lambda c: c.step_state([]), r"z must have \d entries"),
    ("step_state strings", lambda c: c.step_state(["a"] * c.order), "sequence of floats"),
    ("step_state str", lambda c: c.step_state("abc"), "sequence of floats"),
]


@pytest.mark.parametrize("case", STEP_ERRORS, ids=[c[0] for c in STEP_ERRORS])
def test_step_errors_raise_step_error_and_change_nothing(pair, case):
    ctrl, _ = pair
    _, call, pattern = case
    time = ctrl.time
    with pytest.raises(famcc.StepError, match=pattern) as info:
        call(ctrl)
    assert isinstance(info.value, ValueError)
    assert ctrl.time == time


def test_non_finite_first_sample_does_not_latch():
    ctrl = famcc.scenarios.paper("finite-time").controller()
    twin = copy.copy(ctrl)
    for bad in (NAN, INF, -INF):
        with pytest.raises(famcc.StepError, match="state unchanged"):
            ctrl.step(bad)
    assert ctrl.state()[0] == 0.0  # not started
    assert_same(ctrl, twin)


def test_step_without_differentiator_points_to_step_state():
    ctrl = famcc.Controller(2, 1e-3, L, constraint="lateral", eps=0.1, k_u=5.0, differentiator=None)
    twin = copy.copy(ctrl)
    with pytest.raises(famcc.StepError, match="step_state"):
        ctrl.step(0.5)
    with pytest.raises(famcc.StepError, match="step_state"):
        ctrl.step_dt(0.5, 1e-3)
    assert ctrl.step_state([0.5, 0.0]) == twin.step_state([0.5, 0.0])


TYPE_ERRORS = [
    ("step str", lambda c: c.step("0.1"), "e"),
    ("step None", lambda c: c.step(None), "e"),
    ("step list", lambda c: c.step([0.1]), "e"),
    ("step applied str", lambda c: c.step(0.1, applied="0.0"), "applied"),
    ("step_dt dt str", lambda c: c.step_dt(0.1, "1e-3"), "dt"),
    ("step unknown keyword", lambda c: c.step(0.1, aplied=0.0), "aplied"),
    ("step_state unknown keyword", lambda c: c.step_state([0.0] * c.order, u=1.0), "u"),
    ("set_state str", lambda c: c.set_state("state"), "state"),
    # set_state takes a float64 NumPy array only (lists and int arrays are rejected)
    ("set_state list", lambda c: c.set_state(list(c.state())), "ndarray"),
    ("set_state int64", lambda c: c.set_state(c.state().astype(np.int64)), "float64"),
    ("set_state 2-D", lambda c: c.set_state(c.state()[None, :]), "dimensionality"),
]


@pytest.mark.parametrize("case", TYPE_ERRORS, ids=[c[0] for c in TYPE_ERRORS])
def test_wrong_python_types_raise_type_error_naming_the_argument(pair, case):
    ctrl, _ = pair
    _, call, name = case
    with pytest.raises(TypeError) as info:
        call(ctrl)
    assert re.search(rf"\b{name}\b", _text(info.value)), _text(info.value)


SET_STATE_ERRORS = [
    ("too short", lambda s: s[:-1], "length"),
    ("too long", lambda s: np.append(s, 0.0), "length"),
    ("empty", lambda s: s[:0], "length"),
    ("nan estimate", lambda s: np.where(np.arange(s.size) == s.size - 1, NAN, s), "finite"),
    ("inf time", lambda s: np.where(np.arange(s.size) == 1, INF, s), "finite"),
    ("negative time", lambda s: np.where(np.arange(s.size) == 1, -1.0, s), "time"),
    ("fractional k", lambda s: np.where(np.arange(s.size) == 2, 1.5, s), "k must be"),
    ("negative k", lambda s: np.where(np.arange(s.size) == 2, -1.0, s), "k must be"),
    ("nan clamp_count", lambda s: np.where(np.arange(s.size) == 5, NAN, s), "clamp_count"),
    ("widths below eps", lambda s: np.where(np.isin(np.arange(s.size), (3, 4)), 1e-9, s), "eps"),
    ("negative widths", lambda s: np.where(np.isin(np.arange(s.size), (3, 4)), -1.0, s), "eps"),
    ("non-contiguous", lambda s: np.repeat(s, 2)[::2], "contiguous"),
]


@pytest.mark.parametrize("case", SET_STATE_ERRORS, ids=[c[0] for c in SET_STATE_ERRORS])
def test_bad_state_vectors_raise_config_error_and_change_nothing(pair, case):
    ctrl, _ = pair
    _, make, pattern = case
    with pytest.raises(famcc.ConfigError, match=pattern) as info:
        ctrl.set_state(make(ctrl.state()))
    assert "state" in str(info.value)


# -- configuration errors ----------------------------------------------------------

BASE = {"order": 2, "dt": 1e-3, "feedback": L, "constraint": "lateral", "eps": 0.1, "k_u": 5.0}


def _build(**changes):
    kw = {**BASE, **changes}
    return famcc.Controller(kw.pop("order"), kw.pop("dt"), **kw)


CONFIG_ERRORS = [
    # (id, call, parameter named in the message)
    ("dt 0", lambda: _build(dt=0.0), "dt"),
    ("dt < 0", lambda: _build(dt=-1e-3), "dt"),
    ("dt nan", lambda: _build(dt=NAN), "dt"),
    ("dt inf", lambda: _build(dt=INF), "dt"),
    ("order 0", lambda: _build(order=0), "order"),
    ("order 9", lambda: _build(order=9), "order"),
    ("eps 0", lambda: _build(eps=0.0), "eps"),
    ("eps < 0", lambda: _build(eps=-0.1), "eps"),
    ("eps nan", lambda: _build(eps=NAN), "eps"),
    ("eps str", lambda: _build(eps="0.1"), "eps"),
    ("eps pair for lateral", lambda: _build(eps=(0.1, 0.1)), "eps"),
    ("oblique eps float", lambda: _build(constraint="oblique", eps=0.1), "eps"),
    ("oblique eps_x", lambda: _build(constraint="oblique", eps=(0.0, 0.1)), "eps_x"),
    ("oblique eps_y", lambda: _build(constraint="oblique", eps=(0.1, -1.0)), "eps_y"),
    ("k0 1", lambda: _build(k0=1.0), "k0"),
    ("k0 < 1", lambda: _build(k0=0.5), "k0"),
    ("k0 inf", lambda: _build(k0=INF), "k0"),
    ("k_u 0", lambda: _build(k_u=0.0), "k_u"),
    ("k_u < 0", lambda: _build(k_u=-5.0), "k_u"),
    ("k_u nan", lambda: _build(k_u=NAN), "k_u"),
    ("settle_time 0", lambda: _build(settle_time=0.0), "settle_time"),
    ("settle_time inf", lambda: _build(settle_time=INF), "settle_time"),
    ("rho_e = eps", lambda: _build(rho_e=0.1), "rho_e"),
    ("rho_e > eps", lambda: _build(rho_e=0.5), "rho_e"),
    ("rho_e 0", lambda: _build(rho_e=0.0), "rho_e"),
    ("rho_e < 0", lambda: _build(rho_e=-0.01), "rho_e"),
    ("constraint", lambda: _build(constraint="diagonal"), "constraint"),
    ("constraint case", lambda: _build(constraint="Lateral"), "constraint"),
    ("gamma", lambda: _build(gamma="tanh"), "gamma"),
    ("latch", lambda: _build(latch="matlab"), "latch"),
    ("transition", lambda: _build(transition="linear"), "transition"),
    ("dtype", lambda: _build(dtype="float16"), "dtype"),
    ("differentiator str", lambda: _build(differentiator="exact"), "differentiator"),
    (
        "differentiator a length",
        lambda: _build(differentiator=famcc.HighGain(0.01, [4.0, 6.0, 4.0])),
        "differentiator.a",
    ),
    ("feedback missing", lambda: _build(feedback=None), "feedback"),
    ("feedback float", lambda: _build(feedback=1.0), "feedback"),
    ("feedback list of str", lambda: _build(order=3, feedback=["a", "b"]), "feedback"),
    ("feedback list length", lambda: _build(order=3, feedback=[L], skew=NS), "feedback"),
    ("feedback list too long", lambda: _build(feedback=[L, L]), "feedback"),
    ("skew list length", lambda: _build(order=3, skew=[NS]), "skew"),
    ("skew list too long", lambda: _build(skew=[None, None]), "skew"),
    ("skew str", lambda: _build(skew="nsmd"), "skew"),
    ("skew law", lambda: _build(skew=L), "skew"),
    ("skew needed at order 3", lambda: _build(order=3, constraint="longitudinal"), "skew"),
    (
        "initial_derivatives length",
        lambda: _build(initial_derivatives=[0.0, 0.0]),
        "initial_derivatives",
    ),
    ("initial_derivatives empty", lambda: _build(initial_derivatives=[]), "initial_derivatives"),
    ("initial_derivatives nan", lambda: _build(initial_derivatives=[NAN]), "initial_derivatives"),
    ("lateral at order 1", lambda: _build(order=1, feedback=None), "constraint"),
    # building blocks
    ("Linear k 0", lambda: famcc.Linear(0.0), "k"),
    ("Linear k nan", lambda: famcc.Linear(NAN), "k"),
    ("Linear k inf", lambda: famcc.Linear(INF), "k"),
    ("FiniteTime k", lambda: famcc.FiniteTime(-1.0, 0.5), "k"),
    ("FiniteTime p 0", lambda: famcc.FiniteTime(1.0, 0.0), "p"),
    ("FiniteTime p 1", lambda: famcc.FiniteTime(1.0, 1.0), "p"),
    ("FiniteTime p nan", lambda: famcc.FiniteTime(1.0, NAN), "p"),
    ("FixedTime alpha", lambda: famcc.FixedTime(0.0, 0.5, 0.5, 2.0), "alpha"),
    ("FixedTime beta", lambda: famcc.FixedTime(1.0, 0.5, -0.5, 2.0), "beta"),
    ("FixedTime p", lambda: famcc.FixedTime(1.0, 1.5, 0.5, 2.0), "p"),
    ("FixedTime q 1", lambda: famcc.FixedTime(1.0, 0.5, 0.5, 1.0), "q"),
    ("FixedTime q < 1", lambda: famcc.FixedTime(1.0, 0.5, 0.5, 0.5), "q"),
    ("FixedTime q inf", lambda: famcc.FixedTime(1.0, 0.5, 0.5, INF), "q"),
    ("VariableExponent k", lambda: famcc.VariableExponent(0.0, 0.5, 2.0, 3.0), "k"),
    ("VariableExponent r_b", lambda: famcc.VariableExponent(1.5, 1.5, 2.0, 3.0), "r_b"),
    ("VariableExponent r_1", lambda: famcc.VariableExponent(1.5, 0.5, 0.9, 3.0), "r_1"),
    ("VariableExponent r_t", lambda: famcc.VariableExponent(1.5, 0.5, 2.0, 1.5), "r_t"),
    ("Moulay beta", lambda: famcc.MoulayDiscontinuous(0.0, 1.0, 0.0), "beta"),
    ("Moulay lambda", lambda: famcc.MoulayDiscontinuous(1.0, 0.0, 0.0), "lambda"),
    ("Moulay mu", lambda: famcc.MoulayDiscontinuous(1.0, 1.0, -1.0), "mu"),
    ("Smooth eps_s", lambda: famcc.Smooth(0.0, 0.1), "eps_s"),
    ("Smooth eps_z", lambda: famcc.Smooth(0.1, -0.1), "eps_z"),
    ("Smooth transition", lambda: famcc.Smooth(0.1, 0.1, "step"), "transition"),
    ("Nonsingular k_pp", lambda: famcc.Nonsingular(0.1, 0.1, 0.0), "k_pp"),
    ("Nonsingular eps_s", lambda: famcc.Nonsingular(NAN, 0.1, 0.1), "eps_s"),
    ("Nonsingular transition", lambda: famcc.Nonsingular(0.1, 0.1, 0.1, "x"), "transition"),
    ("HighGain mu 0", lambda: famcc.HighGain(0.0, [4.0, 4.0]), "mu"),
    ("HighGain mu < 0", lambda: famcc.HighGain(-0.01, [4.0, 4.0]), "mu"),
    ("HighGain mu nan", lambda: famcc.HighGain(NAN, [4.0, 4.0]), "mu"),
    ("HighGain not Hurwitz", lambda: famcc.HighGain(0.01, [1.0, 1.0, 5.0]), "a"),
    ("HighGain negative a", lambda: famcc.HighGain(0.01, [1.0, -1.0]), "a"),
    ("HighGain a nan", lambda: famcc.HighGain(0.01, [4.0, NAN]), "a"),
    ("HighGain a empty", lambda: famcc.HighGain(0.01, []), "a"),
    ("HighGain a 9", lambda: famcc.HighGain(0.01, [1.0] * 9), "a"),
    ("HighGain discretization", lambda: famcc.HighGain(0.01, [4.0, 4.0], "rk4"), "discretization"),
    ("HighGain limits length", lambda: famcc.HighGain(0.01, [4.0, 4.0], limits=[1.0]), "limits"),
    ("HighGain limits 0", lambda: famcc.HighGain(0.01, [4.0, 4.0], limits=[1.0, 0.0]), "limits"),
    ("HighGain.default order 0", lambda: famcc.HighGain.default(0), "order"),
    ("HighGain.default order 9", lambda: famcc.HighGain.default(9), "order"),
    ("HighGain.default mu", lambda: famcc.HighGain.default(2, mu=0.0), "mu"),
    ("ControllerBank n 0", lambda: famcc.ControllerBank(_build(), 0), "n"),
    # functions
    ("manifold z empty", lambda: famcc.manifold([], L), "z"),
    ("manifold z nan", lambda: famcc.manifold([NAN, 0.0], famcc.Linear(1.0)), "z"),
    ("manifold z 9", lambda: famcc.manifold([0.0] * 9, famcc.Linear(1.0)), "z"),
    ("manifold feedback length", lambda: famcc.manifold([1.0, 0.0, 0.0], [L]), "feedback"),
    ("manifold skew length", lambda: famcc.manifold([1.0, 0.0, 0.0], L, [NS]), "skew"),
    ("manifold feedback type", lambda: famcc.manifold([1.0, 0.0], "linear"), "feedback"),
    ("skewed law type", lambda: famcc.skewed(NS, None), "law"),
    ("skewed skew type", lambda: famcc.skewed(L, L), "skew"),
    ("rho eps", lambda: famcc.envelope.rho(2.0, 0.0, 1.0, 0.5), "eps"),
    ("rho rho0 < eps", lambda: famcc.envelope.rho(0.05, 0.1, 1.0, 0.5), "rho0"),
    ("rho settle_time", lambda: famcc.envelope.rho(2.0, 0.1, 0.0, 0.5), "settle_time"),
    ("transition kind", lambda: famcc.transition.S(0.5, kind="tanh"), "kind"),
    ("transition U kind", lambda: famcc.transition.U(0.5, "x"), "kind"),
    ("bounds finite_time p", lambda: famcc.bounds.finite_time(1.0, 1.0, 1.0), "p"),
    (
        "bounds variable_exponent r_1",
        lambda: famcc.bounds.variable_exponent(1.0, 0.5, 1.0, 3.0),
        "r_1",
    ),
    (
        "bounds fixed_time stage 2",
        lambda: famcc.bounds.fixed_time([(1.0, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 0.5)]),
        "stage 2: q",
    ),
]


@pytest.mark.parametrize("case", CONFIG_ERRORS, ids=[c[0] for c in CONFIG_ERRORS])
def test_config_errors_name_the_parameter(case):
    _, build, name = case
    with pytest.raises(famcc.ConfigError) as info:
        build()
    assert isinstance(info.value, ValueError)
    message = str(info.value)
    assert re.search(rf"(?<![\w.]){re.escape(name)}\b", message), message


def test_config_errors_state_the_rule():
    with pytest.raises(famcc.ConfigError, match=r"^dt must be finite and > 0$"):
        _build(dt=0.0)
    with pytest.raises(famcc.ConfigError, match=r"^k0 must be finite and > 1$"):
        _build(k0=1.0)
    with pytest.raises(famcc.ConfigError, match=r"^p must satisfy 0 < p < 1$"):
        famcc.FiniteTime(1.0, 2.0)
    with pytest.raises(famcc.ConfigError, match=r"rho_e must be smaller than .*eps"):
        _build(rho_e=1.0)
    with pytest.raises(famcc.ConfigError, match=r"order must be between 1 and 8 \(got 9\)"):
        _build(order=9)
    with pytest.raises(famcc.ConfigError, match=r"'log', 'rational' \(got \"tanh\"\)"):
        _build(gamma="tanh")
    with pytest.raises(famcc.ConfigError, match="not Hurwitz"):
        famcc.HighGain(0.01, [1.0, 1.0, 5.0])
    with pytest.raises(famcc.ConfigError, match="^stage 1: skew must be Nonsingular"):
        _build(order=3, constraint="longitudinal", feedback=L)


UNKNOWN_KEYWORDS = [
    ("Controller", lambda: _build(gain=1.0), "gain"),
    ("Controller eps_x", lambda: _build(eps_x=0.1), "eps_x"),
    ("Linear", lambda: famcc.Linear(kk=1.0), "kk"),
    ("FiniteTime", lambda: famcc.FiniteTime(k=1.0, p=0.5, q=2.0), "q"),
    ("FixedTime", lambda: famcc.FixedTime(alpha=1.0, p=0.5, beta=0.5, q=2.0, r=1.0), "r"),
    ("VariableExponent", lambda: famcc.VariableExponent(1.5, 0.5, 2.0, r_inf=3.0), "r_inf"),
    ("MoulayDiscontinuous", lambda: famcc.MoulayDiscontinuous(1.0, mu=0.0, lam=1.0), "lam"),
    ("Smooth", lambda: famcc.Smooth(eps_s=0.1, eps_z=0.1, kind="sine"), "kind"),
    ("Nonsingular", lambda: famcc.Nonsingular(0.1, 0.1, k_p=0.1), "k_p"),
    ("HighGain", lambda: famcc.HighGain(0.01, [4.0, 4.0], method="exact"), "method"),
    ("HighGain.default", lambda: famcc.HighGain.default(2, gain=0.01), "gain"),
    ("ControllerBank", lambda: famcc.ControllerBank(_build(), n=3, copies=3), "copies"),
    ("skewed", lambda: famcc.skewed(L, skw=NS), "skw"),
    ("manifold", lambda: famcc.manifold([1.0, 0.0], L, skews=None), "skews"),
    ("rho", lambda: famcc.envelope.rho(2.0, 0.1, 1.0, 0.5, T=1.0), "T"),
    ("transition", lambda: famcc.transition.S(0.5, kinds="sine"), "kinds"),
    ("bounds", lambda: famcc.bounds.finite_time(1.0, 0.5, z0=1.0), "z0"),
]


@pytest.mark.parametrize("case", UNKNOWN_KEYWORDS, ids=[c[0] for c in UNKNOWN_KEYWORDS])
def test_unknown_keywords_raise_type_error_naming_the_keyword(case):
    _, call, name = case
    with pytest.raises(TypeError, match=rf"unexpected keyword argument '{name}'"):
        call()


def test_missing_required_keywords_are_named():
    with pytest.raises(TypeError, match="'k_u'"):
        famcc.Controller(2, 1e-3, L, eps=0.1)
    with pytest.raises(TypeError, match="'eps'"):
        famcc.Controller(2, 1e-3, L, k_u=1.0)
    with pytest.raises(TypeError):
        famcc.Controller(2, 1e-3, L, NS, eps=0.1, k_u=1.0)  # skew is keyword-only


WRONG_TYPES = [
    ("dt str", lambda: _build(dt="1e-3"), "dt"),
    ("k_u str", lambda: _build(k_u="5"), "k_u"),
    ("k0 None", lambda: _build(k0=None), "k0"),
    ("settle_time list", lambda: _build(settle_time=[1.0]), "settle_time"),
    ("order float", lambda: _build(order=2.0), "order"),
    ("order str", lambda: _build(order="2"), "order"),
    ("constraint int", lambda: _build(constraint=1), "constraint"),
    ("dtype type", lambda: _build(dtype=np.float32), "dtype"),
    (
        "initial_derivatives strings",
        lambda: _build(initial_derivatives=["a"]),
        "initial_derivatives",
    ),
    ("initial_derivatives str", lambda: _build(initial_derivatives="a"), "initial_derivatives"),
    ("Linear str", lambda: famcc.Linear("1.0"), "k"),
    ("FixedTime None", lambda: famcc.FixedTime(1.0, 0.5, None, 2.0), "beta"),
    ("HighGain a strings", lambda: famcc.HighGain(0.01, ["4", "4"]), "a"),
    ("HighGain a str", lambda: famcc.HighGain(0.01, "44"), "a"),
    ("HighGain mu str", lambda: famcc.HighGain("0.01", [4.0, 4.0]), "mu"),
    ("ControllerBank n str", lambda: famcc.ControllerBank(_build(), "3"), "n"),
    ("ControllerBank controller", lambda: famcc.ControllerBank("ctrl", 3), "controller"),
    ("manifold z strings", lambda: famcc.manifold(["a", "b"], L), "z"),
    ("bounds str", lambda: famcc.bounds.finite_time("1", 0.5, 1.0), "k"),
]


@pytest.mark.parametrize("case", WRONG_TYPES, ids=[c[0] for c in WRONG_TYPES])
def test_wrong_types_raise_type_error_naming_the_argument(case):
    _, call, name = case
    with pytest.raises(TypeError) as info:
        call()
    assert re.search(rf"'{re.escape(name)}'", _text(info.value)), _text(info.value)


def test_a_law_given_a_string_raises_value_error():
    with pytest.raises(ValueError, match="could not convert"):
        L("x")
    with pytest.raises(ValueError):
        famcc.transition.T(["a"])


def test_differentiator_of_the_wrong_type_is_a_config_error():
    with pytest.raises(famcc.ConfigError, match="differentiator must be a HighGain"):
        _build(differentiator=5)


@pytest.mark.parametrize("value", ["0.01", "none", [0.01]])
def test_rho_e_of_the_wrong_kind_is_a_config_error(value):
    with pytest.raises(famcc.ConfigError, match="rho_e must be a float, 'auto' or None"):
        _build(rho_e=value)


def test_rho_e_auto_scales_with_eps():
    assert _build(rho_e="auto").config()["rho_e"] == 0.01
    small = famcc.Controller(2, 1e-3, famcc.Linear(1.0), eps=0.01, k_u=1.0)
    assert small.config()["rho_e"] == pytest.approx(0.001)


def test_negative_order_is_a_config_error():
    with pytest.raises(famcc.ConfigError, match="order"):
        _build(order=-1)


def test_errors_leave_a_fresh_controller_fresh():
    ctrl = _build()
    twin = copy.copy(ctrl)
    for call in (
        lambda: ctrl.step(NAN),
        lambda: ctrl.step_dt(0.1, 0.0),
        lambda: ctrl.set_state(ctrl.state()[:-1]),
        lambda: ctrl.step_state([0.1]),
    ):
        with pytest.raises(ValueError):
            call()
    assert ctrl.time == 0.0 and ctrl.state()[0] == 0.0
    assert_same(ctrl, twin)
