"""What a goal may touch, and what the goal search says when there is no goal: the ignore list for a grip's goal,
a push that would have to pull refused first, the pushes that would drive a part the way asked (as advice), and
the failure message (which constraint missed by how much, which bodies collide, what to change). Read-only
helpers of `goal_search`; they never step the simulation."""

from __future__ import annotations

import numpy as np

from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.feedback import body_label, contact_advice, push_advice, range_advice
from humanoidgen.planning.goal_solver import GoalResult
from humanoidgen.planning.part_joint import follow_articulation, follow_openness, point_motion
from humanoidgen.planning.hand_ops import is_part
from humanoidgen.sim.layout import OPERABLE_RANGE, Side

PUSH_MIN_COS = 0.3  # a fingertip drives a part only where the part gives way within ~70 deg of the push


def use_ignores(ctx: PlanningContext, side: Side, gen, ignored_before: set[int]) -> None:
    """What a goal for `gen` may touch: the body it operates on, a held part, what rests in a carried object."""
    ctx.collisions.ignored_bodies = ignored_before | ctx.touched_by(gen)
    held = ctx.hands[side].held
    if is_part(held):
        ctx.collisions.ignored_bodies.add(ctx.env.model.body(held.body).id)
    ctx.attach_held(side)
    ctx.ignore_contents(side)


def push_op(ctx: PlanningContext, gen):
    """The push/flip/press annotation a part-riding push was made from (by its point), or None."""
    f = gen.follow
    ann = ctx.env.scene.object(*f.obj).annotations
    return next((o for o in ann.operations if o.operation in ("push", "flip", "press") and o.point == f.part_point),
                None)

def push_cos(ctx: PlanningContext, gen) -> float:
    """How well the fingertip drives the part toward the asked openness: the cosine between the way the
    touched point moves and the direction the fingertip presses in, both now. A push or press presses along
    its approach axis; a flip gets under the part and lifts it, so it only ever opens (cosine 1 or -1)."""
    from humanoidgen.objects.queries import get_axis_in_env

    f = gen.follow
    obj = ctx.env.scene.object(*f.obj)
    now = follow_openness(ctx.env, f)
    wanted = follow_articulation(ctx.env, f).openness_of(f.q_target)
    step = float(np.clip(wanted - now, -0.05, 0.05))
    op = push_op(ctx, gen)
    if abs(step) < 1e-3 or op is None:
        return 1.0
    if op.operation == "flip":
        return 1.0 if step > 0 else -1.0
    v = point_motion(ctx.env, f, step)
    axis = get_axis_in_env(ctx.env, op.approach_axis, obj_type=obj.type_name, obj_id=obj.obj_id)
    return 1.0 if not v.any() else float(v @ axis)

def pushes_toward(ctx: PlanningContext, side: Side, obj, wanted: float, skip_point: str | None = None) -> list[str]:
    """The annotated pushes (target1, target2) that drive `obj` toward openness `wanted`, as suggestions;
    each marked when its push point is out of the hand's reach now."""
    from humanoidgen.planning import skills

    out = []
    for action in ("target1", "target2"):
        try:
            other = skills.generate(ctx.env, ctx.holding, obj.type_name, obj.obj_id, action, side, wanted, targets=ctx.targets)
            start = skills.generate(ctx.env, ctx.holding, obj.type_name, obj.obj_id, action, side, None, targets=ctx.targets)
        except (ValueError, KeyError):
            continue
        if other.follow is None or other.follow.part_point == skip_point or push_cos(ctx, other) < PUSH_MIN_COS:
            continue
        use_ignores(ctx, side, start, set(ctx.collisions.ignored_bodies))
        reach = ctx.solver.solve(side, list(start.constraints), ctx.kin.arm_q(side), ctx.nominal[side])
        out.append(f"action='{action}' (at {other.follow.part_point}"
                   + ("" if reach.success else f", out of the {side} hand's reach now") + ")")
    return out

