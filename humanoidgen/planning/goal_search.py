"""How the planner looks for a goal pose before it says there is none (stage: goal, functions of a PlanningContext) behind
`generate_end_effector_pose`.

In order, each rung tried only when the ones before found nothing (so a goal found before is found the same way):

1. a held articulated part carries the hand: the goal is where the grip goes with the part (tracked along the
   part's joint path from the grip as it is), not a fresh solve of the grip at the new openness;
2. the grip as asked, then the object's other annotated grips (straight approach fitting preferred), then the
   first once more with many more solver seeds (`GoalSolver.solve(thorough=True)`);
3. the fingers may come within FINGER_TABLE_CLEARANCE of the table (not the general 5 mm) when the contact the
   goal needs is between a finger and the table: a fingertip taking a low edge (an event says so);
4. the wrist's freedom: each exact axis of a generated grip or push relaxed into a cone (CONE_DEG for the
   approach direction, ROLL_DEG about it), the exact axes kept as a preference, then wider (WIDE_CONE_DEG,
   WIDE_ROLL_DEG); for at most RELAXED_WAYS grips and RELAX_BUDGET_S seconds (an event gives the angles taken);
5. a loose object's pinch with the fingers turned about the squeeze axis (`pinch_slant`: the wrist higher, over
   the torso or a wall beside the hand).

A goal found for a carried object that turns a joint past near_goal.FAR_JOINT_DEG is solved again near the arm's
posture (near_goal.py; an event says so).

A failure then says which constraint missed and by how much, or which bodies collide, and what to change
(`feedback`). A push that cannot move a part the way asked (the fingertip would have to pull) is refused first.
"""

from __future__ import annotations

from dataclasses import replace

import time
from contextlib import nullcontext

import numpy as np

from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.feedback import push_advice
from humanoidgen.planning.goal_solver import GoalResult
from humanoidgen.planning.goal_targets import AxisWithin
from humanoidgen.planning.motion import track_poses
from humanoidgen.planning.part_joint import PartFollow, part_stays, follow_articulation, follow_openness, grip_joint
from humanoidgen.planning import regrip_request as regrip
from humanoidgen.planning.poses import Pose
from humanoidgen.sim.layout import HAND_PREFIX, ROOT_BODY, Side
from humanoidgen.planning import approach, pinch_slant
from humanoidgen.planning import part_grip
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.recovery import GoalFound
from humanoidgen.planning.goal_checks import check_push_direction, goal_failure, pushes_toward, use_ignores

FINGER_TABLE_CLEARANCE = 0.0015  # m: fingers meant to touch may come this close to the table
CONE_DEG = 15.0  # the approach direction of a grip or push may tilt this far
ROLL_DEG = 15.0  # and the grip turn this far about it
# Then, if that found nothing, a wider cone: an upright laptop screen's top edge at the far end of the right arm's
# reach (close_laptop_hard, laptop turned 24 deg) is pinched from above only 139 mm out of reach, and with the
# wrist tilted 16-39 deg, it is pinched and brought down (measured on the corpus plans' failing seeds).
WIDE_CONE_DEG = 40.0
WIDE_ROLL_DEG = 30.0
RELAXED_WAYS = 3  # grips tried with the wrist's freedom: the first and two alternatives
RELAX_BUDGET_S = 6.0  # seconds for rungs 3 and 4 together
RELAX_SOLVE_S = 2.0  # no new solver seed after this long in one of their solves
RELAX_MAX_MISS = 0.08  # m: grips missing by more than this are not tried with the wrist's freedom
RELAX_SEEDS = 4  # and at most this many seeds each (the current and nominal postures, two random)
ARC_GOOD = 1.8  # a grasp posture that can move its part this far (of 2: both ways to the ends) is kept as is
ARC_MARGIN = 0.1  # another posture is taken only if it reaches this much more of the arc
# A held part the arm can move at least this share of the way is moved that far, gripped again and moved on.
REGRIP_MIN_SHARE = 0.25
PARTIAL_ENOUGH = 0.5  # from this share of the way on, a part that stays put need not be gripped again (recoveries/grip_again.py)
ON_POINT = 0.025  # a fingertip this near a push point is on it: a push from there rides with the part
TWISTED_RAD = 1.5  # an arm joint this far from its nominal posture: a pre-push goal is solved from the nominal one



