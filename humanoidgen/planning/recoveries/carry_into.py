"""Let down from above: a carried object whose goal lies inside a deep container, with no way down between its
walls, is brought to a goal straight above it, clear of the container's top, where letting go drops it in
(`drop_in`). The hand keeps its present orientation where it can (a pinched block swung about slips)."""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.planning import placing
from humanoidgen.planning.approach import PRE_POSE_TURN_DEG
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.drop_in import DROP_HIGHER_M, drop_in, object_geoms
from humanoidgen.planning.finger_room import OPEN_CLEARANCE_M, finger_sweep_clearance
from humanoidgen.planning.goal_targets import pose_within
from humanoidgen.planning.motion import JointPath, MotionError, plan_arm_motion
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.recovery import LegRequest, Recovery
from humanoidgen.sim.action import HAND_SLICE
from humanoidgen.sim.geometry import mat_to_quat
from humanoidgen.sim.layout import Side
from humanoidgen.sim.scene import SceneObject


class CarryInto(Recovery):
    stage = "transit"
    trigger = "failure"
    answers = "no way to a carried object's goal (inside a deep container)"
    tries = "a goal straight above it, clear of the container's top, where letting go drops it in"
    event = "the <side> hand brought <object> <n> cm above where asked, clear of <container>'s top"

    def applies(self, ctx: PlanningContext, request: LegRequest, failure: Exception | None) -> bool:
        return not request.path_constraints and ctx.carries(request.side)

    def attempt(self, ctx: PlanningContext, request: LegRequest, failure: Exception | None) -> list[JointPath]:
        legs = carry_into(ctx, request.side, request.q0, request.target)
        if legs is None:
            raise failure
        return legs


def carry_into(ctx: PlanningContext, side: Side, q0: np.ndarray, target: Pose) -> list[JointPath] | None:
    """A carried object's goal inside a deep container, out of the hand's way (`drop_in`): the object's centre
    straight above that goal, clear of the container's top, where letting go drops it in; None if that is not
    it. The hand keeps its present orientation if it can (a pinched block swung about slips), else takes the
    goal's."""
    held = ctx.hands[side].held
    p_hand, R_hand = ctx.env.hand_pose(side)
    p_obj, R_obj = placing.object_pose(ctx.env, held)
    centre = target.p + target.R @ R_hand.T @ (p_obj - p_hand)  # where the plan puts the object's centre
    way = drop_in(ctx.env, held, centre, target.R @ R_hand.T @ R_obj)
    if way is None:
        return None
    what = f"{way.container.type_name} {way.container.obj_id}"
    # Hand orientations to try, where the hand goes with each for the object's centre to be at `centre`, and
    # how far up that goal moves with the object so turned (lowest first).
    hands = [(R, p, way.raises(held, centre, R @ R_hand.T @ R_obj))
             for R, p in ((R_hand, centre - (p_obj - p_hand)), (target.R, target.p))]
    for k in range(len(DROP_HIGHER_M)):
        for R, p, raises in hands:
            goal = p + np.array([0.0, 0.0, raises[k]])
            solved = ctx.solver.solve(side, pose_within(side, goal, R, PRE_POSE_TURN_DEG,
                                                         f"{held.type_name} {held.obj_id} above {what}"),
                                       q0, ctx.nominal[side])
            if not solved.success or not opens_clear(ctx, side, solved.q, way.container):
                continue
            try:
                leg = plan_arm_motion(ctx.kin, ctx.collisions, side, q0, (solved.ee_pos, solved.ee_mat),
                                      q_goal=solved.q, seed=ctx.seed)
            except MotionError:
                continue
            ctx.hands[side].goal_moved = Pose(solved.ee_pos, mat_to_quat(solved.ee_mat), joint_q=solved.q, side=side)
            rise = float(solved.ee_pos[2] - target.p[2])
            ctx.events.append(f"the {side} hand brought {held.type_name} {held.obj_id} {rise * 100:.0f} cm above "
                               f"where asked, clear of {what}'s top: no way leads down between its walls; let go "
                               "there, it drops in")
            return [leg]
    return None

def opens_clear(ctx: PlanningContext, side: Side, q: np.ndarray, obj: SceneObject) -> bool:
    """Whether the hand, with the arm at `q`, can open its fingers fully without coming within
    OPEN_CLEARANCE_M of `obj`."""
    ctx.kin.set_arm(side, q)
    try:
        d, _ = finger_sweep_clearance(ctx.kin, ctx.collisions, side, ctx.action[HAND_SLICE[side]].copy(),
                                      np.array(HAND_POSTURES["open"]), object_geoms(ctx.env.model, obj))
    finally:
        ctx.kin.sync(ctx.env.data.qpos)
    return d >= OPEN_CLEARANCE_M
