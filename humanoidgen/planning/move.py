"""The move stage: plan each hand's move (`arm_moves.plan_side`), run it (both arms kept apart), then check
it: a part the hand rode with got where it was asked, each hand got where it was sent, a carried object stayed
in the hand. What is left to do after the move (a part to take again on its way) is the pipeline's
(`ctx.after("move", ...)`)."""

from __future__ import annotations

import numpy as np

from humanoidgen.planning import arm_moves, execute, onto_point, press_force, push_move
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.execute import SLIP_LIMIT
from humanoidgen.planning.hand_ops import finger_contacts, is_held
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.recovery import AfterMove
from humanoidgen.sim.layout import Side

CALL = "move_to_pose_with_screw"


def move_hands(ctx: PlanningContext, sides: tuple[Side, ...], poses: list, path_constraints: list | None,
               verbs) -> None:
    if len(sides) == 1 and isinstance(poses[0], Pose) and poses[0].push is not None:
        return push_move.execute(ctx, sides[0], poses[0])  # a task's push on a part (target1/target2)
    samples: dict[Side, np.ndarray] = {}
    targets: dict[Side, Pose] = {}
    for side, target in zip(sides, poses):
        if not isinstance(target, Pose):
            raise PlanningError(CALL, f"pose must be a Pose (from generate_end_effector_pose), got {type(target).__name__}")
        hand = ctx.hands[side]
        if (operation := onto_point.operation_of(ctx, target)) is not None:
            # A ride with a part asked from afar: onto its point first (onto_point), then the ride from there.
            move_hands(ctx, (side,), [onto_point.pose_onto(ctx, side, target, operation)], None, verbs)
            ctx.events.append(f"the {side} fingertip came onto {' '.join(map(str, target.follow.obj))}'s "
                              f"{target.follow.part_point} first ({operation} without openness), to ride from there")
        mine = [c for c in (path_constraints or []) if c.side == side]
        samples[side] = arm_moves.plan_side(ctx, side, target, mine)
        target = hand.take("goal_moved", target)
        used = hand.take("approach_used")  # another way in than the operation's axis
        hand.last_approach = (used if used is not None else target.approach_axis
                              if target.approach_axis is not None else execute.turned_approach(ctx, side, target))
        if target.follow is not None:
            hand.part_moved = target.follow  # how the hand is on the part it moves: how to let go
        hand.closing = target.posture
        targets[side] = target
    if len(sides) == 2:
        samples = arm_moves.coordinate_arms(ctx, samples)
    carried = {s: ctx.relative_to_hand(s, ctx.hands[s].held) for s in sides if ctx.carries(s)}
    watch = press_force.Watch.of(ctx, targets)  # presses to a force stop where the finger pushes that hard
    part_start = {s: arm_moves.part_openness(ctx, t) for s, t in targets.items()
                  if t.follow is not None and t.follow.force is None}
    if watch is None:
        ctx.run_arm_samples(samples)
    else:
        watch.run(ctx, samples)
    ctx.settle(0.2)
    if watch is not None:
        watch.report(ctx)
    for side, start in part_start.items():
        arm_moves.check_part_followed(ctx, side, targets[side], start)
    for side, target in targets.items():
        ctx.after("move", AfterMove(side, target, verbs))
    _check_arrived(ctx, targets)
    _check_carried(ctx, carried)


def _check_arrived(ctx: PlanningContext, targets: dict[Side, Pose]) -> None:
    for side, target in targets.items():
        err = np.linalg.norm(ctx.current_pose(side).p - target.p)
        if err <= 0.02 or target.follow is not None:
            continue
        touching = target.approach_object is not None and finger_contacts(
            ctx.env.model, ctx.env.data, side, target.approach_object)
        if touching and err <= 0.05:  # the hand arrived against what it came to operate on
            ctx.log[-1].message = f"stopped {err * 1000:.0f} mm short, touching {target.approach_object}"
            continue
        raise PlanningError(CALL, execute.stopped_short(ctx, side, err))


def _check_carried(ctx: PlanningContext, carried: dict[Side, np.ndarray]) -> None:
    for side, before in carried.items():
        hand = ctx.hands[side]
        slip = np.linalg.norm(ctx.relative_to_hand(side, hand.held) - before)
        # A wrapped body may settle in the fist when turned (pouring) and still be held; a pinched one that
        # shifted as far is lost unless thumb and a finger still hold it (a block pinched by its end, carried up
        # over a drawer's wall, shifted 12 mm and was let go into the drawer all the same).
        obj = hand.held
        if slip <= SLIP_LIMIT[hand.grip or "pinch"] or (slip <= SLIP_LIMIT["grasp"] and is_held(
                finger_contacts(ctx.env.model, ctx.env.data, side, obj.body))):
            if slip > SLIP_LIMIT["pinch"]:
                ctx.events.append(f"{obj.type_name} {obj.obj_id} shifted {slip * 1000:.0f} mm in the {side} hand")
        else:
            hand.held = None
            raise PlanningError(CALL, execute.slipped(ctx, side, obj, slip))
