"""After a move ran: did each hand get where it was sent, did a carried object stay in the hand, and if not,
what the plan's author is told. Pure reading of the simulation and the hands' state; never steps it."""

from __future__ import annotations

import numpy as np

from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.hand_ops import finger_contacts, hand_touches
from humanoidgen.planning.poses import Pose
from humanoidgen.sim.layout import Side
from humanoidgen.sim.scene import SceneObject

SLIP_LIMIT = {"pinch": 0.01, "grasp": 0.025}  # a held object moving more than this in the hand was lost (m)


def slipped(ctx: PlanningContext, side: Side, obj: SceneObject, slip: float) -> str:
    """Why a carried object was lost, and what the plan could do instead (the message is the LLM's feedback)."""
    grip = ctx.hands[side].grip or "pinch"
    touching = finger_contacts(ctx.env.model, ctx.env.data, side, obj.body)
    mass = float(ctx.env.model.body_subtreemass[ctx.env.model.body(obj.body).id])
    now = f"touching it now: {', '.join(sorted(touching))}" if touching else "no longer touching it"
    if grip == "pinch":
        advice = ("two fingertips did not hold it through the move: try action='grasp' (the whole hand), "
                  "a point= nearer its middle, or shorter moves")
    else:
        advice = "the grasp did not hold it through the move: try a point= nearer its middle, or shorter moves"
    return (f"{obj.type_name} {obj.obj_id} slipped {slip * 1000:.0f} mm in the {side} hand ({grip}, "
            f"{mass:.2f} kg; {now}): {advice}")


def stopped_short(ctx: PlanningContext, side: Side, err: float) -> str:
    """Why the hand did not get there, for the plan's author: what it is pressing against, and what to try."""
    touches = hand_touches(ctx.env.scene, ctx.env.model, ctx.env.data, side)
    held = ctx.hands[side].held
    if held is not None:
        touches.pop(f"{held.type_name} {held.obj_id}", None)
    msg = f"the {side} hand stopped {err * 1000:.0f} mm from its target"
    if touches:
        listed = ", ".join(f"{what} ({', '.join(sorted(parts))})" for what, parts in touches.items())
        return (msg + f", pressed against {listed}: the simulation does not let it through (ignore_collision only "
                "stops the planner avoiding it). Aim short of that surface, move it out of the way first, or "
                "push a part along the way it gives (generate_constraints with openness=)")
    return msg + (": the arm could not keep to the planned motion (a heavy load or a joint at its limit): "
                  "try a shorter move or a target nearer the robot")


def turned_approach(ctx: PlanningContext, side: Side, target: Pose) -> np.ndarray | None:
    """The last approach axis turned as the hand turns on this move: the way out of a grip stays the way in
    relative to the hand (a block turned on its side for a hand-over is let go sideways, not up)."""
    axis = ctx.hands[side].last_approach
    if axis is None:
        return None
    return target.R @ ctx.current_pose(side).R.T @ axis
