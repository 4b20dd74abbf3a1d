"""Invariants of the paper's theorems, on random plants and on the paper's scenarios.

- Theorems 1-3 with the flexible boundary: |xi~| < 1 at every sample, no
  clamping, the applied input inside the limits and every signal finite, for
  random strict-feedback plants of the paper's class (orders 2 and 3), random
  initial states, references and saturation limits (hypothesis).
- The compiled ``step()`` never returns a non-finite value for finite input and
  rejects non-finite input with ``StepError``, leaving the state unchanged.
- Corollaries 1-3: each of the paper's six scenarios (variants "code" and
  "paper") stays within its theoretical bounds (``Scenario.check`` is empty).
"""

from __future__ import annotations

import copy
import math
import os

import famcc
import numpy as np
import pytest
from famcc.plants import StrictFeedback
from famcc.simulation import Sine
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st
from runs import scenario_run

# -- random plants of the paper's class ------------------------------------------

unit = st.floats(-1.0, 1.0, allow_nan=False)
freq = st.floats(0.2, 3.0, allow_nan=False)


@st.composite
def stage(draw, i: int):
    """Coefficients of g_i and f_i (both depend on x_1..x_i and t only)."""
    return {
        "g0": draw(st.floats(0.5, 3.0)),  # nominal gain
        "ga": draw(st.floats(0.0, 0.2)),  # relative variation, < 0.2 g0
        "gw": draw(freq),
        "gj": draw(st.integers(0, i)),  # which x_j (j <= i) modulates g_i
        "damp": draw(st.floats(0.1, 1.0)),  # mild -x_i damping
        "da": draw(st.floats(0.0, 2.0)),  # disturbance amplitude
        "dw": draw(freq),
        "dp": draw(st.floats(0.0, 2 * math.pi)),
        "nl": draw(st.floats(0.0, 0.3)),  # bounded nonlinearity in x_1
    }


class _Plant(StrictFeedback):
    """StrictFeedback with a float fast path for the simulator.

    The invariants need neither the true error vector nor -F/G, so the exact
    (jet-based) output derivatives are skipped to keep the property tests fast.
    """

    def rhs_fast(self, t, x, u):
        n = self.order
        return tuple(
            float(self.g[i](x, t)) * (x[i + 1] if i + 1 < n else u) + float(self.f[i](x, t))
            for i in range(n)
        )

    def output_derivatives(self, t, x):
        raise NotImplementedError


def make_plant(stages: list[dict], x0: list[float]) -> StrictFeedback:
    """x_i' = g_i(x, t) x_{i+1} + f_i(x, t) with NumPy-ufunc callables (jet friendly).

    g_i = g0 (1 + ga sin(gw t + x_j)) stays in [0.8 g0, 1.2 g0] (product away
    from 0); f_i = -damp x_i + da sin(dw t + dp) + nl sin(x_1), bounded except
    for the damping term.
    """
    g, f = [], []
    for i, c in enumerate(stages):

        def gi(x, t, c=c):
            return c["g0"] * (1.0 + c["ga"] * np.sin(c["gw"] * t + x[c["gj"]]))

        def fi(x, t, c=c, i=i):
            return (
                -c["damp"] * x[i] + c["da"] * np.sin(c["dw"] * t + c["dp"]) + c["nl"] * np.sin(x[0])
            )

        g.append(gi)
        f.append(fi)
    return _Plant(g=g, f=f, x0=x0, name="random")


@st.composite
def closed_loop(draw, order: int):
    stages = [draw(stage(i)) for i in range(order)]
    x0 = draw(st.lists(st.floats(-1.5, 1.5), min_size=order, max_size=order))
    ref = Sine(
        draw(st.floats(0.2, 1.5)), draw(st.floats(0.2, 2.0)), draw(st.floats(0.0, 2 * math.pi))
    )
    low, high = draw(st.sampled_from([(0.3, 2.0), (2.0, 10.0), (10.0, 100.0)]))  # tight..wide
    limits = (-draw(st.floats(low, high)), draw(st.floats(low, high)))
    names = ["finite-time", "variable-exponent"] if order == 2 else ["rfc"]
    name = draw(st.sampled_from(names))
    return make_plant(stages, x0), ref, limits, name


def run(plant, ref, limits, name, t_end):
    ctrl = famcc.scenarios.paper(name, "code").controller(dt=1e-3)
    n = plant.order
    # y_d .. y_d^(n-1) only: -F/G (which needs y_d^(n) and costly jets) is not needed.
    reference = [(lambda t, k=k: ref(t, k)) for k in range(n)]
    return famcc.simulate(plant, ctrl, t_end, reference=reference, u_limits=limits, substeps=2)