def solve_goal(ctx: PlanningContext, constraints: list, side: Side) -> tuple[GoalResult, Pose]:
    ctx.kin.sync(ctx.env.data.qpos)
    q_now = ctx.kin.arm_q(side)
    gen = getattr(constraints[0], "meta", None)
    held = ctx.hands[side].held
    follow = getattr(gen, "follow", None) if gen is not None else None
    holds_part = follow is not None and held is not None and held.body == follow.body
    if follow is not None and not holds_part:
        check_push_direction(ctx, side, gen)
    # The hand rides with the part from where it is on it: holding it, or a fingertip already on the point.
    riding = holds_part or (follow is not None and held is None and on_push_point(ctx, side, follow))
    ignored_before = set(ctx.collisions.ignored_bodies)
    slack = 0.0
    try:
        result = None
        if riding:
            result = riding_goal(ctx, side, follow)
        if result is None or not result.success:
            first_try = result
            result, gen, tried = exact_goal(ctx, side, constraints, gen, ignored_before, thorough=not riding)
            if first_try is not None and (not result.success or not reaches_back(ctx, side, follow, result)):
                result = first_try  # the part's own path says best why not
        if not result.success and not riding and ctx.wider_search:
            result, gen, slack = wider_goal(ctx, side, gen, tried, ignored_before, result)
            if not result.success:
                result, gen = pinch_slant.slanted_goal(ctx, side, gen, ignored_before, result)
        if result.success and not riding and getattr(gen, "grip_part", None) is not None:
            result, gen = prefer_arc(ctx, side, gen, result, ignored_before)
        if result.success and not riding:
            # The constraints as passed (a plan may add its own to generated ones), or the other grip taken.
            cons = constraints if gen is None or gen is getattr(constraints[0], "meta", None) else gen.constraints
            found = GoalFound(side, cons, q_now, result)
            ctx.after("goal", found)  # e.g. a carried object's goal taken nearer the arm's posture
            result = found.result
    finally:
        ctx.collisions.ignored_bodies = ignored_before
        ctx.kin.sync(ctx.env.data.qpos)
    ctx.goal_results.append(result)
    partial = None
    if not result.success and riding and result.partial is not None and ctx.regrips_left > 0:
        result, partial = partial_goal(ctx, side, follow, result)
    if not result.success:
        raise PlanningError("generate_end_effector_pose", goal_failure(ctx, side, constraints, gen, result))
    pose = Pose.from_mat(result.ee_pos, result.ee_mat, joint_q=result.q, side=side)
    pose.finger_table_slack = slack
    if gen is not None:
        pose.approach_axis = gen.approach_axis
        pose.approach_object = gen.approach_object
        pose.approach_part = grip_joint(gen)
        pose.follow = gen.follow
        pose.posture = gen.posture
        pose.presses = getattr(gen, "presses", False)
    if partial is not None:
        q_reached, pose.regrip = partial
        pose.follow = replace(gen.follow, q_target=q_reached)
    return result, pose

