"""Corrective moves of a part turned in the fingers (a knob by its fin), tried in the simulation before one is
made: the way that leaves the part nearest the angle asked, of those that turn it on (`arm_moves.settle_turn`)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.motion import MotionError
from humanoidgen.planning.snapshot import trial
from humanoidgen.sim.layout import Side


def best_correction(ctx: PlanningContext, side: Side, plan: Callable[[], np.ndarray], measure: Callable[[], float],
                    goal: float, sign: float) -> np.ndarray | None:
    """The arm samples of a corrective move (`plan()` plans it from the state now) that leave the part (its
    openness: `measure()`) nearest `goal`, of those that turn it on (the way `sign`). Two ways are tried, each in
    the simulation and undone: from where the hand is on the part now, and taken back to how it closed on it
    (`HandState.grip_anchor`, where there is one). None where neither turns it on: the corrections stop there.

    The hand is ahead of a knob by the fingers' give: a short correction taking that back turned the knob back
    (81 deg of 108 asked, to 57); from where the hand is, the arm's way near its joint limits turned the hand
    back (92 deg of 120 asked, to 76, then 0) or gained a degree where taking the grip back gained 25."""
    hand = ctx.hands[side]
    before = measure()
    attached = dict(ctx.kin.attached)  # undoing a trial detaches what the planner's model carries: kept here
    best, miss = None, np.inf
    for anchor in (None, hand.grip_anchor) if hand.grip_anchor is not None else (None,):
        kept, hand.grip_anchor = hand.grip_anchor, anchor
        try:
            samples = plan()
            with trial(ctx):
                ctx.run_arm_samples({side: samples})
                ctx.settle(0.2)
                got = measure()
        except (MotionError, PlanningError):
            continue
        finally:
            hand.grip_anchor = kept
            ctx.kin.attached.update(attached)
        if sign * (got - before) > 0.0 and abs(got - goal) < miss:
            best, miss = samples, abs(got - goal)
    return best
