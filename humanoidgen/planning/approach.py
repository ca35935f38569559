"""How a hand comes in to a grip or a push: straight along the operation's axis over the last few centimetres,
after getting to a pre-approach pose any collision-free way. Stage (approach): functions of a PlanningContext, used by
the transit stage (arm_moves).

Ways to come in, tried in order (the first whose transit can also be planned wins):

1. the straight line tracked back from the solved goal (the goal's arm posture), for APPROACH_DISTANCES;
2. straight lines from other directions that keep the object between thumb and fingers (from above, from the
   front, square to the axis), for OTHER_WAY_DISTANCES: as cheap as 1 (no goal solve), so before 3;
3. a pre-approach pose backed off along the axis and solved on its own (any arm posture, collisions avoided;
   the hand turned up to PRE_POSE_TURN_DEG if the exact orientation is out of reach there), for
   PRE_POSE_DISTANCES, with the straight (screw) motion tracked forward from it into the goal pose. A goal boxed
   in by joint limits, from which the line cannot be tracked back, is often reached this way from another posture.

The transit to the pre-pose is a screw motion, else RRT-Connect (`motion.plan_arm_motion`).

A movable part (a drawer's handle, a box lid) gives way when pushed, so an approach may touch the part it
comes to by at most PART_TOUCH. Where the fingers as they are would push it (the pre-grasp thumb stands 10 cm
out of the palm, in front of a handle) but open fingers would not, the hand opens at the pre-pose and comes in
open; the grasp then closes around the handle. Not where the fingers would strike something as they open there:
a pre-pinch's tucked fingers, unfolding at a safe's knob, stuck on the door beside it and the hand slid in
dragging them, 4 cm short; they come in as they are.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass, replace

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.planning.feedback import approach_advice
from humanoidgen.planning.finger_room import finger_sweep_clearance
from humanoidgen.planning.goal_targets import PoseTarget, pose_within
from humanoidgen.planning.motion import JointPath, MotionError, first_collision, plan_arm_motion, track_poses
from humanoidgen.planning.part_joint import grip_joint, moving_bodies
from humanoidgen.planning.poses import Pose, screw_interpolate
from humanoidgen.sim.layout import FINGERTIP_BODY, Side
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.hand_ops import is_part

# Grasps and pinches come in straight along the approach axis over the first of these that fits (metres).
APPROACH_DISTANCES = (0.08, 0.05, 0.03)
# Pre-approach poses solved on their own when the line cannot be tracked back from the goal (metres).
PRE_POSE_DISTANCES = (0.08, 0.05, 0.03, 0.02)
PRE_POSE_TURN_DEG = 20.0  # a solved pre-pose may be turned this far from the goal's orientation
WRAP_TOUCH = 0.003  # how far the open hand may press into a body it comes to wrap (m)
PART_TOUCH = 0.002  # how far an approach may press into a movable part it comes to (m)
# Where no way along the operation's axis fits: other directions that keep the object between thumb and fingers
# (a block held out beside an open drawer: the left hand's way in along the block runs its wrist into the drawer).
OTHER_WAY_DISTANCES = (0.05, 0.03)
OTHER_WAY_MAX_COS = 0.7  # other directions at least ~45 deg off the axis and off each other
APPROACH_BUDGET_S = 12.0  # no further way of coming in is tried after this long
# A transit that ends farther than this (rad, any joint) from where the way in starts ends in another arm posture.
JOIN_TOL = 1e-6
TRANSIT_TIME_LIMIT = 2.0  # RRT-Connect seconds per way of coming in after the first (the first gets the default)


@dataclass
class ComeIn:
    """One way of coming in: the joint path from the pre-pose into the goal, and how to get ready for it."""

    path: np.ndarray  # (n, 7), path[0] at the pre-pose, path[-1] at the goal pose
    pre: tuple[np.ndarray, np.ndarray]  # the pre-pose (p, R)
    label: str  # "8 cm" or "5 cm from a solved pre-pose": for the log and for failure reasons
    posture: str | None = None  # finger posture to take at the pre-pose before coming in (None: as they are)
    axis: np.ndarray | None = None  # the direction it comes in along, where not the operation's axis


@dataclass
class ApproachPlan:
    legs: list[JointPath]  # the transit to the pre-pose, then the straight approach
    posture: str | None  # see ComeIn.posture
    label: str
    axis: np.ndarray | None = None  # see ComeIn.axis



def plan_approach(ctx: PlanningContext, side: Side, q0: np.ndarray, target: Pose) -> ApproachPlan:
    """Transit and straight approach into `target` (which has an approach axis and joint_q); MotionError
    with every way's reason if none works."""
    reasons: list[str] = []
    first = True
    t0 = time.perf_counter()
    for way in ways_in(ctx, side, target, reasons):
        if time.perf_counter() - t0 > APPROACH_BUDGET_S:
            reasons.append(f"stopped looking after {APPROACH_BUDGET_S:.0f} s")
            break
        try:
            transit = plan_arm_motion(ctx.kin, ctx.collisions, side, q0, way.pre, q_goal=way.path[0],
                                      seed=ctx.seed, **({} if first else {"time_limit": TRANSIT_TIME_LIMIT}))
        except MotionError as exc:
            reasons.append(f"{way.label}: no way to the pre-approach pose ({exc})")
            first = False
            continue
        joined = join(ctx, side, transit, way, target, reasons)
        if joined is None:
            first = False
            continue
        return ApproachPlan([transit, JointPath(joined.path, "screw")], joined.posture, joined.label, joined.axis)
    advice = approach_advice(side, reasons, target.p, target.approach_axis)
    raise MotionError("no straight approach to the target (" + "; ".join(reasons) + ")"
                      + (f". Suggestion: {advice}" if advice else ""))

