"""Fixed facts of the world: where the robot stands, the table, the hands' reach, joint names.

World frame: +x forward (away from the robot), +y to the robot's left, +z up; the table top is z = 0.
The robot's facts are its data file's (`robots/h1_2_inspire/robot.yaml` and its hand file, the default robot):
the names here are derived from it, for the modules that import them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from humanoidgen.robots import default_robot

Side = Literal["left", "right"]
SIDES: tuple[Side, Side] = ("left", "right")
OTHER_SIDE: dict[Side, Side] = {"left": "right", "right": "left"}

ROBOT = default_robot()
# The robot's base (the joint between its root body and torso) stands here, facing +x (paper, scene prompt).
ROBOT_BASE_POS = np.array(ROBOT.data.stand.base_pos)
ROOT_BODY = ROBOT.data.stand.root_body
TORSO_BODIES: tuple[str, ...] = tuple(ROBOT.data.torso_bodies)  # what feedback calls "the torso"
TABLE_TOP_Z = 0.0

# Table top extent: covers both hands' operable ranges with margin and stays clear of the torso (a robot that
# stands closer gives its own near edge: `stand.table_x`).
TABLE_X = tuple(ROBOT.data.stand.table_x) if ROBOT.data.stand.table_x is not None else (-0.62, 0.20)
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
    side: Range2D(x=ROBOT.data.stand.operable_range[side].x, y=ROBOT.data.stand.operable_range[side].y)
    for side in SIDES
}

ARM_JOINTS: dict[Side, tuple[str, ...]] = {side: ROBOT.arm_joints[side] for side in SIDES}

# The hand's actuated joints; the others follow by couplings (the hand file's `followers`).
HAND_DOF_NAMES = ROBOT.hand.dof_names
HAND_PREFIX: dict[Side, str] = {side: ROBOT.hand_prefix[side] for side in SIDES}
HAND_JOINTS: dict[Side, tuple[str, ...]] = {side: ROBOT.hand_joints[side] for side in SIDES}

# End-effector frames, named as in the paper's planner API.
HAND_BASE_FRAME: dict[Side, str] = {side: ROBOT.hand_frame(side) for side in SIDES}
# The bodies the hands are mounted on (their palms).
WRIST_BODY: dict[Side, str] = {side: ROBOT.hand_mount(side) for side in SIDES}
# Pose of the hand base on its mount (from the upstream MJCF's hand mesh placement).
HAND_BASE_ON_WRIST_POS = ROBOT.data.hands.hand_base.pos
HAND_BASE_ON_WRIST_QUAT = ROBOT.data.hands.hand_base.quat
# The links that carry the fingertips the planner watches (thumb and index: they meet in a pinch).
FINGERTIP_BODY: dict[Side, dict[str, str]] = {
    side: {f: ROBOT.hand_link(side, ROBOT.hand.data.fingers[f][-1]) for f in ROBOT.hand.data.fingers} for side in SIDES
}


def arm_bodies(side: Side) -> tuple[str, ...]:
    """Bodies of one arm, shoulder to wrist (hand bodies not included)."""
    return ROBOT.arm_links[side]


# The thumb sits on the palm side: local -y for the left hand, +y for the right (the hand file's frame).
PALM_SIGN: dict[Side, float] = {side: ROBOT.hand.palm_sign(side) for side in SIDES}


def palm_center_on_wrist(side: Side) -> np.ndarray:
    """A point on the palm surface, midway along the palm, in the wrist-yaw link frame."""
    return ROBOT.hand.points(side)[ROBOT.hand.data.palm.point.format(side=side)]


def palm_normal_on_wrist(side: Side) -> np.ndarray:
    """Unit normal of the palm, pointing out of the palm side, in the wrist-yaw link frame."""
    return ROBOT.hand.axes(side)[ROBOT.hand.data.palm.normal.format(side=side)]
