"""Ajar before a grip: a hinged part that lies shut and flush (a laptop's screen on its base) leaves no room for
fingers on its inner face, so a grasp or pinch of its edge cannot be solved (the fingers would go 3-4 cm into the
table). A person lifts such a lid a little with a fingertip first and then takes it; so does the planner when a
plan asks for a grip on a shut part whose object has a `flip` operation on that part.

How the fingertip lifts it (the steps the reference plan for open_laptop_hard showed to work): the index
fingertip, pointing at the edge along the part's approach axis with the palm across the lid, presses into the
edge's face just below its middle and rises with it in small steps (friction; a big step slips over the top);
with the edge off the base, it drops in front of the edge, slides under it and lifts the part from its inner
face to AJAR_TO, where the grips fit; then it slides back out, and the hand takes the finger posture it had.
Hinge friction keeps the part where it is left (the laptops' screens stay at 0.2).

The geometry comes from the part: the flip point and its two axes (along the part, into it), the part's
thickness at that point from its collision geoms, and the fingertip's radius.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.part_joint import moving_bodies
from humanoidgen.planning.push_actions import part_openness
from humanoidgen.planning.push_move import fingers_for_push, solve_and_go
from humanoidgen.sim.action import HAND_SLICE
from humanoidgen.sim.layout import HAND_BASE_FRAME, Side
from humanoidgen.sim.scene import SceneObject
from humanoidgen.planning import finger_room

SHUT_MAX = 0.1  # a part below this openness is shut for a grip (a laptop screen's edge is < 2.5 cm up)
AJAR_TO = 0.2  # the laptops' screen grasp and pinch solve from 0.15 up; a margin over that
AJAR_MIN = 0.12  # a lift that leaves the part below this did not make room: an error
# The fingertip's targets: the part at these openness values. The part lags behind the fingertip (it touches the
# edge only once the part is a bit below it), so each phase goes on until the part itself has reached its end.
FRICTION_STAGES = tuple(np.round(np.arange(0.015, 0.21, 0.015), 3))  # pressed into the edge's face
FRICTION_TO = 0.06  # the edge this far up (2.5 cm on the larger laptop) leaves room to slide under it
UNDER_STAGES = (0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4)  # from under the part
PRESS_IN_M = 0.02  # the fingertip aims this far into the edge's face, so it presses on it
TIP_R_M = 0.008  # the index fingertip's radius
UNDER_IN_M = 0.025  # under the part, the fingertip this far in from the edge
BACK_OFF_M = 0.05  # the fingertip starts and ends this far out in front of the edge
AIM_CONE_DEG = 40.0  # the fingertip points within this of the part's approach axis
PALM_ACROSS_DEG = (70.0, 110.0)  # the palm's grasp axis this far from the part's normal: the palm is sideways


@dataclass(frozen=True)
class EdgeFrame:
    """The flip point's frame with the part at some openness."""

    point: np.ndarray  # the edge's middle
    along: np.ndarray  # in along the part from its edge (the flip's approach axis)
    into: np.ndarray  # into the part from its outer face (the flip's attach axis)


def flip_operation(obj: SceneObject):
    """The object's flip operation (a fingertip at a lid's edge), or None."""
    ann = obj.annotations
    if ann is None or ann.articulation is None:
        return None
    return next((op for op in ann.operations if op.operation == "flip"), None)


def lies_shut(env, obj: SceneObject) -> bool:
    return flip_operation(obj) is not None and part_openness(env, obj) < SHUT_MAX


def edge_frame(env, obj: SceneObject, op, openness: float | None = None) -> EdgeFrame:
    def axis(name: str) -> np.ndarray:
        return get_axis_in_env(env, name, obj_type=obj.type_name, obj_id=obj.obj_id, openness=openness)

    point = get_point_in_env(env, op.point, obj.type_name, obj.obj_id, openness=openness)
    return EdgeFrame(point, axis(op.approach_axis), axis(op.attach_axis))


def half_thickness(env, obj: SceneObject, frame: EdgeFrame) -> float:
    """How far the part's inner face lies beyond the flip point along `frame.into` (from its geoms' boxes)."""
    m, d = env.model, env.data
    part_bodies = moving_bodies(m, f"{obj.body}_{obj.annotations.articulation.joint}")
    depth = 0.0
    for g in range(m.ngeom):
        if int(m.geom_bodyid[g]) not in part_bodies or m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0:
            continue
        centre, half = m.geom_aabb[g][:3], m.geom_aabb[g][3:]
        R = d.geom_xmat[g].reshape(3, 3)
        c = d.geom_xpos[g] + R @ centre
        reach = float(np.abs(R.T @ frame.into) @ half)  # the box's support along the axis
        # Only boxes over the edge count (not a hinge barrel far along the part).
        if abs(float((c - frame.point) @ frame.along)) <= np.abs(R.T @ frame.along) @ half + 0.01:
            depth = max(depth, float((c - frame.point) @ frame.into) + reach)
    return depth


