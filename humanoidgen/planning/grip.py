"""Closing a hand on an object: the fingers close, the scene settles, and it is a hold only where the thumb
presses against a finger on that object; otherwise the error says which fingers touch and what to change."""

from __future__ import annotations

from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
import numpy as np

from humanoidgen.planning.hand_ops import finger_contacts, is_held, is_part
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
    ctx.hands[side].grip_anchor = grip_anchor(ctx, side, obj) if is_part(obj) else None
    ctx.events.append(f"{'grasped' if verb == 'grasp' else 'pinched'} {obj_type} {obj_id} with the {side} hand")


def grip_anchor(ctx: PlanningContext, side: Side, obj) -> tuple[str, dict[int, tuple[np.ndarray, np.ndarray]]]:
    """The hand's end-effector pose (point, rotation), as it closed on an articulated part, in the frame of each
    of the object's bodies (its moving parts among them): where a hand that slid along the part since is taken back to as it
    moves the part on (`part_grip.part_path_poses`)."""
    m = ctx.env.model
    root = m.body(obj.body).id
    ctx.kin.sync(ctx.env.data.qpos)
    p, R = ctx.kin.ee_pose(side)
    d = ctx.kin.data
    rel = {b: (d.xmat[b].reshape(3, 3).T @ (p - d.xpos[b]), d.xmat[b].reshape(3, 3).T @ R)
           for b in range(m.nbody) if int(m.body_rootid[b]) == root}
    return obj.body, rel
