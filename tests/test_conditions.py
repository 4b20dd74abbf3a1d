"""simulate(noise=, disturbance=, diverge_at=), the comparison metrics, peers and joints."""

from __future__ import annotations

import math
from types import SimpleNamespace

import famcc
import numpy as np
import pyadrc
import pytest
from famcc.joints import simulate_joints, two_link_arm
from famcc.peers import ADRCPeer, LinearADRC, PIDPeer
from famcc.simulation import SimResult


class Recorder:
    """A P controller that records what it was given."""

    def __init__(self, dt=1e-3, order=1, k=5.0):
        self.dt, self.order, self.k, self.seen = dt, order, k, []

    def step(self, e, applied=None):
        self.seen.append(e)
        return -self.k * e


def integrator(x0=1.0):
    return famcc.plants.StrictFeedback([lambda x, t: 1.0], [lambda x, t: 0.0 * x[0]], [x0])


def test_noise_reaches_the_controller_but_not_the_recorded_error():
    ctrl = Recorder()
    res = famcc.simulate(
        integrator(), ctrl, 2.0, reference=famcc.Constant(0.0), record=False, noise=0.01, seed=4
    )
    n = res.z1_measured - res.z1
    assert np.allclose(res.z1_measured, ctrl.seen)
    assert np.std(n) == pytest.approx(0.01, rel=0.1) and abs(np.mean(n)) < 2e-3
    # the same seed, the same noise; another seed, another
    again = famcc.simulate(
        integrator(),
        Recorder(),
        2.0,
        reference=famcc.Constant(0.0),
        record=False,
        noise=0.01,
        seed=4,
    )
    other = famcc.simulate(
        integrator(),
        Recorder(),
        2.0,
        reference=famcc.Constant(0.0),
        record=False,
        noise=0.01,
        seed=5,
    )
    assert np.array_equal(again.z1_measured, res.z1_measured)
    assert not np.array_equal(other.z1_measured, res.z1_measured)
    # without noise nothing is recorded
    clean = famcc.simulate(
        integrator(), Recorder(), 0.1, reference=famcc.Constant(0.0), record=False
    )
    assert clean.z1_measured is None and clean.disturbance is None


def test_callable_noise_is_the_noise_itself():
    ctrl = Recorder()
    res = famcc.simulate(
        integrator(),
        ctrl,
        0.5,
        reference=famcc.Constant(0.0),
        record=False,
        noise=lambda t: 0.1 * math.sin(10 * t),
    )
    np.testing.assert_allclose(res.z1_measured - res.z1, 0.1 * np.sin(10 * res.t), atol=1e-12)


def test_an_input_disturbance_moves_the_plant_not_the_input():
    # x' = u + d with u = 0: x(t) = x0 + d t
    zero = SimpleNamespace(dt=1e-2, order=1, step=lambda e, applied=None: 0.0)
    res = famcc.simulate(
        integrator(0.0), zero, 1.0, reference=famcc.Constant(0.0), record=False, disturbance=0.5
    )
    np.testing.assert_allclose(res.y, 0.5 * res.t, atol=1e-12)
    assert np.all(res.u == 0.0) and np.all(res.disturbance == 0.5)
    # a callable: d(t) = t held per sample, x(t_k) = sum d(t_j) dt
    res = famcc.simulate(
        integrator(0.0),
        zero,
        1.0,
        reference=famcc.Constant(0.0),
        record=False,
        disturbance=lambda t: t,
    )
    want = np.concatenate(([0.0], np.cumsum(res.t[:-1]) * 1e-2))
    np.testing.assert_allclose(res.y, want, atol=1e-12)


def test_a_diverging_loop_is_stopped_and_flagged():
    unstable = SimpleNamespace(dt=1e-3, order=1, step=lambda e, applied=None: 5.0 * e)
    res = famcc.simulate(
        integrator(), unstable, 5.0, reference=famcc.Constant(0.0), record=False, diverge_at=10.0
    )
    assert res.diverged and res.never_settled(0.1)
    # |x| = e^(5 t) passes 10 at ln(10) / 5 = 0.46 s; the arrays end with that sample
    assert res.diverged_at == pytest.approx(math.log(10) / 5, abs=2e-3)
    assert len(res.t) == len(res.u) == len(res.z) and res.t[-1] == res.diverged_at
    assert abs(res.z1[-1]) > 10.0 and np.max(np.abs(res.z1[:-1])) <= 10.0
    s = res.summary(eps=0.1)
    assert s["diverged"] and s["never_settled"] and s["diverged_at"] == res.diverged_at
    assert s.text.startswith("DIVERGED at ")
    # a non-finite controller output is a divergence too with diverge_at, an error without
    nan = SimpleNamespace(dt=1e-3, order=1, step=lambda e, applied=None: math.nan)
    res = famcc.simulate(
        integrator(), nan, 1.0, reference=famcc.Constant(0.0), record=False, diverge_at=10.0
    )
    assert res.diverged and res.diverged_at == 0.0 and len(res.t) == 1 and math.isnan(res.v[0])
    with pytest.raises(FloatingPointError):
        famcc.simulate(integrator(), nan, 1.0, reference=famcc.Constant(0.0), record=False)