def partial_goal(ctx: PlanningContext, side: Side, follow: PartFollow, failed: GoalResult) -> tuple[GoalResult, tuple[float, dict]]:
    """A held part the arm can move only partway: the goal as far as it gets, the part's joint value there, and
    what the move does after it (`Pose.regrip`): it lets go, grips the part again and takes it on to the
    openness asked (planning/recoveries/grip_again.py). Where the part went PARTIAL_ENOUGH of the way and stays where the hand
    leaves it, that second grip is optional: if it cannot be taken, the part stays there (an event says so: the
    plan's next steps may push it on); otherwise its failure is the move's."""
    q, q_reached = failed.partial
    art = follow_articulation(ctx.env, follow)  # the held part's own joint (a knob's, on a door)
    now, reached, wanted = (follow_openness(ctx.env, follow), art.openness_of(q_reached),
                            art.openness_of(follow.q_target))
    share = (reached - now) / (wanted - now) if wanted != now else 1.0
    # A part already most of the way that stays put is worth going on with (a lid left at 0.88 of a task's
    # 0.9) but not worth failing the move for.
    optional = share >= PARTIAL_ENOUGH and part_stays(ctx.env, follow.joint, q_reached)
    return goal_at(ctx, side, q, failed.solve_time), (
        q_reached, regrip.request(follow, wanted, ctx.hands[side].grip, reached, optional))

def goal_at(ctx: PlanningContext, side: Side, q: np.ndarray, solve_time: float) -> GoalResult:
    """A solved goal at arm configuration q (its end-effector pose read from the kinematics)."""
    ctx.kin.set_arm(side, q)
    ctx.kin.forward()
    p, R = ctx.kin.ee_pose(side)
    ctx.kin.sync(ctx.env.data.qpos)
    return GoalResult(True, q, p, R, 0.0, [], None, 0, solve_time)

# -- ignore lists ----------------------------------------------------------------------------------

def on_push_point(ctx: PlanningContext, side: Side, follow: PartFollow) -> bool:
    from humanoidgen.objects.queries import get_point_in_env

    obj = ctx.env.scene.object(*follow.obj)
    tip = get_point_in_env(ctx.env, f"press_point_base_{side}_hand")
    point = get_point_in_env(ctx.env, follow.part_point, obj.type_name, obj.obj_id)
    return float(np.linalg.norm(tip - point)) < ON_POINT

def reaches_back(ctx: PlanningContext, side: Side, follow: PartFollow, result: GoalResult) -> bool:
    """Whether a freshly solved goal for a part the hand rides with can be used: the move then tracks the
    part's path back from it to where the hand is now (`part_grip.follow_part`'s fallback), so check that."""
    ctx.kin.sync(ctx.env.data.qpos)
    arm = ctx.kin.arms[side]
    q0 = np.clip(ctx.kin.arm_q(side), arm.lo, arm.hi)
    poses, _, _ = part_grip.part_path_poses(ctx, side, follow)
    back, reason = track_poses(ctx.kin, side, result.q, poses[-2::-1] + [ctx.kin.ee_pose(side)])
    return not reason and np.max(np.abs(back[-1] - q0)) < 0.15

