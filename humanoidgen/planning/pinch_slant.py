"""The goal search's last rung: a compact body pinched with the fingers slanted about the squeeze axis.

A pinch of a block (`constraint_gen._grip_variants`) comes in with the index edge leading, the fingers level: the
forearm then lies level behind the hand. Where the object stands close in front of the body, or beside a wall,
no level way reaches it: on the G1 the left hand's pinch of a block stood at the hand-over spot 0.3 m in front of
the pelvis had its elbow or wrist 60-90 mm deep in the torso with the fingers forward, its thumb in the open
drawer's wall with the fingers to the side, on every solver seed tried (120). Turned about the squeeze axis, the
fingers point down at a slant and the wrist rides higher, over the torso's front and the wall: the pads still
close on the same two faces. Tried only where every rung before found nothing (wrist cones included, or they
were skipped because the body was in the way), so a goal found before is found the same way.
"""

from __future__ import annotations

import copy
import time
from dataclasses import replace

import numpy as np

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning import approach
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.goal_checks import use_ignores
from humanoidgen.planning.goal_solver import GoalResult
from humanoidgen.planning.context import PlanningContext
from humanoidgen.sim.geometry import axis_angle_mat
from humanoidgen.sim.layout import Side

SLANT_TURNS_DEG = (30, -30, 60, -60)  # turns of the leading edge about the squeeze axis, nearest first
SLANT_WAYS = 4  # pinches tried slanted: the first and three alternatives (the object's other squeeze directions)
SLANT_BUDGET_S = 8.0  # seconds for the rung
SLANT_SOLVE_S = 1.5  # no new solver seed after this long in one solve
SLANT_SEEDS = 4
LEADS = "index edge leads"
SQUEEZE = "pinch along the attach axis"


def slanted(gen, turn_deg: float):
    """The pinch `gen` with its leading edge turned `turn_deg` about its squeeze axis (a new Generated), or None
    where `gen` is no pinch of a loose object (a part's pinch has its own turns; a grasp has no edge leading)."""
    if gen is None or gen.approach_axis is None or gen.follow is not None or gen.grip_part is not None:
        return None
    lead = next((c for c in gen.constraints if c.name == LEADS), None)
    squeeze = next((c for c in gen.constraints if c.name == SQUEEZE), None)
    if lead is None or squeeze is None:
        return None
    R = axis_angle_mat(np.asarray(squeeze.object_axis, float), np.radians(turn_deg))
    turned = copy.copy(lead)
    turned.object_axis = R @ np.asarray(lead.object_axis, float)
    turned.name = f"{LEADS} at {turn_deg:+.0f} deg"
    swap = {id(lead): turned}
    point = next((c for c in gen.constraints if c.type == "point2point"), None)
    if point is not None:
        # A pinch point moved out along the fingers (a plan's finger_offset) is moved out level instead: along
        # the slanted fingers, the offset lifts the pads by its length times the slant's sine, over a block's top
        # (the G1's hand-over: a 2 cm offset at 60 deg closed the pinch 7 mm above the block); without it, the
        # pads wrap the block's corner and it slipped out on the carry.
        raw = get_point_in_env(point.env, f"pinch_point_base_{point.side}_hand")
        offset = np.asarray(point.hand_key_point, float) - raw
        back = axis_angle_mat(get_axis_in_env(point.env, f"{point.side}_thumb_2_index"), -np.radians(turn_deg))
        swap[id(point)] = Constraint(point.env, "point2point", point.end_effector_frame, name=point.name,
                                     hand_key_point=raw + back @ offset, object_key_point=point.object_key_point)
    return replace(gen, constraints=[swap.get(id(c), c) for c in gen.constraints],
                   approach_axis=turned.object_axis, alternatives=[], notes=list(gen.notes))


def slanted_goal(ctx: PlanningContext, side: Side, gen, ignored_before: set[int],
                 failed: GoalResult) -> tuple[GoalResult, object]:
    """(result, the way taken): the first slanted pinch that solves and can be approached straight, or the
    failure as it was."""
    if gen is None:
        return failed, gen
    t0 = time.perf_counter()
    for g in [gen, *gen.alternatives][:SLANT_WAYS]:
        for turn in SLANT_TURNS_DEG:
            way = slanted(g, turn)
            if way is None:
                break
            if time.perf_counter() - t0 > SLANT_BUDGET_S:
                return failed, gen
            use_ignores(ctx, side, way, ignored_before)
            retry = ctx.solver.solve(side, list(way.constraints), ctx.kin.arm_q(side), ctx.nominal[side],
                                      time_limit=SLANT_SOLVE_S, max_seeds=SLANT_SEEDS)
            if retry.success and approach.approach_fits(ctx, side, retry, way):
                ctx.events.append(f"no level pinch reaches it: the {side} hand pinches with the fingers turned "
                                  f"{turn:+d} deg about the squeeze axis (the wrist higher, clear of what is "
                                  "beside and behind the hand)")
                return retry, way
    return failed, gen
