"""Plants that advance themselves (famcc.plants.Stepped, BlackBox, MuJoCo):
the loop steps them by their own update, equal to the same plant integrated
from its right-hand side, and a MuJoCo pendulum tuned through the adapter
holds its eps within the requested time."""

from __future__ import annotations

import famcc
import numpy as np
import pytest
from famcc.plants import BlackBox, MuJoCo, Plant, Stepped
from hypothesis import given, settings
from hypothesis import strategies as st

mujoco = pytest.importorskip("mujoco")

LIMITS = (-5.0, 5.0)


def pd_design() -> famcc.Design:
    return famcc.design(
        2, 1e-3, u_limits=LIMITS, eps=0.02, settle_time=3.0, hold_input=1.0, gain=1.0
    )


class Smooth(Plant):
    """``y'' = u - 0.5 y'`` through its right-hand side (integrated by RK4)."""

    def rhs(self, t: float, x: np.ndarray, u: float) -> np.ndarray:
        return np.array([x[1], u - 0.5 * x[1]])


class SmoothExact(Stepped):
    """The same plant advanced by its exact zero-order-hold map."""

    def advance(self, t: float, x: np.ndarray, u: float, dt: float) -> np.ndarray:
        a = 0.5
        decay = np.exp(-a * dt)
        v = u / a + (x[1] - u / a) * decay
        p = x[0] + u / a * dt + (x[1] - u / a) * (1.0 - decay) / a
        return np.array([p, v])


@settings(max_examples=15, deadline=None)
@given(
    p0=st.floats(-2.0, 2.0),
    v0=st.floats(-2.0, 2.0),
    target=st.floats(-1.0, 1.0),
)
def test_an_exact_update_equals_the_rk4_integration_of_the_same_plant(
    p0: float, v0: float, target: float
) -> None:
    ref = famcc.Constant(target)
    ode = famcc.simulate(
        Smooth(2, [p0, v0]), pd_design().controller(), 2.0, reference=ref, u_limits=LIMITS
    )
    ex = famcc.simulate(
        SmoothExact(2, [p0, v0]), pd_design().controller(), 2.0, reference=ref, u_limits=LIMITS
    )
    # RK4 with 10 substeps against the exact map: equal to integration error
    assert np.max(np.abs(ode.y - ex.y)) < 1e-8
    assert np.max(np.abs(ode.u - ex.u)) < 1e-6


class Cart:
    """A stateful box: ``p'' = u`` with a step load after 1 s (an ``if``)."""

    def __init__(self) -> None:
        self.resets = 0

    def reset(self) -> float:
        self.resets += 1
        self.t, self.p, self.v = 0.0, 1.0, 0.0
        return self.p

    def step(self, u: float, dt: float) -> float:
        load = -0.4 if self.t >= 1.0 else 0.0
        a = u + load
        self.p += self.v * dt + 0.5 * a * dt * dt
        self.v += a * dt
        self.t += dt
        return self.p


def test_a_black_box_restarts_at_every_run_and_holds_eps_through_its_load() -> None:
    box = Cart()
    plant = BlackBox(box, order=2, name="cart")
    runs = [
        famcc.simulate(
            plant, pd_design().controller(), 6.0, reference=famcc.Constant(0.0), u_limits=LIMITS
        )
        for _ in range(2)
    ]
    assert box.resets >= 3  # once to check it, once per run
    np.testing.assert_array_equal(runs[0].y, runs[1].y)
    late = runs[0].t >= 4.5
    assert np.max(np.abs(runs[0].z[late, 0])) < 0.02
    assert np.isnan(runs[0].z[:, 1]).all()  # a box has no exact derivatives


class Bad:
    def __init__(self, out: object) -> None:
        self.out = out

    def reset(self) -> float:
        return 0.5

    def step(self, u: float, dt: float) -> object:
        return self.out


@pytest.mark.parametrize("out", ["3", None, [1.0, 2.0]])
def test_a_black_box_returning_no_number_is_named(out: object) -> None:
    plant = BlackBox(Bad(out), order=2)
    with pytest.raises(FloatingPointError, match=r"step\(u, dt\) must return a real output"):
        famcc.simulate(
            plant, pd_design().controller(), 0.1, reference=famcc.Constant(0.0), record=False
        )