def join(ctx: PlanningContext, side: Side, transit: JointPath, way: ComeIn, target: Pose,
         reasons: list[str]) -> ComeIn | None:
    """The way in, starting where the transit ends. A 7-joint arm reaches one hand pose in many postures, and the
    transit may reach the pre-pose in another than the way in starts from (the G1's shoulder near its roll
    singularity: the same pose with shoulder pitch and yaw 1.0-1.4 rad apart). Played one after the other, the
    arm's targets would jump there in one control step and swing a pinched block out of the fingers; so the way in
    is tracked again from the transit's end (None, with the reason, where it cannot be followed from there)."""
    end = transit.waypoints[-1]
    if np.max(np.abs(end - way.path[0])) <= JOIN_TOL:
        return way
    fwd, reason = track_poses(ctx.kin, side, end, screw_interpolate(*way.pre, target.p, target.R))
    if not reason:
        path = np.vstack([end, fwd])
        posture, reason = check_way_in(ctx, side, path, target.approach_object, target.posture == "wrap",
                                       target.approach_part)
        if not reason:
            return replace(way, path=path, posture=posture)
    reasons.append(f"{way.label}: the way to the pre-approach pose ends in another arm posture than the way in "
                   f"starts from, and the way in cannot be followed from there ({reason})")
    return None


def ways_in(ctx: PlanningContext, side: Side, target: Pose, reasons: list[str]) -> Iterator[ComeIn]:
    """Every way of coming in that fits, most direct first; appends why the others do not fit."""
    p, R, axis, body = target.p, target.R, target.approach_axis, target.approach_object
    wrap = target.posture == "wrap"
    yield from lines_in(ctx, side, target, axis, APPROACH_DISTANCES, "", reasons)
    for u, how in other_ways_in(ctx, side, target):
        yield from lines_in(ctx, side, target, u, OTHER_WAY_DISTANCES, f" {how}", reasons, other=True)
    for distance in PRE_POSE_DISTANCES:
        label = f"{distance * 100:.0f} cm from a pre-approach pose solved on its own"
        solved = ctx.solver.solve(side, [PoseTarget(side, p - distance * axis, R, name="pre-approach pose")],
                                   target.joint_q, ctx.nominal[side])
        if not solved.success:
            # The hand may turn on the way in: a pre-pose turned up to PRE_POSE_TURN_DEG, screwed into the goal.
            solved = ctx.solver.solve(side, pose_within(side, p - distance * axis, R, PRE_POSE_TURN_DEG,
                                                         "pre-approach pose"), target.joint_q, ctx.nominal[side])
        pre = (solved.ee_pos, solved.ee_mat) if solved.success else (p - distance * axis, R)
        if not solved.success:
            reasons.append(f"{label}: the pre-approach pose is out of reach or in collision "
                           f"({'; '.join(solved.violations)})")
            continue
        fwd, reason = track_poses(ctx.kin, side, solved.q, screw_interpolate(*pre, p, R))
        if not reason:
            path = np.vstack([solved.q, fwd])
            posture, reason = check_way_in(ctx, side, path, body, wrap, target.approach_part)
            if not reason:
                yield ComeIn(path, pre, label, posture)
                continue
        reasons.append(f"{label}: {reason}")

