"""The goal stage's entry: constraints in, a goal pose out. Constraints the plan wrote that put a grip point on
an object are solved as that grip (`grip_intent`); the goal search (`goal_search`) does the solving; where it finds
none, the pipeline's goal recoveries answer (`ctx.recover("goal", ...)`)."""

from __future__ import annotations

from humanoidgen.planning import constraint_gen, goal_search, grip_intent, press_intent, skills
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.goal_solver import GoalResult
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.recovery import GoalRequest
from humanoidgen.sim.layout import Side


def generate(ctx: PlanningContext, request: tuple) -> constraint_gen.Generated:
    """Constraints for a verb on an object (`constraint_gen.generate`), tagged with what made them."""
    ctx.kin.sync(ctx.env.data.qpos)
    gen = skills.generate(ctx.env, ctx.holding, *request, targets=ctx.targets)
    gen.request = request  # to generate them again where the scene changes before the solve (part_ajar)
    ctx.events.extend(gen.notes)  # fallbacks and mappings are feedback for the plan's author
    for c in gen.constraints:
        c.meta = gen  # the move needs the approach axis and the part to follow
    return gen


def solve_grip_or_goal(ctx: PlanningContext, constraints: list, side: Side) -> tuple[GoalResult, Pose]:
    """A goal; for plan-written constraints that put a grip point on an object, solved as that grip
    (the object may be touched, the hand comes in along the grip's axis; see grip_intent)."""
    intent = grip_intent.infer(ctx.env, side, constraints, ctx.holding)
    if intent is None:
        press = press_intent.infer(ctx.env, side, constraints, ctx.holding)
        return goal_search.solve_goal(ctx, constraints, side) if press is None else _solve_as(ctx, side, press)
    ways = [intent.first, *intent.first.alternatives]
    mine = {id(c): c for g in ways for c in g.constraints}
    try:
        for c in intent.first.constraints:  # the goal search reads the grip from the first constraint
            c.meta = intent.first
        result, pose = goal_search.solve_goal(ctx, list(intent.first.constraints), side)
    finally:  # the plan's Constraint objects stay as the plan made them (it may use them again)
        for c in mine.values():
            c.meta = None
    if (dz := intent.raised_by(result)) > 0.002:
        ctx.events.append(f"the {intent.operation} of {intent.obj.type_name} {intent.obj.obj_id} is taken "
                          f"{dz * 1000:.0f} mm higher than asked, at its annotated {intent.operation} height: at "
                          "the height asked the fingers would go into the table")
    return result, pose


def _solve_as(ctx: PlanningContext, side: Side, gen: constraint_gen.Generated) -> tuple[GoalResult, Pose]:
    """Plan-written constraints solved as what they describe (`gen`, with its alternatives); the plan's Constraint
    objects are left as the plan made them."""
    mine = [c for g in (gen, *gen.alternatives) for c in g.constraints]
    try:
        for c in gen.constraints:  # the goal search reads what they are from the first constraint
            c.meta = gen
        return goal_search.solve_goal(ctx, list(gen.constraints), side)
    finally:
        for c in mine:
            c.meta = None


def goal(ctx: PlanningContext, side: Side, constraints: list) -> tuple[GoalResult, Pose, list]:
    """(result, goal pose, the constraints it meets): the constraints as given, or those a recovery solved."""
    try:
        result, pose = solve_grip_or_goal(ctx, list(constraints), side)
        return result, pose, constraints
    except PlanningError as failure:
        request = GoalRequest(side, list(constraints), getattr(constraints[0], "meta", None))
        return ctx.recover("goal", request, failure)
