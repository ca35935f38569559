"""Moving a held part on where the arm runs out of reach: let go, grip it again where it is, go on.

A lid or screen swung far with one grip turns the wrist with it until the arm's reach or joint range ends (a
screen that starts nearly upright and is to be closed to 0.3). A person lets go there and takes the part again
from a posture that suits the rest of the way. The goal search (`goal_search.partial_goal`) returns the goal as
far as the arm gets, with `Pose.regrip` saying where the plan asked to go; after that move, this recovery does the
rest with the plan's own verb (grasp or pinch) through the planner's verbs (handed to it in the request, never
imported), so every call is logged as the plan's are. The budget (`ctx.regrips_left`) is the pipeline's.
A part to be shut is not taken shut in the fingers (they would end shut in under it): let go on its way, or
stopped short in the hand, it is pushed shut with the task's fingertip push where the task has one.
"""

from __future__ import annotations

from typing import Any

from humanoidgen.objects.describe import openness
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.part_joint import part_stays
from humanoidgen.planning.part_joint import follow_openness
from humanoidgen.planning.recovery import AfterMove, Recovery
from humanoidgen.planning.regrip_request import SHUT, RegripRequest
from humanoidgen.sim.layout import Side
ARRIVED_TOL = 0.05  # openness: a part let go this near the openness asked, and at rest there, got there
NEAR_END = 0.1  # openness: a part asked this near the end of the task's push is pushed to that end
SHORT_TOL = 0.001  # openness: a part this far short of where it was asked, toward the task's push end, is short
AT_REST_RAD_S = 0.05  # a part's joint turning or sliding slower than this is at rest


def arrived(now: float, wanted: float) -> bool:
    """Whether a part let go on its way is, at openness `now`, where it was to go (a screen let go at 0.17 on its
    way shut falls shut by itself; gripped again it was lifted to 0.25 for the fingers and left at 0.20). Past it
    does not count: a lid let go at 0.5 on its way to 0.3 rests at 0.14 on the fingers; gripped again, taken to
    0.3 and let go, it falls shut."""
    return abs(now - wanted) <= ARRIVED_TOL


class GripAgain(Recovery):
    stage = "move"
    trigger = "after"
    answers = "a held part moved only partway: the arm's reach ends, or the grip slipped short of shut"
    tries = ("let go, push it on with the task's fingertip push, or grip it again (the plan's verb, then the "
             "other) and move it on; optional when the part went most of the way and stays")
    event = "...: it lets go there, grips it again and moves it on to <openness>"

    def applies(self, ctx: PlanningContext, request: AfterMove, failure: Exception | None) -> bool:
        return request.target.regrip is not None

    def attempt(self, ctx: PlanningContext, request: AfterMove, failure: Exception | None) -> None:
        go_on(ctx, request.verbs, request.side, request.target.regrip)


def go_on(ctx: PlanningContext, planner: Any, side: Side, regrip: RegripRequest) -> None:
    """Let go of the part, grip it again at its present openness (the plan's verb, else the other) and move it on
    to `regrip.openness`. Where that fails, the move fails with both reasons, unless the regrip is optional
    (the part went most of the way and stays there): then the part is left where it is, with an event."""

    try:
        _go_on(ctx, planner, side, regrip)
    except PlanningError as exc:
        if not regrip.optional:
            raise
        obj = ctx.env.scene.object(*regrip.obj)
        planner.open_hand(side)
        now = openness(ctx.env.model, ctx.env.data, obj)
        ctx.events.append(f"{obj.type_name} {obj.obj_id} stays at openness {now:.2f} of the "
                              f"{regrip.openness:g} asked: the {side} arm's reach ends there holding it, and "
                              f"going on from a second grip failed ({exc.reason})")


def _go_on(ctx: PlanningContext, planner: Any, side: Side, regrip: RegripRequest) -> None:

    obj = ctx.env.scene.object(*regrip.obj)
    verb = regrip.verb or "grasp"
    label = f"{obj.type_name} {obj.obj_id}"
    why = regrip.why or f"the {side} arm reaches only openness {regrip.reached:.2f} holding {label}"
    ctx.events.append(f"{why}: it lets go there, grips it again and moves it on to {regrip.openness:g}")
    ctx.regrips_left -= 1
    try:
        ctx.regripping = True  # letting go to grip again: the hand may stay on the part (part_release)
        try:
            planner.open_hand(side)
        finally:
            ctx.regripping = False
        now = follow_openness(ctx.env, regrip.follow)
        at_rest = _at_rest(ctx.env, regrip.follow.joint)
        if arrived(now, regrip.openness) and at_rest:
            if _short_of_push_end(ctx, obj, regrip, now) and _pushed_on(ctx, planner, side, obj, regrip, now,
                                                                        "it is left there"):
                return
            ctx.events.append(f"{label} went on to openness {now:.2f} by itself when let go (asked "
                                  f"{regrip.openness:g}): it is not gripped again")
            return
        if at_rest and _pushed_on(ctx, planner, side, obj, regrip, now):
            return
        why = []
        for v in (verb, "pinch" if verb == "grasp" else "grasp"):
            try:
                _grip(planner, side, obj, v)
                break
            except PlanningError as exc:
                why.append(f"{v}: {exc.reason}")
                planner.open_hand(side)
        else:
            raise PlanningError("move_to_pose_with_screw",
                                f"{label} reached only openness {regrip.reached:.2f} of the {regrip.openness:g} "
                                f"asked (the {side} arm's reach ends there holding it), and gripping it again there "
                                f"failed ({'; '.join(why)}): move it there, let go and push it the rest of the way")
        cons = planner.generate_constraints(obj.type_name, obj.obj_id, v, side, openness=regrip.openness)
        _, pose = planner.generate_end_effector_pose(cons, side)
        planner.move_to_pose_with_screw(pose, side, attach_obj=True, object_name=obj.type_name, object_id=obj.obj_id)
    finally:
        ctx.regrips_left += 1