def riding_goal(ctx: PlanningContext, side: Side, follow: PartFollow) -> GoalResult:
    t0 = time.perf_counter()
    use_ignores(ctx, side, None, set(ctx.collisions.ignored_bodies))
    arm = ctx.kin.arms[side]
    q0 = np.clip(ctx.kin.arm_q(side), arm.lo, arm.hi)
    path, q_steps, q_now, reason = part_grip.track_part(ctx, side, q0, follow)
    way = abs(follow.q_target - q_now)
    reached = abs(q_steps[len(path) - 1] - q_now) if len(path) else 0.0
    if not reason or (len(path) and reached >= part_grip.follow_enough(ctx, side) * way):
        return goal_at(ctx, side, path[-1], time.perf_counter() - t0)
    obj = ctx.env.scene.object(*follow.obj)
    held = ctx.hands[side].held is not None
    art = follow_articulation(ctx.env, follow)
    now = follow_openness(ctx.env, follow)
    got = art.openness_of(q_steps[len(path) - 1]) if len(path) else now
    wanted = art.openness_of(follow.q_target)
    pushes = pushes_toward(ctx, side, obj, wanted, skip_point=None if held else follow.part_point)
    ctx.kin.sync(ctx.env.data.qpos)
    partial = None
    if held and len(path) and reached >= REGRIP_MIN_SHARE * way:
        partial = (path[-1], float(q_steps[len(path) - 1]))
    elif held and part_stays(ctx.env, follow.joint, q_now):
        # Hardly any of the way from this grip (a screen lifted 0.3 -> 0.6 in one hold has the wrist turned so
        # far that it gets 0.6 -> 0.68 of a 0.85 asked): where the part stays put if let go, let go here and
        # grip it again in a posture that keeps its arc in reach (recoveries/grip_again.py; at most pipeline.BUDGETS.regrips times).
        partial = (path[-1], float(q_steps[len(path) - 1])) if len(path) else (q0, float(q_now))
    return GoalResult(False, None, partial=partial, violations=[
        f"the {side} hand {'holding' if held else 'pushing'} {obj.type_name} {obj.obj_id} can move it only "
        f"from openness {now:.2f} to {got:.2f} of the {wanted:.2f} asked ({reason}): the hand would have to go "
        f"where the {side} arm does not reach. " + (
            f"Move it to about {got:.2f} this way, then let go (open_hand) and push it the rest with the "
            f"fingertip (hand_press; " + push_advice(f"{obj.type_name} {obj.obj_id}", wanted, pushes, side) + ")"
            if held else f"Push it to about {got:.2f} from here, then from a point nearer the robot, or with the "
            f"other hand ({push_advice(f'{obj.type_name} {obj.obj_id}', wanted, pushes, side)})")],
        solve_time=time.perf_counter() - t0)

# -- rung 2: as asked, the other grips, more seeds ----------------------------------------------------
def exact_goal(ctx: PlanningContext, side: Side, constraints: list, gen, ignored_before: set[int], thorough: bool = True):
    first_gen = gen
    tried: list[tuple[object, list, GoalResult]] = []  # (grip or None, its constraints, result)
    use_ignores(ctx, side, gen, ignored_before)
    result = ctx.solver.solve(side, list(constraints), push_seed(ctx, side, gen), ctx.nominal[side])
    tried.append((gen, list(constraints), result))
    usable = result.success and approach.approach_fits(ctx, side, result, gen)
    for alternative in (gen.alternatives if gen is not None and not usable else []):
        use_ignores(ctx, side, alternative, ignored_before)
        retry = ctx.solver.solve(side, list(alternative.constraints), ctx.kin.arm_q(side), ctx.nominal[side])
        tried.append((alternative, list(alternative.constraints), retry))
        # A grip whose goal solves but whose straight approach does not fit is kept only as a last resort.
        if retry.success and approach.approach_fits(ctx, side, retry, alternative):
            result, gen = retry, alternative
            ctx.events.extend(getattr(alternative, "notes", []))  # what this way does differently
            break
        if retry.success and not result.success:
            result, gen = retry, alternative
    if not result.success and thorough:  # a last, slower try of the first way with many more seeds
        use_ignores(ctx, side, first_gen, ignored_before)
        retry = ctx.solver.solve(side, list(constraints), ctx.kin.arm_q(side), ctx.nominal[side], thorough=True)
        if retry.success:
            result, gen = retry, first_gen
    if not result.success:
        gen = first_gen
    return result, gen, tried

def push_seed(ctx: PlanningContext, side: Side, gen) -> np.ndarray:
    """The arm posture the goal solver starts from: the arm's own, except for the pose before a fingertip push
    (target1 of a task's push) where a grip before left the arm twisted far from its nominal posture: the push's
    stages are tracked from the posture found here, and one found near the twisted arm may not carry the part
    (open_box_hard seed 1, a lid lifted by its tab to 0.5 and let go shut: the arm's third joint 2.5 rad from
    nominal, target2 then pushed the lid from 0.00 to 0.00; the same target1 solved from the nominal posture, as
    in a fresh episode, flipped it open)."""
    q = ctx.kin.arm_q(side)
    push = getattr(gen, "push", None)
    if getattr(push, "phase", None) == "pre" and np.max(np.abs(q - ctx.nominal[side])) > TWISTED_RAD:
        return ctx.nominal[side]
    return q


