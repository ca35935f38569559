"""What explicit constraints mean to press: plans build a press from the API's own constraints.

    Constraint(point2point, hand_key_point=press_point_base_right_hand, object_key_point=<the lever's top, + 2 cm>)
    Constraint(parallel, hand_axis=right_press_axis, object_axis=<the toaster's down>)

is a press of the toaster's lever as much as `generate_constraints("toaster", 0, action="press")` is. What follows
that the constraints alone do not say, and that the generated press already gets:
- the part is meant to be touched: the goal and the move may bring the finger against the pressed part (its body,
  the `approach_object`; not the rest of the object), and the hand comes in along the press direction the plan set
  (from above for a `down` axis), unless the fingertip is already there;
- the press direction is a way to push, not an orientation the arm must hold exactly: a fingertip drives a part as
  well up to PUSH_CONE_DEG off it (the generated press allows that cone). Where the plan's exact `parallel` of the
  hand's press axis cannot be reached, the same constraints with that axis within the cone of the plan's direction
  are tried next (and an event says so);
- the turn of the hand about the finger is free: the palm, and so the curled fingers, is preferred away from the
  object's body (a cost), which they would otherwise meet on the way down;
- a target at or past the point along the press (the point taken at a further openness, or a few mm into it) is the
  press itself: the move rides with the part, as a generated press with `openness=` does, until the fingertip is
  where the plan put it.

A point2point of the hand's press point counts as a press where its target lies within NEAR_M of an annotated press
point of an articulated object, anywhere along that point's travel (the part at any openness); not where the point
would have to come back against the finger (a finger lifted off the pressed part).
"""

from __future__ import annotations

from dataclasses import replace

import mujoco
import numpy as np

from humanoidgen.objects.describe import openness
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning.constraint_gen import PUSH_CONE_DEG, Generated, ride_with_part
from humanoidgen.planning.constraints import Const
from humanoidgen.sim.layout import Side

SAME_POINT_M = 1e-3  # a constraint's hand point this near the press point now is the press point
NEAR_M = 0.03  # a target this near a press point's travel is a press on it (a plan aims 1-2 cm above)
TRAVEL_SAMPLES = 21  # openness values sampled along a point's travel
# Presses only: the pushes and flips of lids, screens and drawers that plans write as constraints are staged
# pushes with their own offsets (the reference plans of the box and laptop tasks), which keep their meaning.
PRESS_OPERATIONS = ("press",)
RIDE_PAST_STOP = 1.5  # the openness (extrapolated past the stop) up to which a press's ride may aim
CLEAR_WEIGHT = 0.2  # the palm's preference, below the plan's own costs (weight 1 by default)
MOVES_PART = 0.1  # a target where the point will be this much further back along its travel is a finger lifted off
CONTACT_M = 0.005  # a target this little short of the point (along the press) or past it presses the part
AT_M = 0.03  # a fingertip this near its target is there: no approach from further out along the press direction


def part_openness(env, obj, point: str) -> float:
    """The openness now of the part that `point` is on."""
    return float(np.clip(openness(env.model, env.data, obj, obj.annotations.point(point).part), 0.0, 1.0))


def _pressed_point(env, target: np.ndarray, holding: dict):
    """(object, operation, openness) whose press point passes within NEAR_M of `target` at some openness, nearest
    first; None if none. Held objects are left out (a hand holding a part grips it, it does not press it)."""
    held = {id(o) for o in holding.values() if o is not None}
    best, best_d = None, NEAR_M
    for obj in env.scene.objects:
        ann = obj.annotations
        if ann is None or ann.articulation is None or id(obj) in held:
            continue
        for op in (o for o in ann.operations if o.operation in PRESS_OPERATIONS):
            for o in np.linspace(0.0, 1.0, TRAVEL_SAMPLES):
                d = float(np.linalg.norm(get_point_in_env(env, op.point, obj.type_name, obj.obj_id, openness=o) - target))
                if d < best_d:
                    best, best_d = (obj, op, float(o)), d
    return best


def infer(env, side: Side, constraints: list, holding: dict) -> Generated | None:
    """The press that plan-written constraints describe, as the ways to solve it (the plan's own constraints,
    then with its press direction within the cone), or None (generated constraints, a hand that holds something,
    or no press point of the hand on an object's press point)."""
    if not constraints or getattr(constraints[0], "meta", None) is not None or holding.get(side) is not None:
        return None
    tip = get_point_in_env(env, f"press_point_base_{side}_hand")
    pinned = next((c for c in constraints if not c.soft and c.type == "point2point" and c.side == side
                   and c.upper <= SAME_POINT_M and np.linalg.norm(c.hand_key_point - tip) <= SAME_POINT_M), None)
    if pinned is None:
        return None
    found = _pressed_point(env, np.asarray(pinned.object_key_point, float), holding)
    if found is None:
        return None
    obj, op, at = found
    axis_now = get_axis_in_env(env, f"{side}_press_axis")
    exact = [c for c in constraints if not c.soft and c.type == "parallel" and c.side == side
             and np.allclose(c.hand_axis, axis_now, atol=1e-6)]
    approach = (np.asarray(exact[0].object_axis, float) / np.linalg.norm(exact[0].object_axis) if exact else
                get_axis_in_env(env, op.approach_axis, obj_type=obj.type_name, obj_id=obj.obj_id))
    now = part_openness(env, obj, op.point)
    if abs(at - now) > MOVES_PART and _gives_way(env, obj, op.point, now, at) @ approach <= 0.0:
        return None  # the point would have to come back against the finger: not a press (a finger lifted off)
    point_now = get_point_in_env(env, op.point, obj.type_name, obj.obj_id)
    presses = float((np.asarray(pinned.object_key_point, float) - point_now) @ approach) > -CONTACT_M
    if presses or np.linalg.norm(tip - np.asarray(pinned.object_key_point, float)) < AT_M:
        # the press itself, or a fingertip already there: it goes straight on from where it is (taking the part
        # along), not back out to come in again
        approach = None
    part = obj.annotations.point(op.point).part
    # The finger may touch the pressed part, not the rest of the object: the curled fingers keep clear of its body.
    body = f"{obj.body}_{part}" if part else obj.body
    keep_clear = _fingers_off_body(env, side, obj, op, constraints[0].end_effector_frame)
    first = Generated(list(constraints) + keep_clear, approach_axis=approach, approach_object=body, presses=presses)
    if exact:
        first.alternatives.append(Generated(_within_cone(env, constraints, exact) + keep_clear, approach_axis=approach,
                                            approach_object=body, presses=presses,
                                            notes=[_cone_note(side, obj, op)]))
    if presses:
        for gen in (first, *first.alternatives):
            _ride(env, side, gen, obj, op.point, np.asarray(pinned.object_key_point, float))
    return first


