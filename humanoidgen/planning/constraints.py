"""Relational constraints between the hand's action frame and the world (paper appendix, c(u_act, u_all)).

A hand point or axis (or a point or axis of an object the hand holds) is given in world coordinates at the
current state; it is stored in the end-effector frame and moves rigidly with it. Targets stay fixed in the
world. `Constraint` is hard (the goal solver must satisfy it within its bounds); `Const` is the same relation
as a weighted cost.

Types:
- `point2point`: hand point on target point (distance within [lower, upper], default exactly 0);
- `parallel`: hand axis along target axis (same direction);
- `point2line`: distance from the hand point to the line (object_key_point, object_axis);
- `line2point`: distance from the line (hand_key_point, hand_axis) to the object point;
- `angle`: angle between hand axis and target axis within [lower, upper] radians.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import weakref
from typing import Any

import numpy as np

from humanoidgen.planning.kinematics import Kinematics, side_of_frame
from humanoidgen.sim.layout import Side

TYPES = ("point2point", "parallel", "point2line", "line2point", "angle")
POINT_TOL = 1e-3  # metres: hard point constraints are satisfied to 1 mm
AXIS_TOL = np.sin(np.radians(0.5))  # parallel axes to half a degree


class ConstraintError(ValueError):
    """A constraint that cannot be built (missing or malformed arguments)."""


def _vec(name: str, v: Any, unit: bool = False) -> np.ndarray:
    try:
        a = np.asarray(v, dtype=float).reshape(3)
    except (TypeError, ValueError):
        raise ConstraintError(f"{name} must be a 3-vector, got {v!r}") from None
    if not np.all(np.isfinite(a)):
        raise ConstraintError(f"{name} must be finite, got {a}")
    if unit:
        n = np.linalg.norm(a)
        if n < 1e-9:
            raise ConstraintError(f"{name} must not be the zero vector")
        a = a / n
    return a


@dataclass
class Constraint:
    env: Any
    type: str
    end_effector_frame: str
    hand_key_point: Any = None
    object_key_point: Any = None
    hand_axis: Any = None
    object_axis: Any = None
    lower: float = 0.0
    upper: float = 0.0
    weight: float = 1.0
    soft: bool = field(default=False, init=False)
    name: str = ""
    side: Side = field(init=False)
    local_point: np.ndarray | None = field(init=False, default=None)
    local_axis: np.ndarray | None = field(init=False, default=None)
    # What generated it (constraint_gen.Generated: the approach axis, the part to follow, the grip's ways), set by
    # the planner on constraints it made; None on a plan's own.
    meta: Any = field(init=False, default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.type not in TYPES:
            raise ConstraintError(f"unknown constraint type {self.type!r}; use one of {', '.join(TYPES)}")
        try:
            self.side = side_of_frame(self.end_effector_frame)
        except ValueError as exc:
            raise ConstraintError(str(exc)) from None
        needs_point = self.type in ("point2point", "point2line", "line2point")
        needs_axis = self.type in ("parallel", "line2point", "angle")
        if needs_point:
            if self.hand_key_point is None or self.object_key_point is None:
                raise ConstraintError(f"{self.type} needs hand_key_point and object_key_point")
            self.hand_key_point = _vec("hand_key_point", self.hand_key_point)
            self.object_key_point = _vec("object_key_point", self.object_key_point)
        if needs_axis or self.type == "point2line":
            if self.type != "point2line" and self.hand_axis is None:
                raise ConstraintError(f"{self.type} needs hand_axis")
            if self.object_axis is None and self.type in ("parallel", "angle", "point2line"):
                raise ConstraintError(f"{self.type} needs object_axis")
            if self.hand_axis is not None:
                self.hand_axis = _vec("hand_axis", self.hand_axis, unit=True)
            if self.object_axis is not None:
                self.object_axis = _vec("object_axis", self.object_axis, unit=True)
        if self.lower > self.upper:
            raise ConstraintError(f"lower ({self.lower}) must not exceed upper ({self.upper})")
        # Anchor the hand-side elements to the end effector at the current state.
        kin = _kinematics_of(self.env)
        p, R = kin.ee_pose(self.side)
        if self.hand_key_point is not None:
            self.local_point = R.T @ (self.hand_key_point - p)
        if self.hand_axis is not None:
            self.local_axis = R.T @ self.hand_axis
        if not self.name:
            self.name = self.type

    # -- evaluation ---------------------------------------------------------------------------------
    def evaluate(self, kin: Kinematics) -> tuple[np.ndarray, np.ndarray]:
        """Residual value and its Jacobian over the 7 arm joints of this side, at `kin`'s state."""
        p, R = kin.ee_pose(self.side)
        t = self.type
        if t == "point2point":
            x = p + R @ self.local_point
            v = x - self.object_key_point
            if self.upper > 0:  # a distance band instead of coincidence
                d = np.linalg.norm(v)
                J = kin.point_jacobian(self.side, x)
                return np.array([d]), ((v / max(d, 1e-9)) @ J)[None]
            return v, kin.point_jacobian(self.side, x)
        if t == "parallel":
            a = R @ self.local_axis
            Jr = kin.rotation_jacobian(self.side)
            return a - self.object_axis, -_skew(a) @ Jr  # d(a) = w x a = -[a]x w
        if t == "angle":
            a = R @ self.local_axis
            Jr = kin.rotation_jacobian(self.side)
            c = float(a @ self.object_axis)
            # Bounds on the angle become bounds on its cosine (reversed); see bounds().
            return np.array([c]), (self.object_axis @ (-_skew(a) @ Jr))[None]
        if t == "point2line":
            x = p + R @ self.local_point
            u = self.object_axis
            r = x - self.object_key_point
            perp = r - (r @ u) * u
            d = np.linalg.norm(perp)
            J = kin.point_jacobian(self.side, x)
            return np.array([d]), ((perp / max(d, 1e-9)) @ (np.eye(3) - np.outer(u, u)) @ J)[None]
        # line2point: the hand's line moves; distance from the fixed object point to it
        x = p + R @ self.local_point
        a = R @ self.local_axis
        r = self.object_key_point - x
        perp = r - (r @ a) * a
        d = np.linalg.norm(perp)
        Jx = kin.point_jacobian(self.side, x)
        Ja = -_skew(a) @ kin.rotation_jacobian(self.side)
        # d(perp) = -(I - a a^T) dx - ((r.a) I + a r^T) da
        dperp = -(np.eye(3) - np.outer(a, a)) @ Jx - ((r @ a) * np.eye(3) + np.outer(a, r)) @ Ja
        return np.array([d]), ((perp / max(d, 1e-9)) @ dperp)[None]

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        t = self.type
        if t == "point2point":
            if self.upper > 0:
                return np.array([self.lower]), np.array([self.upper])
            return np.full(3, -POINT_TOL), np.full(3, POINT_TOL)
        if t == "parallel":
            return np.full(3, -AXIS_TOL), np.full(3, AXIS_TOL)
        if t == "angle":
            return np.array([np.cos(self.upper)]), np.array([np.cos(self.lower)])
        return np.array([self.lower]), np.array([max(self.upper, self.lower + POINT_TOL)])

    def violation(self, kin: Kinematics) -> float:
        """How far outside its bounds the constraint is (0 when satisfied)."""
        v, _ = self.evaluate(kin)
        lo, hi = self.bounds()
        return float(np.max(np.maximum(lo - v, 0.0) + np.maximum(v - hi, 0.0)))

    def describe(self, kin: Kinematics) -> str:
        v, _ = self.evaluate(kin)
        if self.type == "point2point" and self.upper == 0:
            return f"{self.name}: hand point is {np.linalg.norm(v) * 1000:.1f} mm from its target"
        if self.type == "parallel":
            ang = np.degrees(2 * np.arcsin(min(np.linalg.norm(v) / 2, 1.0)))
            return f"{self.name}: hand axis is {ang:.1f} deg from its target axis"
        if self.type == "angle":
            return f"{self.name}: angle {np.degrees(np.arccos(np.clip(v[0], -1, 1))):.1f} deg, wanted " \
                   f"[{np.degrees(self.lower):.1f}, {np.degrees(self.upper):.1f}]"
        return f"{self.name}: distance {v[0] * 1000:.1f} mm, wanted [{self.lower * 1000:.1f}, {self.upper * 1000:.1f}] mm"


