"""Closing a hand on an object: the fingers close, the scene settles, and it is a hold only where the thumb
presses against a finger on that object; otherwise the error says which fingers touch and what to change."""

from __future__ import annotations

from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.hand_ops import finger_contacts, is_held
from humanoidgen.sim.layout import Side


def close_on(ctx: PlanningContext, side: Side, obj_type: str, obj_id: int, posture: str, verb: str) -> None:
    obj = ctx.env.scene.object(obj_type, obj_id)
    ctx.move_fingers((side,), posture, seconds=0.6)
    ctx.settle(0.3)
    touched = finger_contacts(ctx.env.model, ctx.env.data, side, obj.body)
    if not is_held(touched):
        if not touched:
            tip = (f"the hand is not at {obj_type} {obj_id}: check that the move before reached its grip pose, "
                   f"or that {obj_type} {obj_id} did not move away")
        elif "thumb" not in touched:
            other = "pinch" if verb == "grasp" else "grasp"
            tip = (f"the thumb does not reach it: the grip point is off for this part's shape; try "
                   f"action='{other}', another point= of its annotations, or finger_offset= (e.g. 0.02)")
        else:
            tip = "only the thumb touches it: the fingers close past it; try finger_offset=-0.01 or another point="
        raise PlanningError(
            f"hand_{verb}",
            f"the {side} hand closed but does not hold {obj_type} {obj_id} "
            f"(touching: {', '.join(sorted(touched)) or 'nothing'}; a hold needs the thumb against a finger): {tip}",
        )
    ctx.hands[side].held = obj
    ctx.hands[side].grip = verb
    ctx.events.append(f"{'grasped' if verb == 'grasp' else 'pinched'} {obj_type} {obj_id} with the {side} hand")
