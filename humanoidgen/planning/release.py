"""The release stage (`open_hand`): each hand's release request goes through the pipeline first (a hand-over
is made safe, an articulated part is let go by trial); the usual way then loosens into the grip's "pre"
posture (a small finger motion that does not sweep the object), backs out along the way in, and only then
opens fully, clear of what it let go of. Where each released object came to rest is an event."""

from __future__ import annotations

import numpy as np

from humanoidgen.planning import back_away, finger_room
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
            f = ctx.hands[s].part_moved
            falls = falls_when_let_go(ctx, s, held)
            ctx.before("release", ReleaseRequest(s, held, sides))
            if falls:
                ctx.events.append(falls + wait_for_fall(ctx, f))
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
            back_away.retreat_from(ctx, side, obj)
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


FALL_WAIT_S = 4.0  # at most this long for a part let go where it does not stay to come to rest
FALL_STILL = 0.05  # rad/s (m/s for a slide): the part's joint this slow for FALL_STILL_S is at rest
FALL_STILL_S = 0.2
AT_STOP = 0.02  # openness this near 0 or 1: the part rests against its stop (a lid shut on its walls)


def wait_for_fall(ctx: PlanningContext, f) -> str:
    """Let a part that falls when let go come to rest before the plan goes on, and say where it did (the event
    after "it falls by its own weight"): a lid let go low falls shut by its own weight within 1-5 s, and the plan's
    next step (a push to flip it open, solved for where the lid is) should meet it at rest, shut, as the family's
    description says it ends up, not on its way down."""
    from humanoidgen.planning.part_joint import follow_openness, stays_now

    m = ctx.env.model
    dof = m.jnt_dofadr[m.joint(f.joint).id]
    still, waited, dt = 0.0, 0.0, 1.0 / ctx.env.control_hz
    while waited < FALL_WAIT_S and still < FALL_STILL_S:
        ctx.step()
        waited += dt
        slow = abs(float(ctx.env.data.qvel[dof])) < FALL_STILL
        # Slow is not at rest where its weight still turns it on (a lid let go just under where it holds
        # starts slowly): at rest at a stop (shut, all the way open) or where its joint's friction holds it.
        at = follow_openness(ctx.env, f)
        held = slow and (not AT_STOP < at < 1.0 - AT_STOP or stays_now(ctx.env, f))
        still = still + dt if held else 0.0
    now = follow_openness(ctx.env, f)
    where = "shut" if now <= AT_STOP else f"at openness {now:.2f}"
    rest = "came to rest" if still >= FALL_STILL_S else "was still moving"
    return f"; it {rest} {where} {waited:.1f} s later"


def falls_when_let_go(ctx: PlanningContext, side: Side, part) -> str | None:
    """Why a part let go here will not stay (its joint's friction does not hold its weight: a light lid let go
    low falls shut), in the family's terms, or None where it stays."""
    from humanoidgen.objects import library
    from humanoidgen.planning.part_joint import follow_openness, stays_now

    f = ctx.hands[side].part_moved
    if f is None or ctx.env.scene.object(*f.obj).body != part.body or stays_now(ctx.env, f):
        return None
    try:
        holds = library.model(part.type_name, part.type_id).params.get("holds_from")
    except (KeyError, ValueError, AttributeError):
        holds = None
    where = f" (it stays where it is left only from openness {holds:g} up)" if holds is not None else ""
    return (f"{part.type_name} {part.obj_id} was let go at openness {follow_openness(ctx.env, f):.2f}, where it does "
            f"not stay{where}: it falls by its own weight")