def check_push_direction(ctx: PlanningContext, side: Side, gen) -> None:
    """Refuse a fingertip push that cannot move the part the way asked (it would have to pull)."""
    if not any(getattr(c, "type", "") == "angle" for c in gen.constraints):
        return  # a grip, not a push
    cos = push_cos(ctx, gen)
    if cos >= PUSH_MIN_COS:
        return
    f = gen.follow
    obj = ctx.env.scene.object(*f.obj)
    wanted = follow_articulation(ctx.env, f).openness_of(f.q_target)
    ignored = set(ctx.collisions.ignored_bodies)
    try:
        usable = pushes_toward(ctx, side, obj, wanted, skip_point=f.part_point)
    finally:
        ctx.collisions.ignored_bodies = ignored
        ctx.kin.sync(ctx.env.data.qpos)
    op = push_op(ctx, gen)
    why = (f"a flip gets under {obj.type_name} {obj.obj_id} at {f.part_point} and lifts it: it opens it, it "
           f"cannot bring it down to openness {wanted:g}" if op is not None and op.operation == "flip" else
           f"a fingertip at {obj.type_name} {obj.obj_id} {f.part_point} cannot move it to openness {wanted:g} "
           f"(it is at {follow_openness(ctx.env, f):.2f} now): "
           f"the point moves {np.degrees(np.arccos(np.clip(cos, -1, 1))):.0f} deg away from the push direction, "
           f"so the finger would have to pull")
    raise PlanningError("generate_end_effector_pose",
                        why + "; " + push_advice(f"{obj.type_name} {obj.obj_id}", wanted, usable, side))

# -- failure message ---------------------------------------------------------------------------------
def exact_axis_advice(constraints: list) -> str:
    """Said where the plan holds a hand axis exactly (a hard 'parallel'): an 'angle' within some degrees gives the
    arm room (the hand axis named as the plan took it from get_axis_in_env, where it is one of the hand's)."""
    exact = [c for c in constraints if getattr(c, "type", "") == "parallel" and not c.soft]
    if not exact:
        return ""
    from humanoidgen.objects.queries import get_axis_in_env
    from humanoidgen.objects.hands import HAND_AXIS_NAMES

    c = exact[0]
    env = getattr(c, "env", None)
    names = [n for n in HAND_AXIS_NAMES if env is not None and f"_{c.side}_" in f"_{n}_"
             and np.allclose(get_axis_in_env(env, n), c.hand_axis, atol=1e-6)]  # several hand axes coincide
    name = " / ".join(names) or "the hand axis"
    return (f"; or hold {name} within some degrees of its target axis instead of exactly along it: "
            "Constraint(..., \"angle\", ..., lower=0.0, upper=math.radians(20)) in place of \"parallel\"")


def goal_failure(ctx: PlanningContext, side: Side, constraints: list, gen, result: GoalResult) -> str:
    msg = result.message()
    advice = ""
    if result.contacts:
        other = ctx.hands["left" if side == "right" else "right"].held
        advice = contact_advice(ctx.env, side, result.contacts, getattr(gen, "approach_object", None),
                                held_by_other=None if other is None else f"{other.type_name} {other.obj_id}")
        bodies = ", ".join(dict.fromkeys(body_label(ctx.env, b) for _, b, _ in result.contacts))
        msg += f" [in the way: {bodies}]"
    else:
        point = next((c.object_key_point for c in constraints
                      if getattr(c, "type", "") == "point2point" and not c.soft), None)
        if point is not None and any("mm from its target" in v for v in result.violations):
            other = "left" if side == "right" else "right"
            in_other = OPERABLE_RANGE[other].contains(point, tol=0.01)
            advice = range_advice(side, point) or (
                f"the point is just out of the {side} arm's reach in this hand orientation: "
                + (f"try the {other} hand, " if in_other else "")
                + "another grip (point=...), or move the object nearer the robot first") + exact_axis_advice(constraints)
    return msg + (f". Suggestion: {advice}" if advice else "")
