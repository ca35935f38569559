"""Other ways in (planning/approach.py): where no straight line along the operation's axis fits, the hand comes in
straight from another direction that keeps the object between thumb and fingers.

- the directions: unit, across the thumb-to-index line at the goal, at least ~45 deg off the axis and each other;
- a plan written outside the project hands a block over beside the open drawer (the right hand holds it out at
  15 cm, free end toward the left): the left hand's way in along the block runs its wrist into the drawer, from
  above it fits; the pinch holds, and the hand later backs out the way it came.
"""

from __future__ import annotations

import numpy as np
import pytest

from humanoidgen.planning import approach
from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.planning.approach import OTHER_WAY_MAX_COS
from humanoidgen.planning.constraints import Constraint
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import cube_pinch_pose, task_planner  # noqa: E402


def test_other_directions_keep_the_object_between_thumb_and_fingers():
    planner, pose = cube_pinch_pose()
    ways = approach.other_ways_in(planner.ctx, "right", pose)
    assert len(ways) >= 2
    thumb, index = approach.fingertips_at(planner.ctx, "right", pose.joint_q)
    t = (index - thumb) / np.linalg.norm(index - thumb)
    axis = np.asarray(pose.approach_axis)
    for k, (u, how) in enumerate(ways):
        assert np.linalg.norm(u) == pytest.approx(1.0)
        assert abs(u @ t) < 1e-9, how
        assert u @ axis <= OTHER_WAY_MAX_COS
        assert all(u @ w <= OTHER_WAY_MAX_COS for w, _ in ways[:k])


@pytest.mark.slow
def test_a_hand_over_beside_the_open_drawer_is_taken_from_another_side():
    _, env = build_scene(load_task("handover_and_storage"), 0)
    planner = task_planner(env)
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints("drawer", 0, "grasp", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left")
    planner.hand_grasp("left", "drawer", 0)
    c = planner.generate_constraints("drawer", 0, "grasp", "left", openness=0.9)
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    planner.open_hand("left")
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints("rectangular_cube", 0, "pinch", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    planner.hand_pinch("right", "rectangular_cube", 0)
    c = planner.generate_constraints("rectangular_cube", 0, "target", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="rectangular_cube", object_id=0)
    c = [Constraint(env=env, type="point2point", end_effector_frame="r_hand_base_link",
                    hand_key_point=get_point_in_env(env, type_name="cube", obj_id=0),
                    object_key_point=np.array([-0.30, 0.0, 0.15]))]
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="rectangular_cube", object_id=0)
    planner.hand_pre_pinch("left")
    c = planner.generate_constraints("rectangular_cube", 0, "pinch", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left")
    came_in = [e for e in planner.events if e.startswith("the left hand came in")][-1]
    assert any(how in came_in for how in ("from above", "from the front", "square to")), came_in
    assert abs(np.asarray(planner.ctx.hands["left"].last_approach) @ np.asarray(pose.approach_axis)) < 0.9
    planner.hand_pinch("left", "rectangular_cube", 0)
    assert planner.holding["left"] is env.scene.object("cube", 0)
