"""End-effector poses and straight SE(3) ("screw") interpolation between them. Pure functions."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from humanoidgen.sim.geometry import axis_angle_mat, mat_to_quat, quat_to_mat, rotation_error

if TYPE_CHECKING:
    from humanoidgen.planning.part_joint import PartFollow
    from humanoidgen.planning.regrip_request import RegripRequest


@dataclass
class Pose:
    """A pose of a hand's end-effector frame in the world: position `p`, quaternion `q` (w, x, y, z).

    Poses from the goal solver also carry the arm joints that reach them (`joint_q`) and how they were made,
    so that a move can approach along the operation's axis or follow an articulated part.
    """

    p: np.ndarray
    q: np.ndarray
    joint_q: np.ndarray | None = None
    side: str | None = None
    approach_axis: np.ndarray | None = None  # world direction the hand approaches along (grasp, pinch)
    approach_object: str | None = None  # body the hand may touch at the end of the approach
    approach_part: str | None = None  # the joint of the articulated part it comes to grip (that part gives way)
    follow: PartFollow | None = field(default=None, repr=False)  # articulated part path: body, joint, q0, q1
    posture: str | None = None  # finger posture for closing on the object there (e.g. "wrap")
    # The fingers may come this much closer to the table than the general clearance on the way to this pose
    # (a goal that needs a fingertip at a low edge; goal_search.FINGER_TABLE_CLEARANCE).
    finger_table_slack: float = 0.0
    # A press's goal presses the fingertip into approach_object (a lever pushed down): the move goes straight on
    # and may touch it (press_intent).
    presses: bool = False
    # A held part moved only partway by this pose (the arm's reach ends): what the move does next, gripping it
    # again to move it on (recoveries/grip_again.py).
    regrip: RegripRequest | None = field(default=None, repr=False)
    push: Any = field(default=None, repr=False)  # a task's push on a part this pose starts (push_actions.mark)

    def __post_init__(self) -> None:
        self.p = np.asarray(self.p, float).reshape(3)
        self.q = np.asarray(self.q, float).reshape(4)
        self.q = self.q / np.linalg.norm(self.q)

    @classmethod
    def from_mat(cls, p: np.ndarray, R: np.ndarray, **kw) -> "Pose":
        return cls(p=p, q=mat_to_quat(R), **kw)

    @property
    def R(self) -> np.ndarray:
        return quat_to_mat(self.q)


def pose_distance(a: Pose, b: Pose) -> tuple[float, float]:
    """Translation (m) and rotation (rad) between two poses."""
    return float(np.linalg.norm(a.p - b.p)), float(np.linalg.norm(rotation_error(a.R, b.R)))


def _rot_from_vec(w: np.ndarray) -> np.ndarray:
    angle = np.linalg.norm(w)
    if angle < 1e-12:
        return np.eye(3)
    return axis_angle_mat(w / angle, angle)


def screw_interpolate(p0: np.ndarray, R0: np.ndarray, p1: np.ndarray, R1: np.ndarray, max_step: float = 0.01,
                      max_angle: float = 0.05) -> list[tuple[np.ndarray, np.ndarray]]:
    """Poses along the straight line from (p0, R0) to (p1, R1), rotation about a fixed axis; end included."""
    w = rotation_error(R0, R1)
    n = max(1, int(np.ceil(max(np.linalg.norm(p1 - p0) / max_step, np.linalg.norm(w) / max_angle))))
    return [(p0 + (p1 - p0) * s, _rot_from_vec(w * s) @ R0) for s in np.linspace(0, 1, n + 1)[1:]]