# -- a grip on an articulated part: the arm posture that keeps the part's arc in reach ----------------
def prefer_arc(ctx: PlanningContext, side: Side, gen, result: GoalResult, ignored_before: set[int]) -> tuple[GoalResult, object]:
    """A grasp of a drawer handle or a lid's tab is nearly always followed by moving the part, and the arm
    cannot change its posture family while it holds it: where the solved posture reaches little of the
    part's arc (`part_grip.arc_span`), try the grip with the wrist's freedom (CONE_DEG) and keep the posture
    that reaches the most (an event says so)."""
    t0 = time.perf_counter()
    kind = "pinch" if gen.posture == "pinch" else "grasp"
    best_span = part_grip.arc_span(ctx, side, gen.grip_part, result.q, kind)
    if best_span >= ARC_GOOD:
        return result, gen
    first_span, best = best_span, (result, gen)
    for g in [gen] + [a for a in gen.alternatives if a.grip_part is not None][:RELAXED_WAYS - 1]:
        relaxed = _relax(side, g)
        if not relaxed or time.perf_counter() - t0 > RELAX_BUDGET_S:
            continue
        use_ignores(ctx, side, g, ignored_before)
        retry = ctx.solver.solve(side, relaxed, ctx.kin.arm_q(side), ctx.nominal[side],
                                  time_limit=RELAX_SOLVE_S, max_seeds=RELAX_SEEDS)
        if not retry.success or not approach.approach_fits(ctx, side, retry, g):
            continue
        span = part_grip.arc_span(ctx, side, g.grip_part, retry.q, kind)
        if span > best_span + ARC_MARGIN:
            best_span, best = span, (retry, g)
    if best[0] is not result:
        obj = "{} {}".format(*gen.grip_part.obj)
        ctx.events.append(f"the {side} hand takes {obj} with the wrist turned a little, in an arm posture that "
                           f"can move it over {50 * best_span:.0f}% of its arc (the exact grip: "
                           f"{50 * first_span:.0f}%)")
    return best

# -- rungs 3 and 4: closer to the table, the wrist's freedom -------------------------------------------
def wider_goal(ctx: PlanningContext, side: Side, gen, tried: list, ignored_before: set[int], failed: GoalResult):
    """(result, gen, finger-table slack) from the wider searches, or the failure as it was."""
    t0 = time.perf_counter()
    table = ctx.env.model.body("table").id
    fingers = set(finger_bodies(ctx, side))
    low = [(g, cons) for g, cons, r in tried
           if r.contacts and all(b1 in fingers and b2 == table for b1, b2, _ in r.contacts)]
    slack = ctx.solver.clearance - FINGER_TABLE_CLEARANCE
    table_geoms = ctx.collisions.body_geoms(table)
    finger_geoms = ctx.collisions.finger_geoms(side)
    for g, cons in low:
        use_ignores(ctx, side, g, ignored_before)
        with ctx.collisions.allow_touch(finger_geoms, table_geoms, slack):
            retry = ctx.solver.solve(side, cons, ctx.kin.arm_q(side), ctx.nominal[side],
                                      time_limit=RELAX_SOLVE_S, max_seeds=RELAX_SEEDS)
        if retry.success:
            ctx.events.append(table_event(ctx, side, retry, finger_geoms, table_geoms))
            return retry, g, slack
    if gen is None or getattr(gen, "approach_axis", None) is None:
        return failed, gen, 0.0
    robot = {ctx.env.model.body(b).id for b in range(ctx.env.model.nbody)
             if int(ctx.env.model.body_rootid[b]) == ctx.env.model.body(ROOT_BODY).id}
    if failed.contacts and any(b2 in robot for _, b2, _ in failed.contacts):
        return failed, gen, 0.0  # the other arm or the body in the way: turning the wrist does not clear it
    cones = [(CONE_DEG, ROLL_DEG), (WIDE_CONE_DEG, WIDE_ROLL_DEG)]
    if not failed.contacts and all(r.miss is not None and r.miss > RELAX_MAX_MISS for _, _, r in tried):
        cones = cones[1:]  # far out of reach: a cone of CONE_DEG at the wrist does not bring it there
    ways = [gen] + list(gen.alternatives)[:RELAXED_WAYS - 1]
    for cone, roll in cones:
        for touch in ((0.0, slack) if low else (0.0,)):
            for g in ways:
                if time.perf_counter() - t0 > RELAX_BUDGET_S:
                    break
                relaxed = _relax(side, g, cone, roll)
                if not relaxed:
                    continue
                use_ignores(ctx, side, g, ignored_before)
                with (ctx.collisions.allow_touch(finger_geoms, table_geoms, touch) if touch else nullcontext()):
                    retry = ctx.solver.solve(side, relaxed, ctx.kin.arm_q(side), ctx.nominal[side],
                                              time_limit=RELAX_SOLVE_S, max_seeds=RELAX_SEEDS)
                if retry.success:
                    ctx.events.append(relaxed_event(ctx, side, g, relaxed, retry))
                    if touch:
                        ctx.events.append(table_event(ctx, side, retry, finger_geoms, table_geoms))
                    return retry, g, touch
                if retry.contacts and not failed.contacts and g is gen:
                    failed = retry  # what the wrist's freedom runs into says more than a bare miss
    return failed, gen, 0.0

