"""How the planner moves an arm: plans (screw motion, straight approach, sampled detour, part following),
timing, and the check that two arms moving at once keep apart. Stage (transit): functions of a PlanningContext; where
no plain move exists it asks the pipeline (`ctx.recover("transit", LegRequest, failure)`)."""

from __future__ import annotations

import time
from contextlib import nullcontext
from dataclasses import replace

import mujoco
import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.planning import approach, finger_room, part_grip, placing, shared_hold
from humanoidgen.planning import regrip_request as regrip
from humanoidgen.planning.context import HAND_MOTION_TIME, PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.feedback import motion_advice
from humanoidgen.planning.motion import JointPath, MotionError, plan_arm_motion, time_dense_path
from humanoidgen.planning.part_joint import follow_articulation, follow_openness
from humanoidgen.planning.paths import time_parametrize
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.recovery import LegRequest
from humanoidgen.planning.turn_trials import best_correction
from humanoidgen.planning.hand_ops import is_part
from humanoidgen.sim.action import ARM_SLICE, HAND_SLICE
from humanoidgen.sim.geometry import rotation_angle
from humanoidgen.sim.layout import SIDES, Side

RETREAT_DISTANCE = 0.10  # after letting go, the hand backs out along its approach axis this far
FOLLOW_TOL = 0.05  # openness: a part this near the asked openness after a move got there
FOLLOW_RETRY = 0.3  # a part that moved at least this share of the way but stopped short is pushed again, once
TURN_TOL_DEG = 5.0  # a part turned in the fingers (a knob) is taken to the angle asked, past it by at most this ...
TURN_CORRECTIONS = 3  # ... in at most this many corrective moves
AIM_PAST = 0.5  # ... each aimed past the band by this share of the error left
CARRY_LIMITS = {"v_max": 0.6, "a_max": 1.5}  # joint speed (rad/s) and acceleration with an object in the hand
# A carried object that stands on something (or is within this of it) and is to be turned more than this is first
# lifted straight up this far: turned where it stands, its lower edge drags on the support and twists it out of a
# pinch.
LIFT_BEFORE_TURN_DEG = 20.0
LIFT_BEFORE_TURN_M = 0.05


def _with_hand(arm: np.ndarray, hand: np.ndarray) -> np.ndarray:
    """Arm samples (n, 7) with the hand's targets (6,) on every row: (n, 13)."""
    return np.hstack([arm, np.repeat(hand[None], len(arm), 0)])


def retreat(ctx: PlanningContext, side: Side, open_fingers: bool = False) -> None:
    """Back the hand out along its last approach axis (best effort: skipped if that way is blocked),
    optionally opening the fingers on the way."""
    axis = ctx.hands[side].last_approach
    if axis is None:
        if open_fingers:
            ctx.move_fingers((side,), "open")
        return
    ctx.kin.sync(ctx.env.data.qpos)
    if open_fingers:
        # The fingers open on the way out: check the way with them open, or the closed fingers around a
        # handle would block every way back.
        ctx.kin.set_hand(side, np.array(HAND_POSTURES["open"]))
        ctx.kin.forward()
    p, R = ctx.kin.ee_pose(side)
    arm = ctx.kin.arms[side]
    try:
        path = plan_arm_motion(ctx.kin, ctx.collisions, side, np.clip(ctx.kin.arm_q(side), arm.lo, arm.hi),
                               (p - RETREAT_DISTANCE * axis, R), allow_sampling=False)
    except MotionError:
        if open_fingers:
            ctx.move_fingers((side,), "open")
        return
    finally:
        ctx.kin.sync(ctx.env.data.qpos)
    samples = time_dense_path(path.waypoints, 1.0 / ctx.env.control_hz, v_max=0.3)
    if open_fingers:
        # Unhook in place first: backing out with the fingers still around a handle drags the part after the
        # hand (a shut drawer pulled open again by ~7 mm).
        finger_room.loosen_in_place(ctx, side)
        start, goal = ctx.action[HAND_SLICE[side]].copy(), np.array(HAND_POSTURES["open"])
        for k, q in enumerate(samples, 1):
            ctx.action[ARM_SLICE[side]] = q
            ctx.action[HAND_SLICE[side]] = start + (goal - start) * min(1.0, 2.0 * k / len(samples))
            ctx.step()
    else:
        ctx.run_arm_samples({side: samples})
    ctx.hands[side].last_approach = None

