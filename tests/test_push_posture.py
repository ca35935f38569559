"""A pre-push pose (target1) is reached in the arm posture the goal solver found for it, where a way keeps to it.

The screw motion to a pose keeps the arm's posture family. After a lid lifted by its tab to 0.5 and let go, the
right arm reached the storage box's pre-push pose with the elbow and wrist turned over (third joint 2.3 rad; the
solver's goal, solved from the nominal posture, -0.2 rad), and the push's stages, tracked from there, pushed the
lid "from 0.00 to 0.00" (the contract corpus's open_box_hard/grasp_lift_flip, seeds 2, 3 and 9). `keep_posture`
(set for target1 poses) tries a sampled path to the solver's posture first; the screw motion stays the fallback.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.planning.motion import LANDING_MAX_RAD, plan_arm_motion
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene
from plan_runs import run_plan

ROOT = Path(__file__).resolve().parents[1]
# The two postures of the right arm at open_box_hard seed 2's pre-push pose (measured in the episode).
TURNED_OVER = np.array([-1.24, -0.84, 2.26, -0.4, 1.18, 0.24, -1.27])
SOLVED = np.array([-0.12, -0.1, -0.16, -0.4, -1.17, 0.29, 1.03])


def test_keep_posture_ends_in_the_goals_posture():
    _, env = build_scene(load_task("open_box_hard"), 2)
    kin = Kinematics(env.model)
    kin.sync(env.data.qpos)
    cw = CollisionWorld(kin)
    kin.set_arm("right", SOLVED)
    kin.forward()
    target = kin.ee_pose("right")
    # A little way off the pre-push pose in the turned-over posture, as the arm comes there.
    kin.set_arm("right", TURNED_OVER)
    kin.forward()
    plain = plan_arm_motion(kin, cw, "right", TURNED_OVER, target, q_goal=SOLVED)
    kept = plan_arm_motion(kin, cw, "right", TURNED_OVER, target, q_goal=SOLVED, keep_posture=True)
    assert np.max(np.abs(plain.waypoints[-1] - SOLVED)) > LANDING_MAX_RAD  # the screw motion stays turned over
    assert np.max(np.abs(kept.waypoints[-1] - SOLVED)) < 1e-3
    assert kept.method == "rrt_connect"


def test_a_lid_let_go_shut_after_a_lift_is_flipped_open_from_target1(tmp_path):
    plan = (ROOT / "bench/contract_plans/open_box_hard/grasp_lift_flip.py").read_text()
    result = run_plan(tmp_path, "open_box_hard", 2, plan)
    assert result.success, [s.error for s in result.steps if not s.ok] or result.checks