def finger_bodies(ctx: PlanningContext, side: Side) -> list[int]:
    m = ctx.env.model
    return [b for b in range(m.nbody) if m.body(b).name.startswith(HAND_PREFIX[side] + "_")]

def table_event(ctx: PlanningContext, side: Side, result: GoalResult, finger_geoms: list[int], table_geoms) -> str:
    ctx.kin.set_arm(side, result.q)
    ctx.kin.forward()
    d = min(ctx.collisions.pair_distance(g, t) for g in finger_geoms for t in table_geoms)
    ctx.kin.sync(ctx.env.data.qpos)
    return (f"the {side} fingers come within {max(d, 0.0) * 1000:.1f} mm of the table at this goal (they are "
            f"meant to touch there; {ctx.solver.clearance * 1000:.0f} mm elsewhere)")

def relaxed_event(ctx: PlanningContext, side: Side, gen, relaxed: list, result: GoalResult) -> str:
    ctx.kin.set_arm(side, result.q)
    ctx.kin.forward()
    angles = [f"{c.name.split(' (within')[0]} {c.angle(ctx.kin):.0f} deg" for c in relaxed
              if isinstance(c, AxisWithin) and not c.soft]
    ctx.kin.sync(ctx.env.data.qpos)
    what = gen.constraints[0].name if gen.constraints else "the grip"
    return (f"the exact {what} is out of the {side} hand's reach; it takes it with the wrist turned "
            f"({', '.join(angles)} off the annotated axes)")

# -- pushes ----------------------------------------------------------------------------------------

def _relax(side: Side, gen, cone_deg: float = CONE_DEG, roll_deg: float = ROLL_DEG) -> list:
    """The grip's constraints with each exact hand axis opened into a cone (and preferred exact): `cone_deg` for
    the approach direction, `roll_deg` for the others."""
    out, changed = [], False
    approach = getattr(gen, "approach_axis", None)
    for c in gen.constraints:
        if getattr(c, "type", "") == "parallel" and not c.soft and c.local_axis is not None:
            is_approach = approach is not None and abs(float(c.object_axis @ approach)) > 0.999
            limit = np.radians(cone_deg if is_approach else roll_deg)
            out.append(AxisWithin(side, c.local_axis, c.object_axis, limit, f"{c.name} (within {np.degrees(limit):.0f} deg)"))
            out.append(AxisWithin(side, c.local_axis, c.object_axis, limit, f"{c.name} (preferred)", soft=True))
            changed = True
        else:
            out.append(c)
    return out if changed else []