def coordinate_arms(ctx: PlanningContext, samples: dict[Side, np.ndarray]) -> dict[Side, np.ndarray]:
    """Both arms move at once: check every control step for arm-arm contact; if they would touch, move
    them one after the other (left first, then right), and if that collides too, give up with a reason.
    Arms carrying one object together move in step (shared_hold) and never one after the other."""
    ctx.kin.sync(ctx.env.data.qpos)
    for side in SIDES:
        ctx.attach_held(side)
    together = shared_hold.shared_object(ctx.holding) is not None
    if together:
        samples = shared_hold.in_step(ctx.kin, samples)
        ctx.kin.sync(ctx.env.data.qpos)

    # Arms that start in contact may only come apart (a giver's thumb still on the bottle the taker holds).
    ctx.kin.forward()
    need = min(0.003, ctx.collisions.arm_arm_distance() - 1e-4)

    def clear(left: np.ndarray, right: np.ndarray) -> bool:
        # Each arm's own path was checked against the scene when it was planned; here only arm vs arm.
        n = max(len(left), len(right))
        for k in range(0, n, 2):
            ctx.kin.set_arm("left", left[min(k, len(left) - 1), :7])
            ctx.kin.set_arm("right", right[min(k, len(right) - 1), :7])
            ctx.kin.forward()
            if ctx.collisions.arm_arm_distance() < need:
                return False
        return True

    try:
        left, right = samples["left"], samples["right"]
        if clear(left, right):
            return samples
        if together:
            raise PlanningError("move_to_pose_with_screw", "the two arms carrying "
                                f"{ctx.hands['left'].held.type_name} {ctx.hands['left'].held.obj_id} together would "
                                "collide with each other on the way")
        left_first = {"left": left, "right": np.vstack([np.repeat(right[:1], len(left), 0), right])}
        if clear(left_first["left"], left_first["right"]):
            ctx.log[-1].message = "moved the arms one after the other to keep them apart"
            return left_first
        # The other order: the right arm may be the one in the way (leaving a hand-over, it goes home first).
        right_first = {"left": np.vstack([np.repeat(left[:1], len(right), 0), left]), "right": right}
        if clear(right_first["left"], right_first["right"]):
            ctx.log[-1].message = "moved the arms one after the other (right first) to keep them apart"
            return right_first
        raise PlanningError("move_to_pose_with_screw", "the two arms' motions would collide with each other, "
                            "together and one after the other: move one hand first to a pose out of the other's "
                            "way (e.g. its *_hand_init_pose), then the other, in two calls")
    finally:
        ctx.kin.sync(ctx.env.data.qpos)


def turns_standing_object(ctx: PlanningContext, side: Side, target: Pose) -> bool:
    """Whether the hand carries an object that rests on something and the move turns it by more than
    LIFT_BEFORE_TURN_DEG."""
    if not ctx.carries(side) or placing.height_above_support(ctx.env, ctx.hands[side].held) > LIFT_BEFORE_TURN_M:
        return False
    _, R_now = ctx.kin.ee_pose(side)
    return np.degrees(rotation_angle(R_now, target.R)) > LIFT_BEFORE_TURN_DEG

def plan_side(ctx: PlanningContext, side: Side, target: Pose, path_constraints: list = ()) -> np.ndarray:
    t0 = time.perf_counter()
    ctx.hands[side].take("goal_moved")
    try:
        with touch_for(ctx, side, target):
            return plan_side_timed(ctx, side, target, path_constraints)
    finally:
        ctx.plan_seconds.append(time.perf_counter() - t0)

def touch_for(ctx: PlanningContext, side: Side, target: Pose):
    """The fingers may come closer to the table on the way to a goal that was solved that way."""
    if not getattr(target, "finger_table_slack", 0.0):
        return nullcontext()
    table = ctx.collisions.body_geoms(ctx.env.model.body("table").id)
    return ctx.collisions.allow_touch(ctx.collisions.finger_geoms(side), table, target.finger_table_slack)

