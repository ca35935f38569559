"""Ajar before a grip: no goal for a grasp or pinch on a hinged part that lies shut and flush (a laptop's
screen on its base leaves no room for fingers on its inner face). The part is lifted ajar with a fingertip
(`part_ajar.lift_ajar`), then the grip is generated again where the part is now and solved."""

from __future__ import annotations

from humanoidgen.planning import goal_entry, part_ajar
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.recovery import GoalRequest, Recovery
from humanoidgen.sim.scene import SceneObject


def shut_grip_part(ctx: PlanningContext, gen, side) -> SceneObject | None:
    """The object of a generated grasp/pinch on a part that lies shut and could be lifted ajar, else None."""
    request = getattr(gen, "request", None)
    if request is None or request[2] not in ("grasp", "pinch") or gen.grip_part is None:
        return None
    obj = ctx.env.scene.object(*gen.grip_part.obj)
    return obj if ctx.hands[side].held is None and part_ajar.lies_shut(ctx.env, obj) else None


class AjarBeforeGrip(Recovery):
    stage = "goal"
    trigger = "failure"
    answers = "no goal for a grip on a hinged part that lies shut and flush"
    tries = "lift the part ajar with the fingertip, then generate and solve the grip again"
    event = "lifted <part> ajar ..., to grip it"

    def applies(self, ctx: PlanningContext, request: GoalRequest, failure: Exception | None) -> bool:
        return shut_grip_part(ctx, request.gen, request.side) is not None

    def attempt(self, ctx: PlanningContext, request: GoalRequest, failure: Exception | None):
        part_ajar.lift_ajar(ctx, request.side, shut_grip_part(ctx, request.gen, request.side))
        constraints = list(goal_entry.generate(ctx, request.gen.request).constraints)
        result, pose = goal_entry.solve_grip_or_goal(ctx, constraints, request.side)
        return result, pose, constraints
