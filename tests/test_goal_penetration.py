"""A path may leave a start that touches something, but a goal deep in an obstacle lets nothing through
(planning/motion.py `start_clearance` floor, GOAL_PENETRATION_M): before, the relaxed clearance of such a goal
held for the whole path, and a pre-approach pose 44 mm into an open drawer's wall took the wrist through it."""

from __future__ import annotations

import numpy as np
import pytest

from humanoidgen.planning.motion import (GOAL_PENETRATION_M, MotionError, plan_arm_motion, start_clearance,
                                         track_poses)
from humanoidgen.planning.poses import screw_interpolate
from humanoidgen.planning.planner import HumanoidMotionPlanner
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


def _deep_in_the_table(planner: HumanoidMotionPlanner, q0: np.ndarray) -> np.ndarray:
    """An arm configuration whose hand is at least 2 cm into the table: the hand tracked straight down from
    `q0` (tracking checks no collisions) until it is."""
    kin, cw = planner.ctx.kin, planner.ctx.collisions
    kin.set_arm("right", q0)
    kin.forward()
    p0, R0 = kin.ee_pose("right")
    for drop in np.arange(0.05, 0.5, 0.02):
        q, reason = track_poses(kin, "right", q0, screw_interpolate(p0, R0, p0 - np.array([0.0, 0.0, drop]), R0))
        if reason:
            break
        kin.set_arm("right", q[-1])
        kin.forward()
        if cw.min_distance(("right",))[0] < -0.02:
            return q[-1].copy()
    raise AssertionError("no configuration into the table found below the start")


def test_a_goal_deep_in_the_table_is_refused_but_a_start_there_may_leave():
    _, env = build_scene(load_task("block_stack_single"), 0)
    planner = task_planner(env, seed=0)
    kin, cw = planner.ctx.kin, planner.ctx.collisions
    kin.sync(env.data.qpos)
    q0 = kin.arm_q("right").copy()
    deep = _deep_in_the_table(planner, q0)
    kin.sync(env.data.qpos)
    assert start_clearance(kin, cw, "right", deep) < -0.02  # as a start: leave from as deep as it is
    assert start_clearance(kin, cw, "right", deep, -GOAL_PENETRATION_M) == pytest.approx(-GOAL_PENETRATION_M)
    kin.set_arm("right", deep)
    kin.forward()
    target = kin.ee_pose("right")
    kin.sync(env.data.qpos)
    with pytest.raises(MotionError):
        plan_arm_motion(kin, cw, "right", q0, target, q_goal=deep, seed=0, time_limit=0.5)
    # From there, back out to the start is a path (the start's own depth relaxes the clearance).
    kin.set_arm("right", q0)
    kin.forward()
    home = kin.ee_pose("right")
    kin.sync(env.data.qpos)
    path = plan_arm_motion(kin, cw, "right", deep, home, q_goal=q0, seed=0, time_limit=2.0)
    assert np.allclose(path.waypoints[0], deep) and np.allclose(path.waypoints[-1], q0, atol=1e-3)