def test_a_stable_loop_is_not_flagged():
    res = famcc.simulate(
        integrator(),
        Recorder(k=10.0),
        2.0,
        reference=famcc.Constant(0.0),
        record=False,
        diverge_at=10.0,
    )
    assert not res.diverged and res.diverged_at is None and not res.never_settled(0.01)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"noise": -0.1}, "noise"),
        ({"noise": "loud"}, "noise"),
        ({"noise": 0.1, "seed": "x"}, "seed"),
        ({"disturbance": math.inf}, "disturbance"),
        ({"disturbance": lambda t: math.nan}, "disturbance"),
        ({"diverge_at": 0.0}, "diverge_at"),
        ({"diverge_at": 0.5}, "diverge_at"),  # below |z1(0)| = 1
    ],
)
def test_bad_conditions_are_named(kwargs, name):
    with pytest.raises(ValueError, match=name):
        famcc.simulate(
            integrator(), Recorder(), 0.1, reference=famcc.Constant(0.0), record=False, **kwargs
        )


def result(z1, u, dt=0.1):
    z1, u = np.asarray(z1, float), np.asarray(u, float)
    t = np.arange(len(z1)) * dt
    return SimResult(t=t, y=z1, y_d=0 * t, x=z1[:, None], z=z1[:, None], v=u, u=u, dt=dt)


def test_each_metric_against_a_hand_computation():
    r = result([1.0, -0.5, 0.05, -0.02, 0.01], [2.0, -1.0, 0.5, 0.5, 0.0])
    assert r.iae == pytest.approx(0.1 * (1.0 / 2 + 0.5 + 0.05 + 0.02 + 0.01 / 2))
    assert r.rms_u == pytest.approx(math.sqrt((4 + 1 + 0.25 + 0.25) / 5))
    assert r.tv_u_per_s == pytest.approx((3.0 + 1.5 + 0.0 + 0.5) / 0.4)
    assert r.settling_time(0.1) == 0.2
    assert r.z1_ripple(0.1) == pytest.approx(0.07) and r.ripple(0.1) == pytest.approx(0.5)
    assert not r.never_settled(0.1) and not r.diverged
    s = r.summary(eps=0.1)
    for key in ("iae", "rms_u", "tv_u_per_s", "z1_ripple", "diverged", "never_settled"):
        assert key in s
    assert "IAE 0.108 s" in s.text and "TV(u) 12.5/s" in s.text


def test_each_metric_and_flag_can_fail():
    # never settles: the last sample is outside the band
    r = result([1.0, 0.05, 0.2], [0.0, 0.0, 0.0])
    assert r.never_settled(0.1) and r.z1_ripple(0.1) is None and r.steady_rms(0.1) is None
    # a worse error has a larger IAE, a chattering input a larger TV and RMS
    calm, rough = result([0.1] * 5, [1.0] * 5), result([0.3] * 5, [1.0, -1.0] * 2 + [1.0])
    assert rough.iae > calm.iae and rough.tv_u_per_s > calm.tv_u_per_s == 0.0
    assert result([0.0] * 3, [3.0] * 3).rms_u > result([0.0] * 3, [1.0] * 3).rms_u
    flagged = result([0.0, 0.0], [0.0, 0.0])
    flagged.diverged_at = 0.1
    assert flagged.diverged and flagged.never_settled(0.1)


# -- peers ---------------------------------------------------------------------


@pytest.mark.parametrize("order", [1, 2])
def test_linear_adrc_is_pyadrc_at_orders_1_and_2(order):
    ss = pyadrc.StateSpace(order, 1e-3, 2.0, 8.0, 5.0, m_lim=(-3.0, 3.0))
    own = LinearADRC(order, 1e-3, 2.0, 8.0, 5.0, u_limits=(-3.0, 3.0))
    np.testing.assert_allclose(own.L, ss.L.ravel(), rtol=1e-12)
    rng = np.random.default_rng(1)
    u = 0.0
    for _ in range(300):
        y = float(rng.normal())
        a, b = ss(y, u, 0.0), own(y, u)
        assert b == pytest.approx(a, rel=1e-9, abs=1e-9)
        u = a


def test_linear_adrc_places_its_observer_poles():
    own = LinearADRC(4, 1e-3, 3.0, 5.0, 4.0)
    poles = np.linalg.eigvals(own._oA)
    np.testing.assert_allclose(poles, math.exp(-20.0 * 1e-3), atol=2e-3)


def test_pid_acts_against_the_error_within_its_limits():
    pid = PIDPeer(1e-3, 2, kp=10.0, ki=0.0, kd=0.0, tf=0.0, u_limits=(-2.0, 2.0))
    assert pid.step(0.1) == pytest.approx(-1.0)  # e = y - y_d > 0: push down
    assert pid.step(1.0) == -2.0  # clamped
    with pytest.raises(ValueError, match="kp"):
        PIDPeer(1e-3, 2, kp=-1.0, ki=0.0, kd=0.0, tf=0.0)


