"""Pinch instead: a whole-hand grasp (or another grip) whose goal cannot be found falls back to the grip's last
resort that constraint generation attached to it (a grasp's: the object's pinch), with the hand first set to
pre_pinch; where that cannot be solved either, the first grip's failure stands."""

from __future__ import annotations

from humanoidgen.planning import finger_room, goal_search
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.recovery import GoalRequest, Recovery


class PinchInstead(Recovery):
    stage = "goal"
    trigger = "failure"
    answers = "no goal for a grip that has a last resort (a grasp: its pinch), with the hand empty"
    tries = "set the hand to pre_pinch and solve the last resort's constraints"
    event = "a whole-hand grasp of <object> does not fit (...): the <side> hand pinches it instead"

    def applies(self, ctx: PlanningContext, request: GoalRequest, failure: Exception | None) -> bool:
        return getattr(request.gen, "fallback", None) is not None and ctx.hands[request.side].held is None

    def attempt(self, ctx: PlanningContext, request: GoalRequest, failure: Exception | None):
        side, gen = request.side, request.gen
        fallback = gen.fallback
        for c in fallback.constraints:
            c.meta = fallback  # the move needs its approach axis and closing posture
        finger_room.posture_with_room(ctx, (side,), "pre_pinch")  # the goal is solved with the fingers as they come in
        try:
            result, pose = goal_search.solve_goal(ctx, list(fallback.constraints), side)
        except PlanningError:
            raise failure from None
        reason = failure.reason
        if "in contact: " in reason:  # the deepest contact says why, e.g. "R_thumb_distal and table (33.2 mm deep)"
            reason = reason.split("in contact: ", 1)[1].split(")", 1)[0] + ")"
        obj = f"{gen.request[0]} {gen.request[1]}" if gen.request else "the object"
        ctx.events.append(f"a whole-hand grasp of {obj} does not fit ({reason[:120]}): the {side} hand pinches it "
                          "instead (set to pre_pinch; hand_grasp closes as a pinch)")
        return result, pose, list(fallback.constraints)