def assert_invariants(res, limits):
    lo, hi = limits
    assert res.xi is not None
    assert np.all(np.isfinite(res.xi))
    assert res.max_abs_xi < 1.0
    assert res.clamp_count == 0
    assert np.all(np.isfinite(res.v)) and np.all(np.isfinite(res.x))
    assert np.all(np.isfinite(res.z_hat)) and np.all(np.isfinite(res.bounds))
    assert lo <= res.u_min and res.u_max <= hi
    # The flexible bounds never shrink below the nominal ones.
    used = res.nominal_bounds > 0
    assert np.all(res.bounds[used] >= res.nominal_bounds[used] * (1 - 1e-12))


#: Closed-loop examples per property: random each run, the seed printed on failure
#: (hypothesis prints ``@seed(...)`` to reproduce). FAMCC_HYPOTHESIS_EXAMPLES raises it.
INVARIANT_SETTINGS = settings(
    max_examples=int(os.environ.get("FAMCC_HYPOTHESIS_EXAMPLES", "25")),
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)


def _tight_case(order: int, name: str, limits: tuple[float, float]):
    """A hand-picked case that saturates hard: strong disturbance, tight limits."""
    stages = [
        {
            "g0": 1.0 + 0.5 * i,
            "ga": 0.2,
            "gw": 2.0,
            "gj": i,
            "damp": 0.2,
            "da": 2.0,
            "dw": 3.0,
            "dp": 0.5,
            "nl": 0.3,
        }
        for i in range(order)
    ]
    return make_plant(stages, [1.5] + [-1.0] * (order - 1)), Sine(1.0, 2.0), limits, name


#: Random plants of the paper's class may keep the bounds expanded with headroom
#: (issue 13: rho_e = 0.01 loses accuracy on some): the health warning is expected
#: there and is not what these invariants test.
_HEALTH = pytest.mark.filterwarnings("ignore:k_u too small:famcc.DesignWarning")


@_HEALTH
@INVARIANT_SETTINGS
@given(closed_loop(2))
@example(_tight_case(2, "finite-time", (-0.5, 0.8)))
@example(_tight_case(2, "variable-exponent", (-1.0, 0.4)))
def test_xi_stays_inside_order_2(case):
    plant, ref, limits, name = case
    assert_invariants(run(plant, ref, limits, name, t_end=3.0), limits)


@_HEALTH
@INVARIANT_SETTINGS
@given(closed_loop(3))
@example(_tight_case(3, "rfc", (-0.6, 0.6)))
def test_xi_stays_inside_order_3(case):
    plant, ref, limits, name = case
    assert_invariants(run(plant, ref, limits, name, t_end=2.0), limits)


def test_random_plants_are_of_the_papers_class():
    """The generated plants have strict-feedback structure and a gain away from 0."""
    rng = np.random.default_rng(0)
    stages = [
        {
            "g0": 0.5,
            "ga": 0.2,
            "gw": 1.0,
            "gj": i,
            "damp": 0.5,
            "da": 1.0,
            "dw": 1.0,
            "dp": 0.0,
            "nl": 0.3,
        }
        for i in range(3)
    ]
    plant = make_plant(stages, [0.1, 0.2, 0.3])
    for _ in range(20):
        x, t = rng.uniform(-3, 3, 3), rng.uniform(0, 10)
        gain, _ = plant.gain_and_drift(t, x)
        assert gain >= (0.5 * 0.8) ** 3
        # x_1' does not depend on x_3 (strict feedback): y' is input-free.
        x2 = x.copy()
        x2[2] += 1.0
        dy = StrictFeedback.output_derivatives
        assert dy(plant, t, x)[1] == dy(plant, t, x2)[1]
        # The fast path is the same vector field.
        assert np.allclose(plant.rhs_fast(t, tuple(x), 0.7), plant.rhs(t, x, 0.7), rtol=1e-14)


# -- the compiled step never produces a non-finite value ---------------------------

finite = st.floats(allow_nan=False, allow_infinity=False)
non_finite = st.sampled_from([math.nan, math.inf, -math.inf])

_DESIGNS = {
    name: famcc.scenarios.paper(name).controller(dt=1e-3)
    for name in ("finite-time", "variable-exponent", "rfc")
}
_DESIGNS["rfc-f32"] = famcc.scenarios.paper("rfc").controller(dtype="float32")
# dt = mu: legal but coarse (a DesignWarning), and still never non-finite.
with pytest.warns(famcc.DesignWarning, match="dt / mu"):
    _DESIGNS["linear-no-flex"] = famcc.Controller(
        2, 1e-2, famcc.Linear(1.0), eps=0.1, k_u=1.0, rho_e=None, gamma="rational"
    )


def _consumed(before: np.ndarray, after: np.ndarray) -> bool:
    """The step consumed the sample: started, one more sample on the clock."""
    return bool(after[0] == 1.0 and after[2] == before[2] + 1 and after[1] == before[1])