def plan_side_timed(ctx: PlanningContext, side: Side, target: Pose, path_constraints: list) -> np.ndarray:
    ctx.kin.sync(ctx.env.data.qpos)
    ignored_before = set(ctx.collisions.ignored_bodies)
    held = ctx.hands[side].held
    ctx.attach_held(side)
    if is_part(held):
        ctx.collisions.ignored_bodies.add(ctx.env.model.body(held.body).id)  # the hand is on the part
    ctx.ignore_contents(side)
    if target.presses and target.approach_object is not None:  # the fingertip is meant to press into it
        ctx.collisions.ignored_bodies.add(ctx.env.model.body(target.approach_object).id)
    # Contact can push a joint a hair past its limit (e.g. the wrist after a pinch); plan from inside them.
    arm = ctx.kin.arms[side]
    q0 = np.clip(ctx.kin.arm_q(side), arm.lo, arm.hi)
    dt = 1.0 / ctx.env.control_hz
    hand = ctx.action[HAND_SLICE[side]].copy()
    try:
        legs: list[JointPath] = []
        posture = None
        if target.follow is None and turns_standing_object(ctx, side, target):
            try:
                p_now, R_now = ctx.kin.ee_pose(side)
                legs.append(plan_arm_motion(ctx.kin, ctx.collisions, side, q0,
                                            (p_now + np.array([0.0, 0.0, LIFT_BEFORE_TURN_M]), R_now),
                                            allow_sampling=False))
                q0 = legs[-1].waypoints[-1]
            except MotionError:
                pass  # no room straight above: turn it from where it is
        if target.follow is not None:
            try:
                path = part_grip.follow_part(ctx, side, q0, target)
                return _with_hand(time_dense_path(path, dt, v_max=0.6, a_max=2.0), hand)
            except MotionError:
                # A fingertip pushing a part (nothing held) may instead go straight to the solved goal.
                if ctx.hands[side].held is not None or target.joint_q is None:
                    raise
                target = Pose(target.p, target.q, joint_q=target.joint_q, side=side)
        if target.approach_axis is not None and target.joint_q is not None:
            # Come in straight along the approach axis from a pre-pose reached any collision-free way.
            plan = approach.plan_approach(ctx, side, q0, target)
            # after the lift before a turn, if there was one: the approach starts where the lift ends
            legs, posture = legs + plan.legs, plan.posture
            if plan.axis is not None:
                ctx.hands[side].approach_used = plan.axis  # the way back out after the grip
            if "solved" in plan.label or posture is not None or plan.axis is not None:  # not the way asked
                ctx.events.append(f"the {side} hand came in {plan.label}"
                                   + (f" with the fingers {posture}" if posture else ""))
        else:
            legs += plain_move(ctx, side, q0, target, path_constraints)
    except MotionError as exc:
        advice = "" if "Suggestion" in str(exc) else motion_advice(str(exc))
        raise PlanningError("move_to_pose_with_screw",
                            f"{side} arm: {exc}" + (f". Suggestion: {advice}" if advice else "")) from None
    finally:
        ctx.collisions.ignored_bodies = ignored_before
        ctx.kin.sync(ctx.env.data.qpos)
    out = []
    # Gentler with something in the hand: a pinched object slips under hard accelerations (on a planned path
    # too: there the fastest profile swings a block held by its end out of the fingers).
    carrying = ctx.carries(side)
    for k, leg in enumerate(legs):
        if leg.method == "rrt_connect":
            samples = time_parametrize(leg.waypoints, dt=dt, **(CARRY_LIMITS if carrying else {}))[1]
        else:
            v, a = (CARRY_LIMITS["v_max"], CARRY_LIMITS["a_max"]) if carrying else (1.0, 3.0)
            samples = time_dense_path(leg.waypoints, dt, v_max=v, a_max=a)
        if k == len(legs) - 1 and posture is not None and len(legs) > 1:
            # Change the fingers at the pre-pose, arm still, before the last (straight) leg.
            goal = np.array(HAND_POSTURES[posture])
            n = max(1, int(round(HAND_MOTION_TIME * ctx.env.control_hz)))
            hold = np.repeat(out[-1][-1:, :7], n, 0) if out else np.repeat(samples[:1], n, 0)
            fingers = hand + (goal - hand) * (np.arange(1, n + 1) / n)[:, None]
            out.append(np.hstack([hold, fingers]))
            hand = goal
        out.append(_with_hand(samples, hand))
    return np.vstack(out)

def plan_leg(ctx: PlanningContext, side: Side, q: np.ndarray, target: Pose, path_constraints: list) -> JointPath:
    """A screw motion (or a sampled path) from `q` to the target; to a pre-push pose (target1) in the posture
    solved for it where a way keeps to it: the push's stages are tracked from there (push_move)."""
    return plan_arm_motion(ctx.kin, ctx.collisions, side, q, (target.p, target.R), q_goal=target.joint_q,
                           path_constraints=path_constraints, seed=ctx.seed,
                           keep_posture=getattr(target.push, "phase", None) == "pre")