def test_a_black_box_without_the_protocol_or_a_finite_start_is_refused() -> None:
    with pytest.raises(TypeError, match=r"reset\(\)"):
        BlackBox(object(), order=1)

    class NanStart(Bad):
        def reset(self) -> float:
            return float("nan")

    with pytest.raises(ValueError, match="finite real output"):
        BlackBox(NanStart(0.0), order=1)


PENDULUM = """
<mujoco>
  <option timestep="0.001"/>
  <worldbody>
    <body pos="0 0 1">
      <joint name="hinge" type="hinge" axis="0 1 0" damping="0.05"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.02" mass="0.5"/>
      <body pos="0 0 -0.3">
        <joint name="elbow" type="hinge" axis="0 1 0" damping="0.2"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.2" size="0.015" mass="0.1"/>
      </body>
    </body>
  </worldbody>
  <actuator><motor name="torque" joint="hinge" ctrlrange="-3 3" ctrllimited="true"/></actuator>
</mujoco>
"""


def test_mujoco_steps_the_model_and_measures_its_gain_from_the_mass_matrix() -> None:
    plant = MuJoCo(PENDULUM, actuator="torque", x0=[0.4, -0.2])
    model = plant.model
    assert (plant.order, plant.joint_name, plant.output.unit) == (2, "hinge", "rad")
    x0 = plant.x0
    assert x0.shape == (model.nq + model.nv,) and (x0[0], x0[model.nq]) == (0.4, -0.2)
    # G = (M^-1)[j, j] for a motor on the joint: from MuJoCo's mass matrix
    data = mujoco.MjData(model)
    data.qpos[:] = [0.4, 0.0]
    data.qvel[:] = [-0.2, 0.0]
    mujoco.mj_forward(model, data)
    m_inv = np.zeros((model.nv, model.nv))
    mujoco.mj_solveM(model, data, m_inv, np.eye(model.nv))
    g, _ = plant.gain_and_drift(0.0, x0)
    assert g == pytest.approx(m_inv[0, 0], rel=1e-6)
    # one sample of 2 ms is two MuJoCo steps with the control held
    x1 = plant.advance(0.0, x0, 0.7, 2e-3)
    data.ctrl[:] = 0.7
    mujoco.mj_step(model, data)
    mujoco.mj_step(model, data)
    np.testing.assert_allclose(x1, [data.qpos[0], data.qpos[1], data.qvel[0], data.qvel[1]])
    # two lanes at once are two single lanes
    both = plant.advance(0.0, np.stack([x0, x1], axis=1), np.array([0.7, -1.0]), 2e-3)
    np.testing.assert_allclose(both[:, 0], x1)
    np.testing.assert_allclose(both[:, 1], plant.advance(0.0, x1, -1.0, 2e-3))


def test_mujoco_names_a_bad_actuator_joint_or_sample_period() -> None:
    with pytest.raises(ValueError, match=r"actuator 'motor' is not in the model.*'torque'"):
        MuJoCo(PENDULUM, actuator="motor")
    with pytest.raises(ValueError, match="joint 'knee' is not in the model"):
        MuJoCo(PENDULUM, joint="knee")
    plant = MuJoCo(PENDULUM, joint="elbow")
    assert plant.joint_name == "elbow"
    with pytest.raises(ValueError, match=r"dt \(0.0015 s\) must be a whole multiple.*0.001"):
        plant.substeps_of(1.5e-3)
    with pytest.raises(TypeError, match="MjModel, an MJCF XML string or a path"):
        MuJoCo(3.0)


def test_a_mujoco_pendulum_tuned_through_the_adapter_settles_within_the_requested_time(
    tmp_path: object,
) -> None:
    import pathlib

    path = pathlib.Path(str(tmp_path)) / "pendulum.xml"
    path.write_text(PENDULUM)
    plant = MuJoCo(path, actuator="torque", x0=[0.0, 0.0])  # from a file
    ref, eps, settle = famcc.Constant(1.0), 0.01, 1.5
    d = famcc.tune(
        plant,
        dt=2e-3,
        u_limits=(-3, 3),
        eps=eps,
        settle_time=settle,
        reference=ref,
        progress=False,
    )
    res = famcc.simulate(plant, d.controller(), 3.0, reference=ref, u_limits=(-3, 3))
    late = res.t >= settle
    assert np.max(np.abs(res.z[late, 0])) < eps
    assert next(f for f in d.checks if f.name == "tune").level == "ok"
