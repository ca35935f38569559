"""Onto the point first: a fingertip push, flip or press asked straight to an openness (or a force) from a hand
that is not on the part yet.

`generate_constraints(obj, action="press", openness=1)` (or `force=`, or a push/flip with `openness=`) describes a
ride with the part from where the fingertip touches it. Asked from afar, as a new author writes it ("press the
lever all the way down" as the first press; "the fingertip on the lid at its openness now" as openness=<now>),
the move had nothing to ride from: the arm tracked the part's path from wherever the hand was, stopped far from
the point, and the part did not move. So the move first comes onto the point as the same action without
`openness` puts it (the fingertip on the point as the part is now, in along the operation's approach axis), and
rides from there. Only for a bare fingertip (nothing held): a grip that moves a part came onto it with the grip.
"""

from __future__ import annotations

from humanoidgen.planning import goal_entry
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.goal_search import on_push_point
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.target_actions import PUSH_OPERATIONS
from humanoidgen.sim.layout import Side


def operation_of(ctx: PlanningContext, target: Pose) -> str | None:
    """The push-like operation (push, flip, press) whose point a bare fingertip's ride starts from, where the
    fingertip is not on that point yet; else None."""
    f = target.follow
    if f is None or f.part_point is None or target.push is not None:
        return None
    side = target.side
    if side is None or ctx.hands[side].held is not None:
        return None
    obj = ctx.env.scene.object(*f.obj)
    ops = [o for o in (obj.annotations.operations if obj.annotations else [])
           if o.operation in PUSH_OPERATIONS and o.point == f.part_point]
    if not ops or on_push_point(ctx, side, f):
        return None
    return ops[0].operation


def pose_onto(ctx: PlanningContext, side: Side, target: Pose, operation: str) -> Pose:
    """The goal with the fingertip on the ride's point as the part is now (the same action, no openness)."""
    name, obj_id = target.follow.obj
    gen = goal_entry.generate(ctx, (name, obj_id, operation, side, None, None, None, None, None, 0.0, None))
    _, pose, _ = goal_entry.goal(ctx, side, list(gen.constraints))
    return pose