def plain_move(ctx: PlanningContext, side: Side, q0: np.ndarray, target: Pose, path_constraints: list) -> list[JointPath]:
    """A screw motion (or a sampled path) to the target; where there is none, the transit stage's recoveries
    (a carried object let down into a container from above, an empty hand rising first)."""
    try:
        return [plan_leg(ctx, side, q0, target, path_constraints)]
    except MotionError as exc:
        return ctx.recover("transit", LegRequest(side, q0, target, list(path_constraints)), exc)


def part_openness(ctx: PlanningContext, target: Pose) -> float | None:
    if target.follow is None:
        return None
    return follow_openness(ctx.env, target.follow)  # the followed joint's (a knob's own, on a door)

def check_part_followed(ctx: PlanningContext, side: Side, target: Pose, start: float) -> None:
    """After a move that rides with a part: did the part get to the openness asked? One more push from where
    it stopped if it moved a good part of the way; a part that stays short is an error that says why (or an
    event, when it went most of the way)."""
    f = target.follow
    obj = ctx.env.scene.object(*f.obj)
    wanted = follow_articulation(ctx.env, f).openness_of(f.q_target)
    turned = turned_in_the_fingers(ctx, side, f)
    if turned:
        settle_turn(ctx, side, target, wanted, start)
    got = part_openness(ctx, target)
    way = wanted - start
    if abs(got - wanted) <= FOLLOW_TOL or abs(way) < 1e-6:
        return
    if (got - start) / way >= FOLLOW_RETRY and not turned:  # a turned part had its corrections
        try:
            ctx.run_arm_samples({side: plan_side(ctx, side, target)})
            ctx.settle(0.2)
        except (MotionError, PlanningError):
            pass  # no way on from where the part stopped: it stays there, judged below as it is
        got = part_openness(ctx, target)
        if abs(got - wanted) <= FOLLOW_TOL:
            ctx.events.append(f"pushed {part_label(ctx, f)} a second time to reach openness {round(wanted, 2):g}")
            return
    share = (got - start) / way
    label = part_label(ctx, f)
    to_shut = wanted <= regrip.SHUT < got and ctx.hands[side].held is not None and target.regrip is None \
        and ctx.regrips_left > 0
    if share >= 0.5:
        ctx.events.append(f"{label} reached openness {got:.2f} of the {wanted:g} asked")
        if to_shut:
            # Short of shut, held: let go and push it shut where the task has a push (recoveries/grip_again), as
            # where the arm's reach ends; where that fails it stays here, as before.
            target.regrip = regrip.request(f, wanted, ctx.hands[side].grip, got, optional=True,
                                           why=f"{label} stopped at openness {got:.2f} in the {side} hand")
        return
    shut_after = target.regrip is not None and target.regrip.openness <= regrip.SHUT  # part_grip stops short
    if to_shut or shut_after:
        # The grip came off (a lid's tab slips out of the fingers): let go and push it shut from here; where
        # neither the push nor a second grip gets it shut, the move fails as before.
        why = f"{label} stayed at openness {got:.2f}, the {side} hand's grip on it slipping"
        if shut_after:
            target.regrip.reached, target.regrip.why = got, why
        else:
            target.regrip = regrip.request(f, wanted, ctx.hands[side].grip, got, optional=False, why=why)
        return
    if ctx.hands[side].held is not None:
        why = (f"the {side} hand's grip on it {'came off' if not ctx.holds(side, obj) else 'held, but the part did not follow'}: "
               f"{grip_again_advice(ctx.hands[side].grip)}")
    else:
        why = ("the fingertip did not carry it (it slid off or lost contact): put the fingertip where the part "
               "has to give way (for a flip: under the edge, e.g. offset along the part's inner axis), push in "
               "smaller steps with explicit Constraints, or grasp it and move it with openness=")
    raise PlanningError("move_to_pose_with_screw",
                        f"{label} is at openness {got:.2f}{in_degrees(ctx, f, got)} after the move, not the "
                        f"{round(wanted, 2):g}{in_degrees(ctx, f, wanted)} asked (it moved {max(share, 0.0) * 100:.0f}% "
                        f"of the way from {start:.2f}): {why}")