@settings(max_examples=300, deadline=None)
@given(
    design=st.sampled_from(sorted(_DESIGNS)),
    errors=st.lists(finite, min_size=1, max_size=40),
    applied=st.one_of(st.none(), finite),
)
def test_step_output_is_finite_or_a_clean_error(design, errors, applied):
    ctrl = copy.copy(_DESIGNS[design])
    largest = 0.0
    for e in errors:
        largest = max(largest, abs(e), abs(applied or 0.0))
        before = ctrl.state()
        try:
            v = ctrl.step(e, applied=applied)
        except famcc.StepError as exc:
            # Only absurdly large samples may make a finite step fail: an internal
            # overflow, or for float32 cores a float64 e or applied beyond the
            # float32 range, which is reported as "... must be finite" (API wart:
            # the value was finite).
            assert largest > 1e9, (str(exc), e)
            assert "overflow" in str(exc) or ctrl.dtype == "float32", str(exc)
            after = ctrl.state()
            assert np.all(np.isfinite(after))
            # Nothing changed, or (core >= "recover from outliers") the valid
            # sample was consumed so that the estimate can decay again.
            assert np.array_equal(after, before) or (
                "overflow" in str(exc) and _consumed(before, after)
            )
            continue
        assert math.isfinite(v)
        d = ctrl.diagnostics
        assert abs(d.xi) < 1.0
        assert np.all(np.isfinite(ctrl.state()))
        assert math.isfinite(d.s) and np.all(np.isfinite(d.z_hat))


@pytest.mark.parametrize(
    "design, huge, outage",
    # Measured outages (samples of StepError after the outlier) with ~20 % margin.
    [("rfc-f32", 1e11, 8), ("rfc", 1e100, 600), ("finite-time", 1e155, 55)],
)
def test_one_huge_sample_does_not_disable_the_controller(design, huge, outage):
    """One outlier may cost some samples (StepError, hold the last output) but the
    controller must recover by itself as the differentiator's estimate decays, within
    a bounded outage, and then step without errors."""
    ctrl = copy.copy(_DESIGNS[design])
    ctrl.step(0.0)
    try:
        ctrl.step(huge)
    except famcc.StepError:
        pass
    failed = []
    for i in range(2000):
        try:
            v = ctrl.step(0.0)
        except famcc.StepError:
            failed.append(i)
            continue
        assert math.isfinite(v)
    assert len(failed) <= outage, f"{len(failed)} failed samples after one outlier"
    assert failed == list(range(len(failed))), "errors after the controller had recovered"
    assert math.isfinite(ctrl.step(0.0))


@settings(max_examples=200, deadline=None)
@given(
    design=st.sampled_from(sorted(_DESIGNS)),
    warmup=st.lists(finite, max_size=5),
    bad=non_finite,
    where=st.sampled_from(["e", "applied", "step_dt", "state"]),
)
def test_non_finite_input_raises_and_leaves_the_state(design, warmup, bad, where):
    ctrl = copy.copy(_DESIGNS[design])
    for e in warmup:
        try:
            ctrl.step(e)
        except famcc.StepError:
            pass
    before = ctrl.state()
    diag = repr(ctrl.diagnostics)
    with pytest.raises(famcc.StepError, match="finite"):
        if where == "e":
            ctrl.step(bad)
        elif where == "applied":
            ctrl.step(0.1, applied=bad)
        elif where == "step_dt":
            ctrl.step_dt(bad, ctrl.dt)
        else:
            ctrl.step_state([0.0] * (ctrl.order - 1) + [bad])
    assert np.array_equal(ctrl.state(), before)
    assert repr(ctrl.diagnostics) == diag


@settings(max_examples=150, deadline=None)
@given(
    design=st.sampled_from(sorted(_DESIGNS)),
    z=st.lists(st.floats(-1e6, 1e6), min_size=3, max_size=3),
)
def test_step_state_output_is_finite(design, z):
    ctrl = copy.copy(_DESIGNS[design])
    assume(ctrl.order <= len(z))
    v = ctrl.step_state(z[: ctrl.order])
    assert math.isfinite(v) and abs(ctrl.diagnostics.xi) < 1.0


# -- the paper's scenarios stay within the theoretical bounds -------------------------


@pytest.mark.parametrize("variant", ["code", "paper"])
@pytest.mark.parametrize("name", famcc.scenarios.names())
def test_scenario_within_theoretical_bounds(name, variant):
    sc = famcc.scenarios.paper(name, variant)
    res = scenario_run(name, variant)
    if sc.regains_accuracy:
        assert sc.check(res) == []
    else:
        # The paper's own numbers do not regain the accuracy (docs/errata.md): the
        # claim fails, marked known, and nothing else fails.
        (failure,) = sc.check(res)
        assert failure.startswith("settles: failed (known")
    # What check() promises, spelled out for the unsaturated runs.
    assert res.max_abs_xi < 1.0 and res.clamp_count == 0
    if not sc.saturated:
        ts = res.settling_time(sc.eps_z)
        assert ts is not None and ts <= sc.bound
