"""A MuJoCo model as a plant: :class:`MuJoCo` (``pip install famcc[mujoco]``).

The input is one actuator's control, the output one hinge or slide joint's
position; between two samples MuJoCo steps the model at its own timestep
(``model.opt.timestep``) with the control held. The loop keeps MuJoCo's
whole state (every ``qpos``, ``qvel`` and ``act``), so each run restarts from
``x0`` and lanes share one model.

Examples
--------
>>> import famcc
>>> from famcc.plants import MuJoCo
>>> PENDULUM = '''
... <mujoco>
...   <option timestep="0.001"/>
...   <worldbody><body><joint name="hinge" type="hinge" axis="0 1 0" damping="0.05"/>
...     <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.02" mass="0.5"/></body>
...   </worldbody>
...   <actuator><motor name="torque" joint="hinge" ctrlrange="-2 2"/></actuator>
... </mujoco>'''
>>> plant = MuJoCo(PENDULUM, actuator="torque", x0=[0.5, 0.0])
>>> plant.order, plant.joint_name, round(plant.gain_and_drift(0.0, plant.x0)[0], 2)
(2, 'hinge', 63.47)
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from famcc.plants.stepped import Stepped, lanes_of

__all__ = ["MuJoCo"]

#: The input step of :meth:`MuJoCo.gain_and_drift`'s finite difference.
GAIN_PROBE = 1e-3


def _mujoco() -> Any:
    try:
        import mujoco  # type: ignore[import-untyped,unused-ignore]
    except ImportError as exc:  # pragma: no cover - the extra is installed in the tests
        raise ImportError(
            "famcc.plants.MuJoCo needs the mujoco package: pip install 'famcc[mujoco]'"
        ) from exc
    return mujoco


def _model(mj: Any, model: Any) -> Any:
    if isinstance(model, mj.MjModel):
        return model
    if isinstance(model, os.PathLike) or (
        isinstance(model, str) and not model.lstrip().startswith("<")
    ):
        return mj.MjModel.from_xml_path(os.fspath(model))
    if isinstance(model, str):
        return mj.MjModel.from_xml_string(model)
    raise TypeError(f"model must be a mujoco.MjModel, an MJCF XML string or a path, got {model!r}")


def _names(mj: Any, model: Any, kind: Any, count: int) -> list[str]:
    return [mj.mj_id2name(model, kind, i) or f"#{i}" for i in range(count)]


def check_names(kind: str, given: Any, names: Sequence[str]) -> int:
    """The index of ``given`` (a name or an index) among ``names``."""
    if isinstance(given, str):
        if given not in names:
            raise ValueError(f"{kind} {given!r} is not in the model; it has {list(names)}")
        return list(names).index(given)
    if isinstance(given, (int, np.integer)) and not isinstance(given, bool):
        if not 0 <= int(given) < len(names):
            raise ValueError(f"{kind} index {given} is out of range: the model has {len(names)}")
        return int(given)
    raise TypeError(f"{kind} must be a name or an index, got {given!r}")


class MuJoCo(Stepped):
    """One actuator's control in, one joint's position out, of a MuJoCo model.

    Parameters
    ----------
    model : mujoco.MjModel, str or path
        The model, its MJCF XML, or the path of an MJCF file.
    actuator : str or int
        The input: the actuator's name or index (default the first).
    joint : str, int or None
        The output: a hinge or slide joint's name or index. None: the joint
        the actuator drives.
    order : int
        The relative degree from the control to the joint position: 2 for a
        force or torque actuator (the default), 3 with a first-order
        activation, and so on.
    x0 : sequence of float or None
        The joint's ``(position, velocity)`` at the start (the other joints at
        the model's ``qpos0`` and at rest); None: the joint too.
    name, output, input
        As for :class:`Plant`; the output defaults to the joint's name in rad
        (hinge) or m (slide), the input to the actuator's name.

    Attributes
    ----------
    model : mujoco.MjModel
    joint_name, actuator_name : str

    Notes
    -----
    State layout: ``x = (q_j, other qpos..., q_j', other qvel..., act...)``,
    so ``y = x[0]`` and ``y' = x[nq]``. :meth:`output_derivatives` is exact at order 2 (the
    joint's position and velocity); :meth:`gain_and_drift` measures ``q_j'' =
    G u + F`` by a finite difference of MuJoCo's forward dynamics in the
    control (exact for MuJoCo's affine actuators).
    """

    def __init__(
        self,
        model: Any,
        *,
        actuator: str | int = 0,
        joint: str | int | None = None,
        order: int = 2,
        x0: Sequence[float] | None = None,
        name: str = "mujoco",
        output: Any = None,
        input: Any = None,
    ) -> None:
        mj = _mujoco()
        self._mj = mj
        self.model = m = _model(mj, model)
        if m.nu < 1:
            raise ValueError("the model has no actuator; famcc needs one as its input")
        self.actuator = check_names(
            "actuator", actuator, _names(mj, m, mj.mjtObj.mjOBJ_ACTUATOR, m.nu)
        )
        if joint is None:
            if int(m.actuator_trntype[self.actuator]) != int(mj.mjtTrn.mjTRN_JOINT):
                raise ValueError("the actuator does not drive a joint: give joint=")
            joint = int(m.actuator_trnid[self.actuator, 0])
        self.joint = check_names("joint", joint, _names(mj, m, mj.mjtObj.mjOBJ_JOINT, m.njnt))
        kind = int(m.jnt_type[self.joint])
        if kind not in (int(mj.mjtJoint.mjJNT_HINGE), int(mj.mjtJoint.mjJNT_SLIDE)):
            raise ValueError("joint must be a hinge or a slide joint (one degree of freedom)")
        self.joint_name = _names(mj, m, mj.mjtObj.mjOBJ_JOINT, m.njnt)[self.joint]
        self.actuator_name = _names(mj, m, mj.mjtObj.mjOBJ_ACTUATOR, m.nu)[self.actuator]
        q, v = int(m.jnt_qposadr[self.joint]), int(m.jnt_dofadr[self.joint])
        others_q = [i for i in range(m.nq) if i != q]
        others_v = [i for i in range(m.nv) if i != v]
        self._q = np.array([q, *others_q])
        self._v = np.array([v, *others_v])
        self._data = mj.MjData(m)
        start = np.concatenate([m.qpos0[self._q], np.zeros(m.nv), np.zeros(m.na)])
        if x0 is not None:
            pair = np.asarray(x0, dtype=np.float64).reshape(-1)
            if pair.shape != (2,) or not np.all(np.isfinite(pair)):
                raise ValueError(f"x0 must be the joint's finite (position, velocity), got {x0!r}")
            start[0], start[m.nq] = pair
        unit = "rad" if kind == int(mj.mjtJoint.mjJNT_HINGE) else "m"
        super().__init__(
            order,
            start.tolist(),
            name,
            output=output if output is not None else (self.joint_name, unit),
            input=input if input is not None else self.actuator_name,
        )

    def substeps_of(self, dt: float) -> int:
        """MuJoCo steps per sample period ``dt``: a whole number, else a ValueError."""
        h = float(self.model.opt.timestep)
        n = round(dt / h)
        if n < 1 or abs(n * h - dt) > 1e-9 * dt:
            raise ValueError(
                f"dt ({dt:g} s) must be a whole multiple of the model's timestep ({h:g} s), "
                f"e.g. dt = {max(n, 1) * h:g}; or set <option timestep=...> to divide dt"
            )
        return n

    def _load(self, t: float, x: np.ndarray, u: float) -> Any:
        m, d = self.model, self._data
        d.time = t
        d.qpos[self._q] = x[: m.nq]
        d.qvel[self._v] = x[m.nq : m.nq + m.nv]
        if m.na:
            d.act[:] = x[m.nq + m.nv :]
        d.ctrl[:] = 0.0
        d.ctrl[self.actuator] = u
        return d

    def _state(self) -> np.ndarray:
        d = self._data
        return np.concatenate([d.qpos[self._q], d.qvel[self._v], d.act])

    def advance(self, t: float, x: np.ndarray, u: Any, dt: float) -> np.ndarray:
        n = self.substeps_of(float(dt))
        xs, us, one = lanes_of(x, u)
        out = np.empty_like(xs)
        for lane in range(xs.shape[1]):
            self._load(t, xs[:, lane], float(us[lane]))
            for _ in range(n):
                self._mj.mj_step(self.model, self._data)
            out[:, lane] = self._state()
        return out[:, 0] if one else out

    def output_derivatives(self, t: float, x: np.ndarray) -> np.ndarray:
        if self.order != 2:
            raise NotImplementedError("exact output derivatives only at order 2")
        return np.array([x[0], x[self.model.nq]])

    def gain_and_drift(self, t: float, x: np.ndarray) -> tuple[float, float]:
        if self.order != 2:
            raise NotImplementedError("the gain and drift only at order 2")
        m = self.model
        lo, hi = (-np.inf, np.inf)
        if m.actuator_ctrllimited[self.actuator]:
            lo, hi = (float(c) for c in m.actuator_ctrlrange[self.actuator])
        u0 = min(max(0.0, lo), hi)
        u1 = u0 + GAIN_PROBE if u0 + GAIN_PROBE <= hi else u0 - GAIN_PROBE
        acc = []
        for u in (u0, u1):
            self._mj.mj_forward(m, self._load(t, np.asarray(x, dtype=np.float64), u))
            acc.append(float(self._data.qacc[self._v[0]]))
        g = (acc[1] - acc[0]) / (u1 - u0)
        return g, acc[0] - g * u0
