"""A goal near the arm's posture: the goal solver's first seed that succeeds can land on another branch of the
arm's inverse kinematics, the hand where asked but the shoulder and elbow turned through 150-200 deg; carrying
an object there swings it through a wide arc (cubes thrown 52 cm out of a cup tipped in stages). Where a
carried object's goal turns a joint more than near_goal.FAR_JOINT_DEG, the same constraints are solved again
from seeds about the arm's posture (`near_goal.nearer_goal`) and the first goal that turns no joint that far is
taken."""

from __future__ import annotations

import numpy as np

from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.near_goal import FAR_JOINT_DEG, joint_turn, nearer_goal
from humanoidgen.planning.recovery import GoalFound, Recovery


class NearPosture(Recovery):
    stage = "goal"
    trigger = "after"
    answers = f"a goal for a carried object that turns a joint more than {FAR_JOINT_DEG:.0f} deg"
    tries = "the same constraints from seeds about the arm's posture; the first goal turning no joint that far"
    event = "the <side> arm takes a goal near its posture: the first found turned a joint <n> deg, swinging <object>"

    def applies(self, ctx: PlanningContext, request: GoalFound, failure: Exception | None) -> bool:
        return request.result.success and ctx.carries(request.side)

    def attempt(self, ctx: PlanningContext, request: GoalFound, failure: Exception | None) -> None:
        side, held = request.side, ctx.hands[request.side].held
        near = nearer_goal(ctx.solver, side, request.constraints, request.q_now, request.result, ctx.seed)
        if near is not None:
            ctx.events.append(f"the {side} arm takes a goal near its posture: the first found turned a joint "
                              f"{np.degrees(joint_turn(request.q_now, request.result.q)):.0f} deg, swinging "
                              f"{held.type_name} {held.obj_id} through a wide arc")
            request.result = near