def lines_in(ctx: PlanningContext, side: Side, target: Pose, u: np.ndarray, distances: tuple[float, ...], how: str,
              reasons: list[str], other: bool = False) -> Iterator[ComeIn]:
    """The straight lines into the goal along `u`, tracked back from the goal's arm posture over `distances`,
    that fit (`other`: `u` is not the operation's axis); appends why the others do not."""
    p, R, body = target.p, target.R, target.approach_object
    for distance in distances:
        pre = (p - distance * u, R)
        back, reason = track_poses(ctx.kin, side, target.joint_q, screw_interpolate(p, R, *pre))
        label = f"{distance * 100:.0f} cm{how}"
        if not reason:
            path = np.vstack([back[::-1], target.joint_q])
            posture, reason = check_way_in(ctx, side, path, body, target.posture == "wrap", target.approach_part)
            if not reason:
                yield ComeIn(path, pre, label, posture, axis=u if other else None)
                continue
        reasons.append(f"{label}: {reason}")

def other_ways_in(ctx: PlanningContext, side: Side, target: Pose) -> list[tuple[np.ndarray, str]]:
    """Approach directions other than the operation's axis that keep the grip's closing line (thumb to index
    at the goal) across the way in, so the object still comes in between thumb and fingers: from above, from
    the robot's side, and square to the axis both ways; each as (unit direction of motion, how)."""
    thumb, index = fingertips_at(ctx, side, target.joint_q)
    t = index - thumb
    if np.linalg.norm(t) < 1e-6:
        return []
    t = t / np.linalg.norm(t)
    axis = np.asarray(target.approach_axis, float)
    side_way = np.cross(t, axis)
    candidates = [(np.array([0.0, 0.0, -1.0]), "from above"), (np.array([1.0, 0.0, 0.0]), "from the front"),
                  (side_way, "square to the grip's axis"), (-side_way, "square to the grip's axis")]
    out: list[tuple[np.ndarray, str]] = []
    for v, how in candidates:
        v = v - (v @ t) * t  # across the closing line
        n = float(np.linalg.norm(v))
        if n < 0.5:
            continue
        v = v / n
        if v @ axis > OTHER_WAY_MAX_COS or any(v @ w > OTHER_WAY_MAX_COS for w, _ in out):
            continue
        out.append((v, how))
    return out