def _ride(env, side: Side, gen: Generated, obj, point: str, target: np.ndarray) -> None:
    """The move of a press rides with the part as the generated press's does (the hand follows the part's joint,
    the fingertip keeping its place on it), to the joint value that brings the fingertip where the plan asked:
    a fingertip that starts 2 cm above a lever goes 2 cm further than the lever's point, past the stop if need
    be (the stop holds the part). The solved goal stays the fallback."""
    ride_with_part(env, gen, obj.type_name, obj.obj_id, point, 1.0)
    f = gen.follow
    if f is None:
        return
    m = env.model
    jid = m.joint(f.joint).id
    adr, body = m.jnt_qposadr[jid], m.jnt_bodyid[jid]
    d = mujoco.MjData(m)
    d.qpos[:] = env.data.qpos
    mujoco.mj_kinematics(m, d)
    tip = get_point_in_env(env, f"press_point_base_{side}_hand")
    rel = d.xmat[body].reshape(3, 3).T @ (tip - d.xpos[body])
    q_now = float(d.qpos[adr])
    best, best_d = q_now, np.inf
    for o in np.linspace(0.0, RIDE_PAST_STOP, int(RIDE_PAST_STOP * 50) + 1):
        d.qpos[adr] = f.articulation.joint_position(o)
        mujoco.mj_kinematics(m, d)
        at = d.xpos[body] + d.xmat[body].reshape(3, 3) @ rel
        if (dist := float(np.linalg.norm(at - target))) < best_d:
            best, best_d = float(d.qpos[adr]), dist
    gen.follow = replace(f, q_target=best)


def _fingers_off_body(env, side: Side, obj, op, frame: str) -> list:
    """A preference (a cost, weight CLEAR_WEIGHT) for the palm, and so the curled fingers, facing away from the
    object's middle, level: the press leaves the hand's turn about the finger free, and with the palm toward the
    object the curled fingers meet its body on the way down (a toaster's top, past a lever 3 cm out)."""
    away = (get_point_in_env(env, op.point, obj.type_name, obj.obj_id)
            - get_point_in_env(env, "center", obj.type_name, obj.obj_id))
    away[2] = 0.0
    if np.linalg.norm(away) < 1e-3:
        return []
    return [Const(env, "parallel", frame, hand_axis=get_axis_in_env(env, f"{side}_grasp_axis"),
                  object_axis=away / np.linalg.norm(away), weight=CLEAR_WEIGHT,
                  name="palm away from the pressed object's body (preferred)")]


def _gives_way(env, obj, point: str, now: float, to: float) -> np.ndarray:
    """Which way the point moves from openness `now` toward `to`."""
    return (get_point_in_env(env, point, obj.type_name, obj.obj_id, openness=to)
            - get_point_in_env(env, point, obj.type_name, obj.obj_id, openness=now))


def _within_cone(env, constraints: list, exact: list) -> list:
    """The constraints with each exact `parallel` of the press axis let within PUSH_CONE_DEG of its direction
    (a hard `angle`), along it preferred (a cost), as the generated press has them."""
    out = []
    for c in constraints:
        if not any(c is e for e in exact):
            out.append(c)
            continue
        loose = replace(c, type="angle", lower=0.0, upper=float(np.radians(PUSH_CONE_DEG)),
                        name=f"{c.name} (within {PUSH_CONE_DEG} deg)")
        loose.meta = None
        out.append(loose)
        out.append(Const(env, "parallel", c.end_effector_frame, hand_axis=c.hand_axis, object_axis=c.object_axis,
                         weight=0.5, name=f"{c.name} (preferred)"))
    return out


def _cone_note(side: Side, obj, op) -> str:
    return (f"the {side} fingertip's press on {obj.type_name} {obj.obj_id} {op.point}: exactly along the direction "
            f"asked ('parallel' of {side}_press_axis) the {side} arm does not reach it, so the finger was let within "
            f"{PUSH_CONE_DEG} deg of that direction (an 'angle' constraint with upper=math.radians({PUSH_CONE_DEG}) "
            "says so in a plan)")