def _short_of_push_end(ctx: PlanningContext, obj, regrip: RegripRequest, now: float) -> bool:
    """Whether a part let go near the openness asked stopped short of it where that openness is near the end the
    task's push goes to: "near" is not there when the task asks for at least that much (a lid pinched 1 cm in from
    its tab's tip, let go at 0.75 on its way to 0.95, went on by itself to 0.94: close enough to stay, not open
    enough for the task's 0.95). Such a part is pushed home with the fingertip. A part to be shut is not: within
    ARRIVED_TOL of shut it is shut as the tasks judge it (to SHUT)."""
    targets = ctx.targets
    push = targets.push(obj.type_name, obj.obj_id) if targets is not None else None
    if push is None or regrip.openness <= SHUT or abs(push.spec.push.to - regrip.openness) > NEAR_END:
        return False
    return (regrip.openness - now) * (push.spec.push.to - now) > 0 and abs(regrip.openness - now) > SHORT_TOL


def _pushed_on(ctx: PlanningContext, planner: Any, side: Side, obj, regrip: RegripRequest, now: float,
               otherwise: str = "it is gripped again") -> bool:
    """A part that went on by itself toward the openness asked when let go and came to rest short of it (at openness
    `now`): where the task defines a fingertip push that way, push it on from there instead of gripping it again (a
    screen let go at 0.25 on its way shut fell to 0.08; gripped again it was first lifted ajar to 0.24 to make room
    for the fingers, and the grip came off at 0.20). A part to be shut is pushed on even where it stayed; one asked
    within NEAR_END of where the task's push ends is pushed to that end. False where there is no such push or it
    fails (then the part is gripped again)."""
    targets = ctx.targets
    push = targets.push(obj.type_name, obj.obj_id) if targets is not None else None
    wanted = regrip.openness
    if push is None or (push.spec.push.to - now) * (wanted - now) <= 0:
        return False  # no push, or the task's push goes the other way
    went_on = (regrip.reached - now) * (regrip.reached - wanted)  # > 0: it went on toward the goal
    # A part to be shut is pushed the rest of the way even where it stayed: gripped again and taken shut, the
    # fingers around its edge end up shut in under it (a screen pinched shut to 0.04 had the thumb between screen
    # and base; every way of letting go dragged it, and the hand going home lifted it to 0.48).
    if went_on < ARRIVED_TOL * abs(regrip.reached - wanted) and wanted > SHUT:
        return False  # it stayed where the hand let go (a lid at 0.66): grip it again
    # Asked near the end the task's push goes to, push to that end: a fingertip stops short of a point on the way
    # (a lid pushed on to 0.95 came to 0.90, just at a task's 0.9), and pressed home it gets there.
    to = push.spec.push.to if abs(push.spec.push.to - wanted) <= NEAR_END else wanted
    try:
        cons = planner.generate_constraints(obj.type_name, obj.obj_id, "target2", side, openness=to)
        _, pose = planner.generate_end_effector_pose(cons, side)
        planner.move_to_pose_with_screw(pose, side)
    except PlanningError as exc:
        ctx.events.append(f"pushing {obj.type_name} {obj.obj_id} on from openness {now:.2f} failed "
                              f"({exc.reason}): {otherwise}")
        return False
    ctx.events.append(f"{obj.type_name} {obj.obj_id}, let go at openness {now:.2f}, is pushed on to "
                          f"{to:g} with the fingertip (the task's push) instead of gripped again")
    return True


def _at_rest(env, joint: str) -> bool:
    """Whether a part's joint is still and would stay where it is left (a lid let go high is still falling)."""
    jid = env.model.joint(joint).id
    still = abs(float(env.data.qvel[env.model.jnt_dofadr[jid]])) < AT_REST_RAD_S
    return still and part_stays(env, joint, float(env.data.qpos[env.model.jnt_qposadr[jid]]))


def _grip(planner: Any, side: Side, obj, verb: str) -> None:
    (planner.hand_pre_grasp if verb == "grasp" else planner.hand_pre_pinch)(side)
    cons = planner.generate_constraints(obj.type_name, obj.obj_id, verb, side)
    _, pose = planner.generate_end_effector_pose(cons, side)
    planner.move_to_pose_with_screw(pose, side)
    (planner.hand_grasp if verb == "grasp" else planner.hand_pinch)(side, obj.type_name, obj.obj_id)