class Const(Constraint):
    """The same relations as `Constraint`, as a weighted cost instead of a hard requirement."""

    def __post_init__(self) -> None:
        super().__post_init__()
        self.soft = True

    def cost(self, kin: Kinematics) -> tuple[float, np.ndarray]:
        v, J = self.evaluate(kin)
        lo, hi = self.bounds()
        r = np.maximum(lo - v, 0.0) - np.maximum(v - hi, 0.0)  # negative where above, positive where below
        # cost = w * |excess|^2; d/dq = -2 w r^T J
        return float(self.weight * r @ r), -2.0 * self.weight * (r @ J)


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


# The planner's kinematics for each simulation a planning context works on, by the env's id: kept by planning, not
# written onto the env. An entry lives as long as its Kinematics (the context holds it, and holds the env, so an id
# cannot be reused while its entry lives).
_KINEMATICS: weakref.WeakValueDictionary[int, Kinematics] = weakref.WeakValueDictionary()


def use_kinematics(env: Any, kin: Kinematics) -> None:
    """Constraints on `env` anchor hand points with `kin` (the planning context's kinematics: its held objects)."""
    _KINEMATICS[id(env)] = kin


def _kinematics_of(env: Any) -> Kinematics:
    """The planner's kinematics synced to the simulation now (a fresh one where no planner works on `env`)."""
    kin = _KINEMATICS.get(id(env))
    if kin is None or kin.model is not env.model:
        kin = Kinematics(env.model)
    kin.sync(env.data.qpos)
    return kin