def grip_again_advice(grip: str | None) -> str:
    """What to change after a held part did not follow, in the grip's own terms: a pinch is taken again with thumb
    and index on the part's two opposite faces (a knob's fin: across its thickness), a grasp around the part."""
    if grip == "pinch":
        return ("pinch it again (action='pinch': thumb and index on its two opposite faces) and turn it in smaller "
                "steps of openness")
    return "grasp it again and move it in smaller steps of openness"


def part_label(ctx: PlanningContext, f) -> str:
    """The moved part as an author names it: "box 0", or "safe 0's knob" for a part with a joint of its own
    (its openness is not the object's: `openness=` with a knob point is the knob's)."""
    obj = ctx.env.scene.object(*f.obj)
    part = follow_articulation(ctx.env, f).part
    return f"{obj.type_name} {obj.obj_id}" + (f"'s {part}" if part else "")


def in_degrees(ctx: PlanningContext, f, openness: float) -> str:
    """" (77 deg)": an openness of a part on a hinge in degrees of its turn; "" for a slide."""
    m = ctx.env.model
    if m.jnt_type[m.joint(f.joint).id] != mujoco.mjtJoint.mjJNT_HINGE:
        return ""
    art = follow_articulation(ctx.env, f)
    return f" ({np.degrees(abs(art.open - art.closed)) * openness:.0f} deg)"


def turned_in_the_fingers(ctx: PlanningContext, side: Side, f) -> bool:
    """A held part turned about a hinge through the hold (a knob by its fin) that stays where it is left: the
    fingers' give lags it behind the hand by some degrees, which a second look can correct."""
    from humanoidgen.planning.part_joint import hinge_through_hold, part_stays

    hand = ctx.hands[side]
    if hand.held is None:
        return False
    return hinge_through_hold(ctx.env, side, hand.grip, f.joint) and part_stays(ctx.env, f.joint, f.q_target)


def settle_turn(ctx: PlanningContext, side: Side, target: Pose, wanted: float, start: float) -> None:
    """Closed loop on a part turned in the fingers: measure where it is, and follow on (or back) toward the angle
    asked by that error, aimed past by it, up to TURN_CORRECTIONS times, until it is at the angle asked or past it
    by at most TURN_TOL_DEG (the way it was turned), not short of it: a knob asked 60 deg, held by a pinch,
    stopped at 55; asked 90 in one move, at 77 (and a task asking 90 deg means 90 at least)."""
    f = target.follow
    art = follow_articulation(ctx.env, f)
    deg = np.degrees(abs(art.open - art.closed))  # openness 1 in degrees
    half = TURN_TOL_DEG / 2 / deg
    sign = 1.0 if wanted >= start else -1.0  # the way it is turned
    goal = float(np.clip(wanted + sign * half, 0.0, 1.0))  # the middle of the band

    def off() -> float:
        return part_openness(ctx, target) - goal

    for _ in range(TURN_CORRECTIONS):
        err = -off()
        # Only on the way it was turned: turned back, the fingers slid on the fin and left it where it was (and one
        # such try dragged a knob back to 0), so an angle a little past the band is left as it is.
        if sign * err <= half or ctx.hands[side].held is None or not ctx.holds(side, ctx.hands[side].held):
            break
        # Aimed past the band by part of the error left: the fingers' give lags the correction as it lagged the
        # move (by all of it, a knob asked 60 deg came to 65; by none, to 48 against its friction).
        step = Pose(target.p, target.q, side=side)
        step.follow = replace(f, q_target=art.joint_position(float(np.clip(goal + AIM_PAST * err, 0.0, 1.0))))
        # Each correction is tried in the simulation first, from where the hand is on the part now and back to
        # how it closed on it (`grip_anchor`), and the one that turns the part on the most is made; none: the
        # corrections stop. The hand is ahead of the part by the fingers' give, and a short move taking that back
        # turned a knob back (81 deg of 108 asked, to 57); the arm's way near its joint limits turned the hand
        # back as well (a knob at 92 deg of 120 asked dragged to 76, then 0); neither way alone did for all.
        best = best_correction(ctx, side, lambda: plan_side(ctx, side, step), lambda: part_openness(ctx, target),
                               goal, sign)
        if best is None:
            break
        try:
            ctx.run_arm_samples({side: best})
            ctx.settle(0.2)
        except (MotionError, PlanningError):
            break
    if abs(off()) > half:
        ctx.events.append(f"{part_label(ctx, f)} is at {part_openness(ctx, target) * deg:.0f} deg, not the "
                          f"{wanted * deg:.0f} deg asked: the {side} hand's corrections stopped there")
