"""Fixed facts of the world: where the robot stands, the table, the hands' reach, joint names.

World frame: +x forward (away from the robot), +y to the robot's left, +z up; the table top is z = 0.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

Side = Literal["left", "right"]
SIDES: tuple[Side, Side] = ("left", "right")
OTHER_SIDE: dict[Side, Side] = {"left": "right", "right": "left"}

# The robot's base (the joint between pelvis and torso) stands here, facing +x (paper, scene prompt).
ROBOT_BASE_POS = np.array([-0.85, 0.0, 0.0])
TABLE_TOP_Z = 0.0

# Table top extent: covers both hands' operable ranges with margin and stays clear of the torso.
TABLE_X = (-0.62, 0.20)
TABLE_Y = (-0.80, 0.80)
TABLE_THICKNESS = 0.04


@dataclass(frozen=True)
class Range2D:
    """An axis-aligned rectangle on the table, in metres."""

    x: tuple[float, float]
    y: tuple[float, float]

    def contains(self, p: np.ndarray, tol: float = 0.0) -> bool:
        return (self.x[0] - tol <= p[0] <= self.x[1] + tol) and (self.y[0] - tol <= p[1] <= self.y[1] + tol)


# Where each hand can work (paper, scene-generation notes).
OPERABLE_RANGE: dict[Side, Range2D] = {
    "left": Range2D(x=(-0.42, -0.19), y=(-0.07, 0.36)),
    "right": Range2D(x=(-0.42, -0.19), y=(-0.36, 0.07)),
}

_ARM_JOINT_SUFFIXES = (
    "shoulder_pitch",
    "shoulder_roll",
    "shoulder_yaw",
    "elbow_pitch",
    "elbow_roll",
    "wrist_pitch",
    "wrist_yaw",
)
ARM_JOINTS: dict[Side, tuple[str, ...]] = {
    side: tuple(f"{side}_{s}_joint" for s in _ARM_JOINT_SUFFIXES) for side in SIDES
}

# The Inspire hand's six actuated joints; the other six follow by mimic couplings (URDF).
HAND_DOF_NAMES = ("thumb_yaw", "thumb_pitch", "index", "middle", "ring", "pinky")
_HAND_JOINT_STEMS = (
    "thumb_proximal_yaw",
    "thumb_proximal_pitch",
    "index_proximal",
    "middle_proximal",
    "ring_proximal",
    "pinky_proximal",
)
HAND_PREFIX: dict[Side, str] = {"left": "L", "right": "R"}
HAND_JOINTS: dict[Side, tuple[str, ...]] = {
    side: tuple(f"{HAND_PREFIX[side]}_{s}_joint" for s in _HAND_JOINT_STEMS) for side in SIDES
}

# End-effector frames, named as in the paper's planner API.
HAND_BASE_FRAME: dict[Side, str] = {"left": "l_hand_base_link", "right": "r_hand_base_link"}
WRIST_BODY: dict[Side, str] = {"left": "left_wrist_yaw_link", "right": "right_wrist_yaw_link"}
# Pose of the hand base on the wrist-yaw link (from the upstream MJCF's hand mesh placement).
HAND_BASE_ON_WRIST_POS = (0.054, 0.0, 0.0)
HAND_BASE_ON_WRIST_QUAT = (0.7071067811865476, 0.0, 0.0, 0.7071067811865476)


def arm_bodies(side: Side) -> tuple[str, ...]:
    """Bodies of one arm, shoulder to wrist (hand bodies not included)."""
    return tuple(j.replace("_joint", "_link") for j in ARM_JOINTS[side])

# Palm geometry on the wrist-yaw link (from the hand-base mesh: palm spans x 0.054..0.196, y +-0.027).
# The thumb sits on the palm side: local -y for the left hand, +y for the right.
PALM_SIGN: dict[Side, float] = {"left": -1.0, "right": 1.0}


def palm_center_on_wrist(side: Side) -> np.ndarray:
    """A point on the palm surface, midway along the palm, in the wrist-yaw link frame."""
    return np.array([0.125, PALM_SIGN[side] * 0.03, 0.0])


def palm_normal_on_wrist(side: Side) -> np.ndarray:
    """Unit normal of the palm, pointing out of the palm side, in the wrist-yaw link frame."""
    return np.array([0.0, PALM_SIGN[side], 0.0])
