"""Rise first: an empty hand boxed in where it is (just let go beside an object) has no way to its goal from
there; it rises straight up RISE_FIRST_M and plans the move from that point."""

from __future__ import annotations

import numpy as np

from humanoidgen.planning.arm_moves import plan_leg
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.motion import JointPath, MotionError, plan_arm_motion
from humanoidgen.planning.recovery import LegRequest, Recovery

RISE_FIRST_M = 0.06  # an empty hand boxed in beside an object rises this much before planning its way out


class RiseFirst(Recovery):
    stage = "transit"
    trigger = "failure"
    answers = "no way from where an empty hand is to its goal"
    tries = f"rise {RISE_FIRST_M * 100:.0f} cm straight up, then plan the move from there"
    event = "the <side> hand rose 6 cm first: the way from where it was is blocked"

    def applies(self, ctx: PlanningContext, request: LegRequest, failure: Exception | None) -> bool:
        return not request.path_constraints and ctx.hands[request.side].held is None

    def attempt(self, ctx: PlanningContext, request: LegRequest, failure: Exception | None) -> list[JointPath]:
        side, q0 = request.side, request.q0
        ctx.kin.set_arm(side, q0)
        ctx.kin.forward()
        p_now, R_now = ctx.kin.ee_pose(side)
        try:
            rise = plan_arm_motion(ctx.kin, ctx.collisions, side, q0,
                                   (p_now + np.array([0.0, 0.0, RISE_FIRST_M]), R_now), allow_sampling=False)
            legs = [rise, plan_leg(ctx, side, rise.waypoints[-1], request.target, request.path_constraints)]
        except MotionError:
            raise failure from None
        ctx.events.append(f"the {side} hand rose {RISE_FIRST_M * 100:.0f} cm first: the way from where it was "
                          "is blocked")
        return legs
