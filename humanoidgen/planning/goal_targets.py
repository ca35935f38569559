"""Targets the planner itself gives the goal solver, in the solver's constraint interface (`side`, `soft`,
`name`, `evaluate`, `bounds`, `violation`, `describe`; soft ones also `cost`). Plan scripts use
`constraints.Constraint`; these need no env and are made during planning:

- `PoseTarget`: the end-effector frame onto a whole pose (a pre-approach pose, where a held part carries the hand);
- `AxisWithin`: a hand axis within an angle of a direction (a grip's exact axis relaxed into a cone), and as a
  soft cost, the same axis preferred exactly on it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.sim.layout import Side

POSE_POINT_TOL = 1e-3  # a pose target: the end effector within 1 mm
POSE_AXIS_TOL = np.sin(np.radians(0.5))  # and its x and y axes within half a degree


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


@dataclass
class PoseTarget:
    """A hard constraint of the end-effector frame onto a whole pose (p, R), in the solver's constraint
    interface. The planner's own goals use it (a pre-approach pose, the pose a held part carries the hand to);
    plan scripts use `Constraint`."""

    side: Side
    p: np.ndarray
    R: np.ndarray
    name: str = "end effector at the pose"
    soft: bool = False
    orient: bool = True  # False: the position only (the orientation left to other targets)

    def evaluate(self, kin: Kinematics) -> tuple[np.ndarray, np.ndarray]:
        p, R = kin.ee_pose(self.side)
        Jr = kin.rotation_jacobian(self.side)
        rows, jac = [p - self.p], [kin.point_jacobian(self.side, p)]
        for k in ((0, 1) if self.orient else ()):  # two axes fix the rotation; each as a 'parallel' residual
            rows.append(R[:, k] - self.R[:, k])
            jac.append(-_skew(R[:, k]) @ Jr)
        return np.concatenate(rows), np.vstack(jac)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        tol = np.concatenate([np.full(3, POSE_POINT_TOL), np.full(6 if self.orient else 0, POSE_AXIS_TOL)])
        return -tol, tol

    def violation(self, kin: Kinematics) -> float:
        v, _ = self.evaluate(kin)
        lo, hi = self.bounds()
        return float(np.max(np.maximum(lo - v, 0.0) + np.maximum(v - hi, 0.0)))

    def describe(self, kin: Kinematics) -> str:
        v, _ = self.evaluate(kin)
        return f"{self.name}: {np.linalg.norm(v[:3]) * 1000:.1f} mm from it"


@dataclass
class AxisWithin:
    """The hand axis `local_axis` (end-effector frame) within `limit` radians of the world direction `target`;
    with `soft=True`, a cost `weight * |axis - target|^2` instead (the exact direction, preferred)."""

    side: Side
    local_axis: np.ndarray
    target: np.ndarray
    limit: float
    name: str
    soft: bool = False
    weight: float = 2.0

    def _axis(self, kin: Kinematics) -> tuple[np.ndarray, np.ndarray]:
        _, R = kin.ee_pose(self.side)
        a = R @ self.local_axis
        return a, -_skew(a) @ kin.rotation_jacobian(self.side)  # d(a) = w x a = -[a]x w

    def evaluate(self, kin: Kinematics) -> tuple[np.ndarray, np.ndarray]:
        a, Ja = self._axis(kin)
        return np.array([float(a @ self.target)]), (self.target @ Ja)[None]

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array([np.cos(self.limit)]), np.array([1.0 + 1e-9])

    def violation(self, kin: Kinematics) -> float:
        v, _ = self.evaluate(kin)
        return float(max(np.cos(self.limit) - v[0], 0.0))

    def angle(self, kin: Kinematics) -> float:
        """Degrees between the axis and its target."""
        return float(np.degrees(np.arccos(np.clip(self.evaluate(kin)[0][0], -1.0, 1.0))))

    def describe(self, kin: Kinematics) -> str:
        return f"{self.name}: {self.angle(kin):.1f} deg, wanted at most {np.degrees(self.limit):.0f} deg"

    def cost(self, kin: Kinematics) -> tuple[float, np.ndarray]:
        a, Ja = self._axis(kin)
        r = a - self.target
        return float(self.weight * r @ r), 2.0 * self.weight * (r @ Ja)


def pose_within(side: Side, p: np.ndarray, R: np.ndarray, limit_deg: float, name: str) -> list:
    """Targets for a pose whose orientation may be off by up to `limit_deg` about any axis (preferred exact):
    the position exactly, the end effector's x and y axes each within the cone."""
    eye = np.eye(3)
    out: list = [PoseTarget(side, p, R, name=name, orient=False)]
    for k in (0, 1):
        out.append(AxisWithin(side, eye[:, k], R[:, k], np.radians(limit_deg), f"{name} axis {k}"))
        out.append(AxisWithin(side, eye[:, k], R[:, k], np.radians(limit_deg), f"{name} axis {k} (preferred)", soft=True))
    return out