def _tip_constraints(env, side: Side, goal: np.ndarray, aim: np.ndarray, normal: np.ndarray, what: str) -> list:
    frame = HAND_BASE_FRAME[side]
    lo, hi = PALM_ACROSS_DEG
    return [
        Constraint(env, "point2point", frame, hand_key_point=get_point_in_env(env, f"press_point_base_{side}_hand"),
                   object_key_point=goal, name=f"fingertip {what}"),
        Constraint(env, "angle", frame, hand_axis=get_axis_in_env(env, f"{side}_press_axis"), object_axis=aim,
                   lower=0.0, upper=np.radians(AIM_CONE_DEG), name="fingertip toward the edge"),
        Constraint(env, "angle", frame, hand_axis=get_axis_in_env(env, f"{side}_grasp_axis"), object_axis=normal,
                   lower=np.radians(lo), upper=np.radians(hi), name="palm across the part"),
    ]


def _nearest_posture(action: np.ndarray) -> str:
    return min(HAND_POSTURES, key=lambda k: float(np.max(np.abs(np.array(HAND_POSTURES[k]) - action))))


def lift_ajar(ctx, side: Side, obj: SceneObject) -> float:
    """Lift `obj`'s shut part ajar with `side`'s index fingertip (see the module doc); returns its openness."""
    env = ctx.env
    op = flip_operation(obj)
    shut = edge_frame(env, obj, op)
    # The fingertip's aim and the palm's normal stay those of the shut part: the hand keeps its orientation.
    aim, normal = shut.along, shut.into
    t = half_thickness(env, obj, shut)
    posture = _nearest_posture(ctx.action[HAND_SLICE[side]])
    start = part_openness(env, obj)
    ignored_before = set(ctx.collisions.ignored_bodies)
    ctx.collisions.ignored_bodies.add(env.model.body(obj.body).id)  # the fingertip is meant to touch it

    def go(openness: float | None, along: float, into: float, what: str, off: float = 0.0) -> None:
        f = edge_frame(env, obj, op, openness)
        solve_and_go(ctx, side, _tip_constraints(env, side, f.point + along * f.along + into * f.into
                                                     - off * aim, aim, normal, what))

    try:
        fingers_for_push(ctx, side)
        press_depth = 0.6 * t  # just below the edge's middle: pressing there lifts it, higher slips over
        go(None, PRESS_IN_M, press_depth, "in front of the edge", off=BACK_OFF_M)
        go(None, PRESS_IN_M, press_depth, "pressed into the edge")
        for o in FRICTION_STAGES:
            if part_openness(env, obj) >= FRICTION_TO:
                break
            if o > start:
                go(o, PRESS_IN_M, press_depth, f"lifting the edge (openness {o:.3f})")
        under = t + TIP_R_M
        go(None, -0.6 * UNDER_IN_M, under + 0.012, "below the raised edge")
        go(None, UNDER_IN_M, under, "under the edge")
        for o in UNDER_STAGES:
            if part_openness(env, obj) >= AJAR_TO:
                break
            go(o, UNDER_IN_M + 0.005, under, f"lifting the part from under (openness {o:.2f})")
        go(None, -UNDER_IN_M, under, "out from under the edge", off=BACK_OFF_M)
    finally:
        ctx.collisions.ignored_bodies = ignored_before
    got = part_openness(env, obj)
    label = f"{obj.type_name} {obj.obj_id}"
    if got < AJAR_MIN:
        raise PlanningError("generate_end_effector_pose",
                            f"{label} lies shut (openness {start:.2f}): no room for the fingers on its inner face, and "
                            f"lifting its edge with the {side} fingertip left it at {got:.2f}: lift it ajar first "
                            "(the fingertip under the edge, generate_constraints(..., action='target1'))")
    ctx.events.append(f"{label} lay shut (openness {start:.2f}): the {side} index fingertip lifted its edge to "
                          f"{got:.2f} first, to make room for the fingers on its inner face")
    finger_room.posture_with_room(ctx, (side,), posture)
    return got