@pytest.mark.parametrize("peer", ["pid", "adrc"])
def test_peers_regulate_the_dc_motor(peer):
    motor = famcc.plants.dc_motor(load=0.0)
    g = motor.gain
    if peer == "pid":
        ctrl = PIDPeer(1e-3, 2, kp=3 * 400 / g, ki=8000 / g, kd=60 / g, tf=1e-3, u_limits=(-12, 12))
    else:
        ctrl = ADRCPeer(1e-3, 2, b0=g, w_cl=20.0, k_eso=5.0, u_limits=(-12, 12))
    res = famcc.simulate(
        motor, ctrl, 2.0, reference=famcc.Constant(1.0), u_limits=(-12, 12), record=False
    )
    assert res.settling_time(0.02) < 1.0


def test_lmcc_is_famcc_without_the_flexible_boundary():
    from famcc.peers import lmcc

    c = lmcc(3, 1e-3, k=2.0, eps=0.5, settle_time=1.0, k_u=5.0, mu=0.01)
    cfg = c.config()
    assert cfg["rho_e"] is None and cfg["constraint"] == "longitudinal"
    assert all(type(law).__name__ == "Linear" for law in cfg["feedback"])


# -- joints --------------------------------------------------------------------


class TwoIntegrators:
    """Two decoupled double integrators with gains 2 and 3: joint-wise, plain plants."""

    joints, order = 2, 2
    x0 = np.array([1.0, 0.0, -0.5, 0.2])
    outputs = (famcc.Signal("a"), famcc.Signal("b"))
    inputs = (famcc.Signal("u1"), famcc.Signal("u2"))

    def rhs(self, t, x, u):
        return [x[1], 2.0 * u[0], x[3], 3.0 * u[1]]


def test_simulate_joints_is_simulate_per_joint_when_decoupled():
    def ctrl():
        return famcc.Controller(
            2, 1e-3, famcc.FiniteTime(1.0, 0.5), constraint="lateral", eps=0.05, k_u=2.0
        )

    joint = simulate_joints(
        TwoIntegrators(),
        [ctrl(), ctrl()],
        2.0,
        [famcc.Constant(0.0), famcc.Constant(0.3)],
        u_limits=[(-5.0, 5.0), (-5.0, 5.0)],
    )
    for i, (gain, x0, ref) in enumerate([(2.0, [1.0, 0.0], 0.0), (3.0, [-0.5, 0.2], 0.3)]):
        single = famcc.plants.StrictFeedback(
            [lambda x, t: 1.0, lambda x, t, g=gain: g], [lambda x, t: 0.0, lambda x, t: 0.0], x0
        )
        alone = famcc.simulate(
            single, ctrl(), 2.0, reference=famcc.Constant(ref), u_limits=(-5.0, 5.0), record=False
        )
        np.testing.assert_allclose(joint[i].u, alone.u, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(joint[i].z, alone.z, rtol=1e-9, atol=1e-9)


def test_the_arm_conserves_energy_without_friction_and_input():
    arm = two_link_arm(b=0.0, x0=(0.3, 0.0, 0.5, 0.0))
    p = arm.params
    m1, m2, l1, lc1, lc2 = p["m1"], p["m2"], p["l1"], p["l1"] / 2, p["l2"] / 2

    def energy(x):
        q1, w1, q2, w2 = x
        w = np.array([w1, w2])
        pot = (m1 * lc1 + m2 * l1) * 9.81 * math.sin(q1) + m2 * lc2 * 9.81 * math.sin(q1 + q2)
        return 0.5 * w @ arm.inertia(q2) @ w + pot

    # The simulator's own RK4 (h = 5e-4 s: 10 substeps of a 5 ms sample) with zero inputs.
    idle = [SimpleNamespace(dt=5e-3, order=2, step=lambda e, applied=None: 0.0)] * 2
    shoulder, elbow = simulate_joints(arm, idle, 2.0, [famcc.Constant(0.0)] * 2, substeps=10)
    e0 = energy(list(arm.x0))
    x = [*shoulder.x[-1], *elbow.x[-1]]
    assert energy(x) == pytest.approx(e0, abs=1e-6 * (1 + abs(e0)))
    assert abs(x[0] - 0.3) > 0.1  # it did swing


def test_simulate_joints_flags_divergence_and_names_bad_input():
    unstable = [
        SimpleNamespace(dt=1e-3, order=2, step=lambda e, applied=None: 50.0 * e) for _ in range(2)
    ]
    out = simulate_joints(two_link_arm(), unstable, 3.0, [famcc.Constant(0.5)] * 2, diverge_at=10.0)
    assert all(r.diverged for r in out) and len(out[0].t) < 3001
    with pytest.raises(ValueError, match="one entry per joint"):
        simulate_joints(two_link_arm(), unstable[:1], 1.0, [famcc.Constant(0.5)])
