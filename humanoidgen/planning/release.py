"""The release stage (`open_hand`): each hand's release request goes through the pipeline first (a hand-over
is made safe, an articulated part is let go by trial); the usual way then loosens into the grip's "pre"
posture (a small finger motion that does not sweep the object), backs out along the way in, and only then
opens fully, clear of what it let go of. Where each released object came to rest is an event."""

from __future__ import annotations

import numpy as np

from humanoidgen.planning import arm_moves, finger_room
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.hand_ops import body_speed, is_part, resting_on
from humanoidgen.planning.recovery import ReleaseRequest
from humanoidgen.sim.layout import Side


def open_hands(ctx: PlanningContext, sides: tuple[Side, ...]) -> None:
    for s in sides:  # a hand-over: the other hand is to keep the object
        held = ctx.hands[s].held
        if held is not None and not is_part(held):
            ctx.before("release", ReleaseRequest(s, held, sides))
    released = [(s, ctx.hands[s].held) for s in sides if ctx.hands[s].held is not None]
    for s in sides:
        held = ctx.hands[s].held
        if is_part(held):
            falls = falls_when_let_go(ctx, s, held)
            ctx.before("release", ReleaseRequest(s, held, sides))
            if falls:
                ctx.events.append(falls)
            continue
        ctx.move_fingers((s,), f"pre_{ctx.hands[s].grip}" if held is not None else "open")
        ctx.hands[s].held = None
        ctx.kin.detach(s)
    rigid = [(s, o) for s, o in released if not is_part(o)]
    if rigid:
        ctx.settle(0.3)
        backed = []
        for side, obj in rigid:
            axis = ctx.hands[side].last_approach
            arm_moves.retreat(ctx, side)
            backed.append((side, obj, None if axis is None else -np.asarray(axis, float)))
        finger_room.open_clear_of(ctx, backed)
    if released:
        ctx.settle(0.2)
        for side, obj in released:
            if is_part(obj):
                ctx.events.append(f"released {obj.type_name} {obj.obj_id} from the {side} hand")
                continue
            below = resting_on(ctx.env.scene, ctx.env.model, ctx.env.data, obj)
            moving = body_speed(ctx.env.model, ctx.env.data, obj.body) > 0.02
            where = " and ".join(below) if below else "nothing"
            state = "is still moving" if moving else f"stayed on {where}"
            ctx.events.append(f"released {obj.type_name} {obj.obj_id} and it {state}")


def falls_when_let_go(ctx: PlanningContext, side: Side, part) -> str | None:
    """Why a part let go here will not stay (its joint's friction does not hold its weight: a light lid let go
    low falls shut), in the family's terms, or None where it stays."""
    from humanoidgen.objects import library
    from humanoidgen.planning.part_joint import follow_openness, part_stays

    f = ctx.hands[side].part_moved
    if f is None or ctx.env.scene.object(*f.obj).body != part.body:
        return None
    m = ctx.env.model
    if part_stays(ctx.env, f.joint, float(ctx.env.data.qpos[m.jnt_qposadr[m.joint(f.joint).id]])):
        return None
    try:
        holds = library.model(part.type_name, part.type_id).params.get("holds_from")
    except (KeyError, ValueError, AttributeError):
        holds = None
    where = f" (it stays where it is left only from openness {holds:g} up)" if holds is not None else ""
    return (f"{part.type_name} {part.obj_id} was let go at openness {follow_openness(ctx.env, f):.2f}, where it does "
            f"not stay{where}: it falls by its own weight")
