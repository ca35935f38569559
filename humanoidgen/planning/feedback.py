"""What a failure message tells the plan's author (a person or an LLM) to change.

A planner failure says which constraint is violated by how much and which bodies collide (the solver's and the
motion planner's own words); these helpers add the concrete next step: the other hand when the target lies in
its operable range, a move of the object when it lies in neither, `ignore_collision` when the contact is with
the object operated on, moving the other arm, approaching from above, another annotated grip.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.sim.layout import HAND_PREFIX, OPERABLE_RANGE, OTHER_SIDE, SIDES, TORSO_BODIES, WRIST_BODY, Side


def _fmt_range(side: Side) -> str:
    r = OPERABLE_RANGE[side]
    return f"x in [{r.x[0]:.2f}, {r.x[1]:.2f}], y in [{r.y[0]:.2f}, {r.y[1]:.2f}]"


def body_label(env, body: int) -> str:
    """A body as the plan's author knows it: "cube 1", "the table", "the left arm", "the torso"."""
    m = env.model
    name = m.body(body).name
    root = int(m.body_rootid[body])
    for o in env.scene.objects:
        if m.body(o.body).id in (body, root):
            return f"{o.type_name} {o.obj_id}"
    if name == "table":
        return "the table"
    for side in SIDES:
        if name.startswith(f"{side}_") or name.startswith(HAND_PREFIX[side] + "_"):
            return f"the {side} {'hand' if name.startswith(HAND_PREFIX[side] + '_') or name == WRIST_BODY[side] else 'arm'}"
    return "the torso" if name in TORSO_BODIES else name


def range_advice(side: Side, point: np.ndarray) -> str:
    """Where the target stands against the hands' operable ranges, and what to do about it ('' if nothing)."""
    mine, other = OPERABLE_RANGE[side], OPERABLE_RANGE[OTHER_SIDE[side]]
    at = f"({point[0]:.2f}, {point[1]:.2f})"
    if mine.contains(point, tol=0.01):
        if point[0] < -0.40:
            return (f"the target {at} is near the far end of the {side} hand's reach: move the object nearer the "
                    f"robot (x > -0.38) first, or grip it from its near side (another `point=`)")
        return ""
    if other.contains(point, tol=0.01):
        return (f"the target {at} is out of the {side} hand's range ({_fmt_range(side)}) but in the "
                f"{OTHER_SIDE[side]} hand's: use the {OTHER_SIDE[side]} hand, or move the object into the {side} hand's range first")
    return (f"the target {at} is out of both hands' ranges (left {_fmt_range('left')}; right {_fmt_range('right')}): "
            f"move the object into range first (push it, or hand it over)")


def contact_advice(env, side: Side, contacts: list[tuple[int, int, float]], approach_object: str | None,
                   held_by_other: str | None = None) -> str:
    """What to do about the contacts a goal needs (moving body, obstacle body, distance). `held_by_other`: what
    the other hand holds ("cube 0"), if anything."""
    m = env.model
    tips = []
    other_obj = None
    if approach_object is not None:
        other_obj = next((f"{o.type_name} {o.obj_id}" for o in env.scene.objects if o.body == approach_object), None)
    for _, obstacle, _ in contacts:
        what = body_label(env, obstacle)
        if what.startswith(f"the {OTHER_SIDE[side]}") and held_by_other is not None and held_by_other == other_obj:
            tip = (f"the {OTHER_SIDE[side]} hand holds {held_by_other} where the {side} hand's fingers would go: present "
                   f"it with more of it free (the {OTHER_SIDE[side]} hand holding it nearer one end, e.g. "
                   f"finger_offset=, or turned), or take it from the other side (another `point=`)")
        elif what == "the table":
            tip = ("the hand cannot take this pose without touching the table: approach from above (e.g. "
                   f"Constraint 'parallel' of {side}_grasp_axis with [0, 0, -1]), grip a higher point (`point=` or "
                   "`finger_offset=`), or lift the object first")
        elif what.startswith(f"the {OTHER_SIDE[side]}"):
            tip = (f"the {OTHER_SIDE[side]} arm is in the way: move it aside first (e.g. "
                   f"move_to_pose_with_screw(planner.{OTHER_SIDE[side]}_hand_init_pose, '{OTHER_SIDE[side]}')) or use the "
                   f"{OTHER_SIDE[side]} hand")
        elif what == "the torso":
            tip = "the target is too close to the robot's body: move the object further out first"
        elif approach_object is not None and m.body(obstacle).name == approach_object:
            tip = f"the hand has to touch {what} here: planner.ignore_collision('{what.rsplit(' ', 1)[0]}', {what.rsplit(' ', 1)[1]}) if that is intended"
        else:
            name, _, num = what.rpartition(" ")
            tip = (f"{what} is in the way: move it first, grip from another side, or "
                   f"planner.ignore_collision('{name}', {num}) if touching it is intended" if num.isdigit()
                   else f"{what} is in the way")
        if tip not in tips:
            tips.append(tip)
    return "; ".join(tips)


def approach_advice(side: Side, reasons: list[str], target_p: np.ndarray, axis: np.ndarray) -> str:
    """What to change when no straight approach fits."""
    tips = []
    if any("collides" in r for r in reasons):
        down = float(axis @ np.array([0.0, 0.0, -1.0])) > 0.7
        tips.append("clear what the hand would sweep on the way in (ignore_collision for an object it may touch), "
                    + ("or come in from the side" if down else "or approach from above: a grip or pose whose "
                       "approach axis points down, e.g. a 'parallel' Constraint of the palm or fingertip with [0, 0, -1]"))
    if any("reach" in r or "out of reach" in r for r in reasons):
        tip = range_advice(side, target_p)
        tips.append(tip or f"the straight line runs out of the {side} arm's reach: a shorter move, a target nearer "
                           f"the {side} shoulder, or the {OTHER_SIDE[side]} hand")
    return "; ".join(tips)


def push_advice(obj: str, wanted: float, usable: list[str], side: Side = "right") -> str:
    """What to use instead of a push that cannot move `obj` to openness `wanted`."""
    reachable = [u for u in usable if "out of" not in u]
    explicit = (f"press it with explicit Constraints: a 'point2point' of press_point_base_{side}_hand on the part's "
                f"surface point (get_point_in_env(..., openness=o)) for o stepping toward {wanted:g}, with an 'angle' "
                f"Constraint keeping {side}_press_axis within ~35 deg of the way the surface must move")
    if reachable:
        return f"to move {obj} to openness {wanted:g}, use {' or '.join(usable)} instead"
    if usable:
        return f"{' and '.join(usable)} would push the right way; or {explicit}"
    return f"no annotated push point moves {obj} that way: {explicit}"


def motion_advice(reason: str) -> str:
    """What to change when a plain move (no approach axis) finds no collision-free way."""
    if "path constraint" in reason:
        return "loosen the path constraints (an 'angle' bound instead of 'parallel') or split the move in two"
    if "no path" in reason or "invalid" in reason:
        return ("the goal is boxed in: if the hand is meant to touch what is near it, ignore_collision for that "
                "object; else come to it in two moves (first to a pose 5 cm back from it, then in)")
    if "reach" in reason:
        return "the straight motion runs out of the arm's reach: go through a pose nearer the robot first"
    return ""
