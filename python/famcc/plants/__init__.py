"""Plants for closed-loop simulation: each plant's dynamics written once.

The plants of the paper are strict-feedback systems (paper eq. SFS)::

    x_i' = g_i(x, t) x_{i+1} + f_i(x, t),   i = 1, ..., n-1
    x_n' = g_n(x, t) u + f_n(x, t)
    y    = x_1

With the fully actuated coordinates ``y, y', ..., y^(n-1)`` the plant reads
(paper eq. FAS) ``y^(n) = G_a u + F_a`` with ``G_a = g_1 g_2 ... g_n``. A
controller's error vector is ``Z = (z_1, ..., z_n)`` with ``z_i = y^(i-1) -
y_d^(i-1)`` and ``dz_n/dt = G u + F``, ``G = G_a``, ``F = F_a - y_d^(n)`` (paper
eq. FASe); ``-F/G`` is the input that would hold ``dz_n/dt = 0``.

=====================  ==================================================
module                 what it owns
=====================  ==================================================
:mod:`.base`           :class:`Plant`, the simulator's plant protocol
:mod:`.strict`         :class:`StrictFeedback` (callables) and exact derivatives by jets
:mod:`.paper`          the paper's plants, from famcc-paper (compiled)
:mod:`.model`          :class:`~famcc.plants.model.Model`: a plant written once
:mod:`.suite`          the physical suite (motor, pendulum, quadrotor, flexible joint)
:mod:`.arm`            the two-link arm (two inputs)
:mod:`.stepped`        plants that advance themselves: :class:`Stepped`, :class:`BlackBox`
:mod:`.mujoco`         :class:`MuJoCo`: a MuJoCo model's actuator and joint
:mod:`.family`         :class:`Family`: N plants of one definition
:mod:`.catalog`        the ready-made families (:func:`family`)
=====================  ==================================================

Examples
--------
>>> import numpy as np
>>> from famcc.plants import second_order
>>> plant = second_order("paper")
>>> plant.order, plant.variant
(2, 'paper')
>>> x = plant.x0
>>> plant.output_derivatives(0.0, x)          # (y, y') at t = 0
array([-1.        ,  1.52701512])
>>> g_a, f_a = plant.gain_and_drift(0.0, x)   # y'' = g_a u + f_a
>>> round(g_a, 6)
2.112398
"""

from famcc.plants.arm import TwoLinkArm, two_link_arm
from famcc.plants.base import Plant
from famcc.plants.catalog import FAMILIES, family, names
from famcc.plants.family import Family, FamilyPlant
from famcc.plants.model import Model, PhysicalPlant
from famcc.plants.mujoco import MuJoCo
from famcc.plants.paper import VARIANTS, PaperPlant, second_order, third_order
from famcc.plants.stepped import BlackBox, Stepped
from famcc.plants.strict import StrictFeedback
from famcc.plants.suite import dc_motor, flexible_joint, pendulum, quadrotor_altitude, smooth_step

__all__ = [
    "FAMILIES",
    "VARIANTS",
    "BlackBox",
    "Family",
    "FamilyPlant",
    "Model",
    "MuJoCo",
    "PaperPlant",
    "PhysicalPlant",
    "Plant",
    "Stepped",
    "StrictFeedback",
    "TwoLinkArm",
    "dc_motor",
    "family",
    "flexible_joint",
    "names",
    "pendulum",
    "quadrotor_altitude",
    "second_order",
    "smooth_step",
    "third_order",
    "two_link_arm",
]
