"""A hand that let go of an object another hand holds (a hand-over) gets clear of it even where it cannot back out
the way it came in: a hand that takes it in a pinch pulls it out of the loosened fingers instead.

`arm_moves.retreat` backs the hand out along its approach. After a mid-air hand-over that way can leave the arm's
reach: measured on handover_and_storage_cooperation (alt_folder seed 1), the right hand had come down onto the
block, carried it up to the hand-over point and, letting go, could not go back up (the straight motion left its
reach at 27% of the way); it could not open either (its fingers would strike the block). It stayed where it was,
its middle finger and palm still on the block, so its next move (home) dragged the block in the left hand's pinch
from between thumb and index to thumb and middle, and the block fell on the carry that followed. Backing the
giver away sideways or down dragged the block too. So the taker, which holds it, pulls it out along the way it
came in (as a person takes a thing handed over), and then the giver's fingers open clear of it."""

from __future__ import annotations

import numpy as np

from humanoidgen.planning import arm_moves
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.motion import MotionError, plan_arm_motion, time_dense_path
from humanoidgen.sim.layout import OTHER_SIDE, Side
from humanoidgen.sim.scene import SceneObject

MOVED_M = 0.005  # a retreat that moved the hand less than this did not happen (its way was blocked)
PULL_DISTANCES = (0.04, 0.025)  # m, the taker's pull out along its way in, tried in turn
PULL_SPEED = 0.1  # m/s: slow, the object is in a pinch


def retreat_from(ctx: PlanningContext, side: Side, obj: SceneObject | None) -> bool:
    """Back `side`'s hand out along its approach (`arm_moves.retreat`); where that way is blocked and the other
    hand pinches `obj` (a hand-over), the other hand pulls `obj` away instead. True when the hands came apart."""
    before = ctx.env.hand_pose(side)[0].copy()
    arm_moves.retreat(ctx, side)
    if float(np.linalg.norm(ctx.env.hand_pose(side)[0] - before)) >= MOVED_M:
        return True
    taker = OTHER_SIDE[side]
    axis = ctx.hands[taker].last_approach
    # Only a pinch: fingertips on one end of the object, which a giver's touch drags out of place. A whole-hand
    # grasp is not dragged so, and pulled out of a giver's hand wrapped round it (bottle_handover: the giver's
    # thumb three quarters round the bottle) it lost its hold in the release trial.
    if obj is None or ctx.hands[taker].held is not obj or axis is None or ctx.hands[taker].grip != "pinch":
        return False
    for dist in PULL_DISTANCES:
        if _pull(ctx, taker, -dist * np.asarray(axis, float)):
            ctx.events.append(f"the {side} hand could not back out the way it came in: the {taker} hand pulled "
                              f"{obj.type_name} {obj.obj_id} {dist * 100:.1f} cm out of its fingers instead")
            return True
    return False


def _pull(ctx: PlanningContext, side: Side, offset: np.ndarray) -> bool:
    """Move `side`'s hand, with what it holds, straight by `offset`; False where that cannot be planned. The
    held object starts touching the other hand's loosened fingers and moves away from them: the other hand's
    object is no obstacle to the plan."""
    kin = ctx.kin
    ignored = set(ctx.collisions.ignored_bodies)
    held = ctx.hands[side].held
    if held is not None:
        ctx.collisions.ignored_bodies.add(ctx.env.model.body(held.body).id)
    kin.sync(ctx.env.data.qpos)
    p, R = kin.ee_pose(side)
    arm = kin.arms[side]
    try:
        path = plan_arm_motion(kin, ctx.collisions, side, np.clip(kin.arm_q(side), arm.lo, arm.hi),
                               (p + offset, R), allow_sampling=False)
    except MotionError:
        return False
    finally:
        ctx.collisions.ignored_bodies = ignored
        kin.sync(ctx.env.data.qpos)
    ctx.run_arm_samples({side: time_dense_path(path.waypoints, 1.0 / ctx.env.control_hz, v_max=PULL_SPEED)})
    return True