def fingertips_at(ctx: PlanningContext, side: Side, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Thumb and index tip positions with the arm at `q` and the fingers as they are now."""
    m = ctx.env.model
    tips = FINGERTIP_BODY[side]
    ctx.kin.set_arm(side, q)
    ctx.kin.forward()
    try:
        return (ctx.kin.data.xpos[m.body(tips["thumb"]).id].copy(),
                ctx.kin.data.xpos[m.body(tips["index"]).id].copy())
    finally:
        ctx.kin.sync(ctx.env.data.qpos)

def check_way_in(ctx: PlanningContext, side: Side, path: np.ndarray, body: str | None, wrap: bool,
                  part: str | None = None) -> tuple[str | None, str]:
    """(finger posture to come in with, "") when the approach path fits, else (None, why not). The body
    approached may be touched; everything else is avoided. `part`: the joint of the articulated part the
    hand comes to grip (`Pose.approach_part`)."""
    if first_collision_ignoring(ctx, side, path, body) is not None:
        return None, "the straight approach along the operation's axis collides"
    if body is None:
        return None, ""
    if wrap and not wrap_clear(ctx, side, path, body):
        return None, f"the open hand would push into {body} on the way in"
    if is_movable_part(ctx, body) and not part_clear(ctx, side, path, body):
        # Try the way in with open fingers: the grip closes around the part from there.
        saved = ctx.kin.hand_q(side)
        ctx.kin.set_hand(side, np.array(HAND_POSTURES["open"]))
        ctx.kin.forward()
        try:
            fits_open = first_collision_ignoring(ctx, side, path, body) is None and part_clear(ctx, side, path,
                                                                                                    body)
        finally:
            ctx.kin.set_hand(side, saved)
            ctx.kin.forward()
        if fits_open and room_to_change(ctx, side, path[0], "open", part):
            return "open", ""
        # Neither fits without pushing the part; come in as before (a part at its end stop does not move).
    return None, ""

def room_to_change(ctx: PlanningContext, side: Side, q: np.ndarray, posture: str, part: str | None) -> bool:
    """Whether the fingers can go from how they are to `posture` with the arm at `q` and come no nearer than
    PART_TOUCH into anything but the part moved by joint `part`, which gives way (a drawer the opening thumb
    touches); the rest of its object counts (a safe's door, beside the knob gripped). Unchecked (True) where
    the part is not known."""
    if part is None:
        return True
    base = ctx.kin.data.qpos.copy()
    ignored = set(ctx.collisions.ignored_bodies)
    ctx.collisions.ignored_bodies |= moving_bodies(ctx.env.model, part)
    try:
        ctx.kin.set_arm(side, q)
        ctx.kin.forward()
        clearance, _ = finger_sweep_clearance(ctx.kin, ctx.collisions, side, ctx.kin.hand_q(side),
                                              np.array(HAND_POSTURES[posture]), ctx.collisions.obstacles(side))
        return clearance > -PART_TOUCH
    finally:
        ctx.collisions.ignored_bodies = ignored
        ctx.kin.data.qpos[:] = base
        ctx.kin.forward()

def is_movable_part(ctx: PlanningContext, body: str) -> bool:
    obj = next((o for o in ctx.env.scene.objects if o.body == body), None)
    return is_part(obj)

def part_clear(ctx: PlanningContext, side: Side, path: np.ndarray, body: str) -> bool:
    return clear_of(ctx, side, path, body, PART_TOUCH)

def wrap_clear(ctx: PlanningContext, side: Side, approach: np.ndarray, body: str) -> bool:
    return clear_of(ctx, side, approach, body, WRAP_TOUCH)

def clear_of(ctx: PlanningContext, side: Side, path: np.ndarray, body: str, touch: float) -> bool:
    """Whether `path` stays out of `body` but for `touch` (everything else as the ignore list says)."""
    ignored = set(ctx.collisions.ignored_bodies)
    ctx.collisions.ignored_bodies.discard(ctx.env.model.body(body).id)
    try:
        return first_collision(ctx.kin, ctx.collisions, side, path, clearance=-touch) is None
    finally:
        ctx.collisions.ignored_bodies = ignored

def straight_approach(ctx: PlanningContext, side: Side, q_goal: np.ndarray, p: np.ndarray, R: np.ndarray, axis: np.ndarray,
                       approach_object: str | None, distances: tuple[float, ...] = APPROACH_DISTANCES,
                       wrap: bool = False, part: str | None = None):
    """The straight approach into a goal along `axis` tracked back from the goal, over the first distance
    that fits: (joint path from the pre-pose to the goal, the pre-pose, reasons) or (None, None, reasons)."""
    reasons = []
    for distance in distances:
        pre = (p - distance * axis, R)
        back, reason = track_poses(ctx.kin, side, q_goal, screw_interpolate(p, R, *pre))
        if not reason:
            approach = np.vstack([back[::-1], q_goal])
            _, reason = check_way_in(ctx, side, approach, approach_object, wrap, part)
            if not reason:
                return approach, pre, reasons
        reasons.append(f"{distance * 100:.0f} cm: {reason}")
    return None, None, reasons

def approach_fits(ctx: PlanningContext, side: Side, result, gen) -> bool:
    """Whether a solved grip can be approached straight along its axis (the shortest approach)."""
    if gen is None or gen.approach_axis is None or gen.follow is not None:
        return True
    ctx.kin.sync(ctx.env.data.qpos)
    ctx.attach_held(side)
    approach, _, _ = straight_approach(ctx, side, result.q, result.ee_pos, result.ee_mat, gen.approach_axis,
                                             gen.approach_object, distances=APPROACH_DISTANCES[-1:],
                                             wrap=gen.posture == "wrap",
                                             part=grip_joint(gen))
    ctx.kin.sync(ctx.env.data.qpos)
    return approach is not None


def first_collision_ignoring(planner, side: Side, path: np.ndarray, body: str | None) -> int | None:
    """`first_collision` along `path` with `body` (the object approached) off the obstacle list."""
    ignored = set(planner.collisions.ignored_bodies)
    if body is not None:
        planner.collisions.ignored_bodies.add(planner.env.model.body(body).id)
    try:
        return first_collision(planner.kin, planner.collisions, side, path, start_is_goal=True)
    finally:
        planner.collisions.ignored_bodies = ignored
