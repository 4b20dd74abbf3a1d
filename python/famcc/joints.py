"""Deprecated home of the joints: the arm is :func:`famcc.plants.two_link_arm`, the
simulator :func:`famcc.sim.joints.simulate_joints` (both re-exported here)."""

from famcc.plants.arm import TwoLinkArm, two_link_arm
from famcc.sim.joints import simulate_joints

__all__ = ["TwoLinkArm", "simulate_joints", "two_link_arm"]
