"""What explicit constraints mean to grip: the paper's MCTS-style plans write a pinch or grasp as Constraints.

    Constraint(point2point, hand_key_point=pinch_point_base_right_hand, object_key_point=<cube 1's centre>)
    Constraint(parallel, hand_axis=right_pinch_axis, object_axis=[0, 0, -1])

is a pinch of cube 1 from above, as much as `generate_constraints("cube", 1, "pinch")` is. Two things follow that the
constraints alone do not say, and that the annotated grips already get:
- the object is meant to be touched: the goal may bring the fingers against it (the grip closes on it next), and the
  hand comes in along the grip's axis (here from above) rather than sweeping sideways into it;
- a pinch closes thumb onto index pad: across a box-shaped object's faces it holds, across its corners it slips.
  Where the plan leaves the squeeze direction free, it is set along one of the object's annotated pinch axes (both
  signs of the attach axis, then of the parallel axis, nearest the hand's present turn first);
- a grip point low on an object standing on the table (a 4 cm cube's centre is 2 cm up) puts the lower fingers into
  the table. Where the object has an annotated grip of that kind higher up, the grip may be taken at that height
  instead (same x and y): a fallback, reported as an event, tried only when the plan's own height cannot be reached.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning.constraint_gen import Generated
from humanoidgen.planning.constraints import Constraint
from humanoidgen.sim.geometry import quat_to_mat
from humanoidgen.sim.layout import Side

SAME_POINT_M = 1e-3  # a constraint's hand point this near a hand key point now is that key point
INSIDE_MARGIN_M = 0.01
SQUARE_COS = np.sin(np.radians(10))  # a squeeze axis within 10 deg of square to the approach  # a target this near an object's box counts as on the object
GRIPS = {"pinch": "pinch_point_base_{side}_hand", "grasp": "grasp_point_base_{side}_hand"}
GRIP_AXES = {"pinch": "{side}_pinch_axis", "grasp": "{side}_grasp_axis"}


@dataclass
class GripIntent:
    """The grip explicit constraints describe: the object, the kind, and the ways to take it (`first`, then its
    alternatives: each squeeze direction at the height asked, the plan's own constraints, then the same higher)."""

    obj: object  # the scene object
    operation: str  # "pinch" or "grasp"
    first: Generated
    pinned: Constraint  # the plan's point2point of the hand's grip point
    target: np.ndarray  # where it asked the grip point to go

    def raised_by(self, result) -> float:
        """How much higher than asked the solved goal takes the grip (m)."""
        return float((result.ee_pos + result.ee_mat @ self.pinned.local_point)[2] - self.target[2])


def _object_at(env, point: np.ndarray, holding: dict):
    """The object whose (slightly grown) bounding box holds `point`, the smallest if several; held ones excluded."""
    held = {id(o) for o in holding.values() if o is not None}
    best, best_vol = None, np.inf
    for obj in env.scene.objects:
        ann = obj.annotations
        if ann is None or id(obj) in held:
            continue
        p, q = env.object_pose(obj.body)
        R = quat_to_mat(q)
        local = R.T @ (point - p)
        lo, hi = np.array(ann.bbox_min) - INSIDE_MARGIN_M, np.array(ann.bbox_max) + INSIDE_MARGIN_M
        if np.all(local >= lo) and np.all(local <= hi):
            vol = float(np.prod(np.array(ann.bbox_max) - np.array(ann.bbox_min)))
            if vol < best_vol:
                best, best_vol = obj, vol
    return best


def infer(env, side: Side, constraints: list, holding: dict) -> GripIntent | None:
    """The grip that plan-written constraints describe, or None (generated ones, or no hand grip point on an object)."""
    if not constraints or getattr(constraints[0], "meta", None) is not None or holding.get(side) is not None:
        return None
    for c in constraints:
        if c.soft or c.type != "point2point" or c.side != side or c.upper > SAME_POINT_M:
            continue
        for operation, name in GRIPS.items():
            if np.linalg.norm(c.hand_key_point - get_point_in_env(env, name.format(side=side))) > SAME_POINT_M:
                continue
            target = np.asarray(c.object_key_point, float)
            obj = _object_at(env, target, holding)
            if obj is None:
                return None
            approach = _approach(env, side, operation, constraints)
            heights = [(list(constraints), None)] + _raised(env, obj, operation, constraints, c, target)
            ways = [Generated(cons, approach_axis=approach, approach_object=obj.body, notes=[note] if note else [])
                    for plain, note in heights
                    for cons in _squeezes(env, side, obj, operation, plain, approach) + [plain]]
            return GripIntent(obj, operation, replace(ways[0], alternatives=ways[1:]), c, target)
    return None


def _squeezes(env, side: Side, obj, operation: str, constraints: list, approach: np.ndarray | None) -> list[list]:
    """The constraints plus a hard squeeze direction along each annotated pinch axis of the object that is square
    to the approach, nearest the hand's present thumb-to-index direction first; none where the plan sets it."""
    if operation != "pinch" or approach is None:
        return []
    squeeze_now = get_axis_in_env(env, f"{side}_thumb_2_index")
    if any(not c.soft and c.type in ("parallel", "angle") and np.allclose(c.hand_axis, squeeze_now, atol=1e-6)
           for c in constraints):
        return []
    frame = constraints[0].end_effector_frame
    axes = []
    for op in (o for o in obj.annotations.operations if o.operation == "pinch"):
        for name in (op.attach_axis, op.parallel_axis):
            a = get_axis_in_env(env, name, obj_type=obj.type_name, obj_id=obj.obj_id)
            if abs(a @ approach) < SQUARE_COS and not any(abs(a @ b) > 0.99 for b in axes):
                axes.append(a)
    ways = sorted((sign * a for a in axes for sign in (1.0, -1.0)), key=lambda a: -float(a @ squeeze_now))
    return [list(constraints) + [Constraint(env, "parallel", frame, hand_axis=squeeze_now, object_axis=a,
                                            name=f"squeeze across {obj.type_name} {obj.obj_id}'s faces")]
            for a in ways]


def _approach(env, side: Side, operation: str, constraints: list) -> np.ndarray | None:
    """The grip's axis set by a hard `parallel` of the hand's pinch/grasp axis: the hand comes in along it."""
    axis_now = get_axis_in_env(env, GRIP_AXES[operation].format(side=side))
    for c in constraints:
        if not c.soft and c.type == "parallel" and c.side == side and np.allclose(c.hand_axis, axis_now, atol=1e-6):
            return np.asarray(c.object_axis, float) / np.linalg.norm(c.object_axis)
    return None


def _raised(env, obj, operation: str, constraints: list, pinned, target: np.ndarray) -> list[tuple[list, str]]:
    """The same grip at the height of the object's annotated grip points of that kind above the target."""
    out = []
    ops = [o for o in obj.annotations.operations if o.operation == operation]
    for op in ops:
        z = get_point_in_env(env, op.point, obj.type_name, obj.obj_id)[2]
        dz = z - target[2]
        if dz <= 0.002 or any(abs(dz - prev) < 0.002 for prev in (d for _, _, d in out)):
            continue
        moved = replace(pinned, object_key_point=target + np.array([0.0, 0.0, dz]))
        moved.meta = None
        cons = [moved if c is pinned else c for c in constraints]
        note = (f"the {operation} of {obj.type_name} {obj.obj_id} was taken {dz * 1000:.0f} mm higher than asked, at "
                f"its annotated {op.point} height: at the height asked the fingers would go into the table")
        out.append((cons, note, dz))
    return [(cons, note) for cons, note, _ in sorted(out, key=lambda t: t[2])]
