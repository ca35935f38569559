"""A whole-hand grasp that does not fit a small, low object falls back to the object's pinch (planner.py
`_solve_fallback`, constraint_gen `Generated.fallback`): a 5 cm cube grasped from above would put the thumb
33 mm into the table; plans that ask for `action="grasp"` on a cube (as LLMs write them) now pick it up."""

from __future__ import annotations

from humanoidgen.planning.planner import HumanoidMotionPlanner
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene


def _planner(task: str, seed: int = 0) -> tuple:
    _, env = build_scene(load_task(task), seed)
    return env, HumanoidMotionPlanner(env, seed=seed)


def test_a_grasp_of_a_small_cube_is_taken_as_a_pinch_and_lifts_it():
    env, planner = _planner("block_stack_single")
    cube = env.scene.object("cube", 1)
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="cube", obj_id=1, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    assert any("does not fit" in e and "pinches it instead" in e for e in planner.events)
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="cube", obj_id=1)
    assert planner.holding["right"] is cube
    z0 = env.object_pose(cube.body)[0][2]
    c = planner.generate_constraints(obj_name="cube", obj_id=1, action="target", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
    assert env.object_pose(cube.body)[0][2] - z0 > 0.02


def test_no_fallback_where_the_plan_named_the_point_or_the_grasp_fits():
    env, planner = _planner("block_stack_single")
    named = planner.generate_constraints(obj_name="cube", obj_id=1, action="grasp", hand_name="right", point="top")
    assert named[0].meta.fallback is None  # the plan asked for that grip: its failure is the answer
    env, planner = _planner("dual_bottles_pick_easy")
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="bottle", obj_id=1, action="grasp", hand_name="right")
    planner.generate_end_effector_pose(c, "right")
    assert not any("does not fit" in e for e in planner.events)
