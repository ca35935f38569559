"""Running a task's push (target1/target2 on a part, `push_actions`): the fingers set for pressing, the pre-push
pose reached first where the fingertip is not on the contact yet, then the staged push along the part's joint,
each stage solved by the goal search and moved by the transit stage; a part left short of half the way is an
error that says so."""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.planning import arm_moves, goal_search

from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.execute import stopped_short
from humanoidgen.planning.hand_ops import finger_contacts
from humanoidgen.planning.push_actions import (AT_M, FINGERS_SET, HOME_PRESS_M, REACH_M, SHORT_SHARE, TOUCH_SHORT_M,
                                               PushMove, _axis, _label, contact_point, part_openness,
                                               stage_constraints, stages, standoff_direction)
from humanoidgen.planning.push_spec import FingertipPush
from humanoidgen.sim.action import HAND_SLICE
from humanoidgen.sim.layout import Side
from humanoidgen.sim.scene import SceneObject


def fingers_for_push(ctx, side: Side) -> None:
    """Index extended, the others curled (hand_press), unless the plan set them so already."""
    if np.max(np.abs(ctx.action[HAND_SLICE[side]] - np.array(HAND_POSTURES["press"]))) > FINGERS_SET:
        ctx.move_fingers((side,), "press")


def _go(ctx, side: Side, pose, must_reach: bool, obj: SceneObject | None = None) -> None:
    ctx.run_arm_samples({side: arm_moves.plan_side(ctx, side, pose)})
    ctx.settle(0.2)
    err = float(np.linalg.norm(ctx.current_pose(side).p - pose.p))
    if not must_reach or err <= REACH_M:
        return
    if obj is not None and err <= TOUCH_SHORT_M and finger_contacts(ctx.env.model, ctx.env.data, side, obj.body):
        # Curled fingers resting on the part short of the pre-push pose: the push starts from here as well.
        ctx.log[-1].message = f"stopped {err * 1000:.0f} mm short of the pre-push pose, touching {_label(obj)}"
        return
    raise PlanningError("move_to_pose_with_screw", stopped_short(ctx, side, err))


def solve_and_go(ctx, side: Side, cons: list, must_reach: bool = False, obj: SceneObject | None = None) -> None:
    _, pose = goal_search.solve_goal(ctx, cons, side)
    _go(ctx, side, pose, must_reach, obj)


def _pre_push(ctx, side: Side, obj: SceneObject, spec: FingertipPush, pose) -> None:
    """To the pre-push pose (`pose`, solved already, or solved here). Where the way there is blocked, e.g. behind
    a screen that stands nearly upright, from above its edge instead: out of the face and past the edge."""
    env = ctx.env
    try:
        if pose is None:
            _, pose = goal_search.solve_goal(ctx, stage_constraints(env, side, obj, spec, None, spec.standoff, "just off"), side)
        _go(ctx, side, pose, must_reach=True, obj=obj)
        return
    except PlanningError as exc:
        if spec.face != "outer":
            raise
        first = exc
    try:
        solve_and_go(ctx, side, stage_constraints(env, side, obj, spec, None, spec.standoff, "above the edge of",
                                                       over_edge=True), True, obj)
    except PlanningError:
        raise first from None
    ctx.events.append(f"the {side} fingertip came to {_label(obj)}'s pre-push pose over its edge "
                          f"(straight off the face: {first.reason[:80]})")


def _tip(ctx, side: Side) -> np.ndarray:
    ctx.kin.sync(ctx.env.data.qpos)
    return get_point_in_env(ctx.env, f"press_point_base_{side}_hand")


def execute(ctx, side: Side, pose) -> None:
    """Move to a target1 pose (fingers set to press), or carry out a target2 push (see the module docstring)."""
    move: PushMove = pose.push
    env, obj, spec = ctx.env, move.obj, move.spec
    fingers_for_push(ctx, side)
    if move.phase == "pre":
        _pre_push(ctx, side, obj, spec, pose)
        return
    tip = _tip(ctx, side)
    on = contact_point(env, obj, spec, None)
    off = on + spec.standoff * standoff_direction(env, obj, spec, None)
    over = off - spec.standoff * _axis(env, obj, spec.axes[0], None)  # the pre-push pose over the edge
    if min(np.linalg.norm(tip - p) for p in (on, off, over)) > AT_M:
        # Not at the push point yet (no target1 before): to the pre-push pose first, around the part.
        _pre_push(ctx, side, obj, spec, None)
        ctx.events.append(f"target2: the {side} fingertip went to {_label(obj)}'s pre-push pose (target1) first")
        pose = None  # the part may have moved meanwhile: the first contact is solved again, where it is now
    start = part_openness(env, obj)
    ignored_before = set(ctx.collisions.ignored_bodies)
    ctx.collisions.ignored_bodies.add(env.model.body(obj.body).id)  # the fingertip is meant to touch it
    skipped: list[str] = []
    try:
        if pose is None:
            solve_and_go(ctx, side, stage_constraints(env, side, obj, spec, None))
        else:
            _go(ctx, side, pose, must_reach=False)  # onto the part (the goal solved for target2)
        for o in stages(start, move.to, spec.step):
            home = HOME_PRESS_M if o == move.to and move.to in (0.0, 1.0) else 0.0
            try:
                solve_and_go(ctx, side, stage_constraints(env, side, obj, spec, o, press=home))
            except PlanningError as exc:  # out of reach there: the next stage may still be reached
                skipped.append(f"{o:.2f} ({exc.reason[:80]})")
        try:  # the fingertip off the part again, at the openness it pushed it to
            solve_and_go(ctx, side, stage_constraints(env, side, obj, spec, part_openness(env, obj),
                                                           spec.standoff, "off"))
        except PlanningError:
            skipped.append("taking the fingertip off the part")
    finally:
        ctx.collisions.ignored_bodies = ignored_before
    got = part_openness(env, obj)
    if skipped:
        ctx.events.append(f"push of {_label(obj)}: could not reach the stage(s) at openness {'; '.join(skipped)}")
    way = move.to - start
    share = (got - start) / way if abs(way) > 1e-6 else 1.0
    ctx.events.append(f"pushed {_label(obj)} from openness {start:.2f} to {got:.2f} (asked {move.to:g})")
    if share < SHORT_SHARE and abs(got - move.to) > 0.05:
        raise PlanningError("move_to_pose_with_screw",
                            f"{_label(obj)} is at openness {got:.2f} after the push, not the {move.to:g} asked (from "
                            f"{start:.2f}): the fingertip did not carry it"
                            + (f"; unreachable stages: {'; '.join(skipped)}" if skipped else "")
                            + ": ask for target1, then target2 again from where the part is now, or take the part "
                            "with action='grasp' (or 'pinch') and move it with openness=")
