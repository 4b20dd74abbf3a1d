"""famcc.interop.to_nlsys: a famcc controller as a python-control system."""

from __future__ import annotations

import copy
import importlib
import sys

import control
import famcc
import numpy as np
import pytest
from famcc.interop import state_labels, to_nlsys


def _controllers():
    yield famcc.scenarios.paper("finite-time").controller(dt=1e-3)
    yield famcc.scenarios.paper("variable-exponent").controller(dt=2e-3)
    yield famcc.scenarios.paper("rfc").controller(dt=1e-3)
    yield famcc.Controller(2, 1e-3, famcc.Linear(2.0), eps=0.2, k_u=3.0, dtype="float32")


def _errors(n: int, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 1e-3
    return np.exp(-t) * np.cos(3.0 * t) - 0.8 + 0.01 * rng.standard_normal(n)


@pytest.mark.parametrize("ctrl", list(_controllers()), ids=lambda c: f"n{c.order}-{c.dtype}")
def test_response_equals_stepping_directly(ctrl):
    sys_ = to_nlsys(ctrl)
    assert sys_.dt == ctrl.dt
    assert (sys_.ninputs, sys_.noutputs, sys_.nstates) == (
        1,
        1,
        len(famcc._core.STATE_FIELDS) + ctrl.order,
    )
    assert sys_.input_labels == ["e"] and sys_.output_labels == ["v"]
    n = 400
    e = _errors(n)
    t = np.arange(n) * ctrl.dt
    resp = control.input_output_response(sys_, t, e, initial_state=ctrl.state(), return_states=True)
    twin = copy.copy(ctrl)
    v, states = [], []
    for ek in e:
        states.append(twin.state())
        v.append(twin.step(float(ek)))
    # Sample by sample, bit for bit: output v[k] from x[k] and e[k], state x[k].
    assert np.array_equal(resp.outputs, np.array(v))
    assert np.array_equal(resp.states, np.array(states).T)
    # The wrapped controller itself was not touched.
    assert ctrl.time == 0.0


def test_functions_are_pure():
    ctrl = famcc.scenarios.paper("finite-time").controller()
    sys_ = to_nlsys(ctrl)
    x0 = ctrl.state()
    v0 = sys_.output(0.0, x0, [0.3])
    x1 = sys_.dynamics(0.0, x0, [0.3])
    # Other calls in between, then the same arguments again: the same results.
    sys_.dynamics(0.0, x1, [-5.0])
    sys_.output(0.0, x1, [2.0])
    assert np.array_equal(sys_.output(0.0, x0, [0.3]), v0)
    assert np.array_equal(sys_.dynamics(0.0, x0, [0.3]), x1)
    # t and params are ignored: the controller's clock is in its state.
    assert np.array_equal(sys_.output(5.0, x0, [0.3], params={"a": 1}), v0)
    assert np.array_equal(x0, ctrl.state())
    # Mutating the returned state does not corrupt later evaluations.
    x1[:] = 0.0
    assert not np.array_equal(sys_.dynamics(0.0, x0, [0.3]), x1)


def test_closed_loop_equals_manual_loop():
    dt = 1e-3
    ctrl = famcc.Controller(
        2, dt, famcc.FiniteTime(k=1.0, p=0.5), constraint="lateral", eps=0.1, k_u=5.0
    )
    plant_d = control.c2d(control.ss([[0, 1], [-1, -0.5]], [[0], [2]], [[1, 0]], 0), dt)
    plant = control.ss(plant_d, inputs="u", outputs="y", name="plant")
    err = control.summing_junction(inputs=["y", "-r"], output="e")
    loop = control.interconnect(
        [plant, err, to_nlsys(ctrl, inputs="e", outputs="u")],
        inplist="r",
        outlist=["y", "u"],
        dt=dt,
    )
    n = 2200
    t = np.arange(n) * dt
    r = 0.5 * np.ones(n)
    x0 = np.concatenate(([-1.0, 0.0], ctrl.state()))
    resp = control.input_output_response(loop, t, r, initial_state=x0)
    y_cl, u_cl = resp.outputs

    A, B, C = (np.asarray(m) for m in (plant_d.A, plant_d.B, plant_d.C))
    x = np.array([-1.0, 0.0])
    y_man, u_man = [], []
    for k in range(n):
        y = float((C @ x)[0])
        u = ctrl.step(y - r[k])
        y_man.append(y)
        u_man.append(u)
        x = A @ x + B[:, 0] * u
    assert np.array_equal(u_cl, np.array(u_man))
    np.testing.assert_allclose(y_cl, y_man, rtol=0, atol=1e-12)
    assert abs(y_man[-1] - 0.5) < 0.1  # and the loop does its job


def test_state_labels_and_names():
    ctrl = famcc.scenarios.paper("rfc").controller()
    sys_ = to_nlsys(ctrl, name="ctl", inputs=["err"], outputs=("cmd",))
    assert sys_.name == "ctl"
    assert sys_.input_labels == ["err"] and sys_.output_labels == ["cmd"]
    assert sys_.state_labels == state_labels(ctrl)
    assert state_labels(ctrl)[:3] == ["started", "t_base", "k"]
    assert state_labels(ctrl)[-3:] == ["z_hat[0]", "z_hat[1]", "z_hat[2]"]
    assert len(state_labels(ctrl)) == len(ctrl.state())


def test_bad_arguments():
    ctrl = famcc.scenarios.paper("finite-time").controller()
    with pytest.raises(ValueError, match="inputs"):
        to_nlsys(ctrl, inputs=("e", "applied"))
    with pytest.raises(ValueError, match="outputs"):
        to_nlsys(ctrl, outputs=())
    with pytest.raises(TypeError):
        to_nlsys(ctrl, "name")  # type: ignore[misc]
    sys_ = to_nlsys(ctrl)
    # The default zero initial state is not a valid controller state.
    with pytest.raises(ValueError, match="initial_state=controller.state"):
        control.input_output_response(sys_, np.arange(3) * ctrl.dt, np.zeros(3))
    with pytest.raises(famcc.StepError):
        sys_.output(0.0, ctrl.state(), [np.nan])


def test_missing_python_control_gives_a_helpful_import_error(monkeypatch):
    from famcc import interop

    monkeypatch.setitem(sys.modules, "control", None)  # makes `import control` fail
    importlib.reload(interop)  # the module itself imports fine
    ctrl = famcc.scenarios.paper("finite-time").controller()
    with pytest.raises(ImportError, match="pip install control"):
        interop.to_nlsys(ctrl)
    monkeypatch.undo()
    importlib.reload(interop)
    assert interop.to_nlsys(ctrl).dt == ctrl.dt


def test_lazy_attribute_on_the_package():
    # famcc.__getattr__ loads famcc.interop on first use.
    assert callable(famcc.interop.to_nlsys)
