"""The paper's scene-scaling transform T_{O -> O'} (appendix, scene scaling) as pure functions.

Frame O: origin o on the table edge nearest the robot, below the robot's base (x = TABLE_X[0], y = 0, z = table
top); x points the way the robot faces, y along the edge to the robot's left, z up. Frame O' is the same
construction on a room's work surface. For a point p, a vector v or a pose P given in the tabletop world,
    alpha' = T_{O -> O'} alpha,  with  T_{O -> O'} = [O' in the room world] * [O in the tabletop world]^-1.

Which frame is which in this project: the simulator's world, the planner, every task spec and plan, and the
recorded observations (poses, end-effector poses, point clouds, camera extrinsics) all stay in the tabletop
world frame. A room is built around the task: its walls, floor and furniture are placed with the inverse
transform, so plans run unchanged. Episode metadata stores T_{O -> O'} so that anything recorded can be
mapped into the room's own coordinates with `apply_point` / `apply_vector` / `apply_pose`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from humanoidgen.sim.geometry import axis_angle_mat, mat_to_quat, quat_to_mat
from humanoidgen.sim.layout import TABLE_TOP_Z, TABLE_X


@dataclass(frozen=True)
class Rigid:
    """A rigid transform x -> R x + t (3x3 rotation, 3-vector)."""

    R: np.ndarray
    t: np.ndarray

    def to_dict(self) -> dict:
        return {"R": np.asarray(self.R).tolist(), "t": np.asarray(self.t).tolist()}

    @classmethod
    def from_dict(cls, d: dict) -> Rigid:
        return cls(np.asarray(d["R"], float), np.asarray(d["t"], float))


def frame(origin: np.ndarray, yaw: float) -> Rigid:
    """A frame with z up, turned by `yaw` about z, at `origin` (frame -> world)."""
    return Rigid(axis_angle_mat(np.array([0.0, 0.0, 1.0]), yaw), np.asarray(origin, float))


def table_frame() -> Rigid:
    """O: on the tabletop's near edge, under the robot, axes as the tabletop world's."""
    return frame(np.array([TABLE_X[0], 0.0, TABLE_TOP_Z]), 0.0)


def inverse(T: Rigid) -> Rigid:
    return Rigid(T.R.T, -T.R.T @ T.t)


def compose(A: Rigid, B: Rigid) -> Rigid:
    """A after B."""
    return Rigid(A.R @ B.R, A.R @ B.t + A.t)


def o_to_o_prime(o_prime: Rigid, o: Rigid | None = None) -> Rigid:
    """T_{O -> O'}: tabletop-world coordinates -> room-world coordinates."""
    return compose(o_prime, inverse(o if o is not None else table_frame()))


def apply_point(T: Rigid, p: np.ndarray) -> np.ndarray:
    """Points (..., 3)."""
    return np.asarray(p, float) @ T.R.T + T.t


def apply_vector(T: Rigid, v: np.ndarray) -> np.ndarray:
    """Directions and axes (..., 3): rotated, not moved."""
    return np.asarray(v, float) @ T.R.T


def apply_pose(T: Rigid, pos: np.ndarray, quat: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A pose given as position and quaternion (w, x, y, z)."""
    R = T.R @ quat_to_mat(np.asarray(quat, float))
    return apply_point(T, pos), mat_to_quat(R)


def yaw_of(T: Rigid) -> float:
    return math.atan2(T.R[1, 0], T.R[0, 0])
