"""A sampled path may come closer than MOTION_CLEARANCE only to what the arm touches at its start or goal
(motion.touched_at, CollisionWorld.touch_only). Relaxed for every obstacle, a path from beside an open drawer to the
left hand's home pose (5 mm into the drawer) swung the hand 3 mm into the right elbow, and the simulated arm struck
it (handover_and_storage, seed 4; end to end in tests/test_drop_in.py)."""

from __future__ import annotations

import numpy as np
import pytest

from humanoidgen.objects.articulated import set_openness
from humanoidgen.planning.motion import MOTION_CLEARANCE, plan_arm_motion, touched_at
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


@pytest.fixture(scope="module")
def home_in_the_drawer():
    _, env = build_scene(load_task("handover_and_storage"), 4)
    drawer = env.scene.object("drawer", 0)
    set_openness(env.model, env.data, drawer.body, drawer.annotations, 0.85)
    planner = task_planner(env, seed=4)
    return env, planner, env.model.body(drawer.body).id


def test_only_the_touched_obstacle_is_let_closer(home_in_the_drawer):
    env, planner, drawer = home_in_the_drawer
    kin, cw = planner.ctx.kin, planner.ctx.collisions
    home = planner.ctx.nominal["left"]
    assert touched_at(kin, cw, "left", [home]) == {drawer}  # the open drawer reaches the left hand's home pose
    kin.set_arm("left", home)
    kin.forward()
    try:
        with cw.touch_only("left", {drawer}, 0.02):
            assert cw.contact_pairs(("left",), MOTION_CLEARANCE) == []
        with cw.touch_only("left", {env.model.body("table").id}, 0.02):  # slack for another obstacle: no help
            assert [b2 for _, b2, _ in cw.contact_pairs(("left",), MOTION_CLEARANCE)] == [drawer]
    finally:
        kin.sync(env.data.qpos)


def test_a_sampled_path_home_keeps_clear_of_the_other_arm(home_in_the_drawer):
    env, planner, drawer = home_in_the_drawer
    kin, cw = planner.ctx.kin, planner.ctx.collisions
    # Where the left arm was after letting go of the open drawer's handle in that episode.
    start = np.array([-1.7451, 0.4851, -2.3689, 0.2446, 1.8739, -0.4699, 0.9064])
    home = planner.ctx.nominal["left"]
    path = plan_arm_motion(kin, cw, "left", start, (planner.left_hand_init_pose.p, planner.left_hand_init_pose.R),
                           q_goal=home, seed=4)
    right_arm = {b for b in range(env.model.nbody) if env.model.body(b).name.startswith(("right_", "R_"))}
    worst = np.inf
    try:
        for a, b in zip(path.waypoints[:-1], path.waypoints[1:]):
            for t in np.linspace(0.0, 1.0, 25):
                kin.set_arm("left", a + t * (b - a))
                kin.forward()
                worst = min([worst] + [d for _, b2, d in cw.contact_pairs(("left",), 0.05) if b2 in right_arm])
    finally:
        kin.sync(env.data.qpos)
    assert worst >= MOTION_CLEARANCE - 1e-3
