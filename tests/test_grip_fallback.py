"""A whole-hand grasp that does not fit a small, low object falls back to the object's pinch (planner.py
`_solve_fallback`, constraint_gen `Generated.fallback`): a 5 cm cube grasped from above would put the thumb
33 mm into the table; plans that ask for `action="grasp"` on a cube (as LLMs write them) now pick it up."""

from __future__ import annotations

from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


def _planner(task: str, seed: int = 0) -> tuple:
    _, env = build_scene(load_task(task), seed)
    return env, task_planner(env, seed=seed)


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


def test_a_named_point_out_of_reach_on_a_rigid_object_is_taken_at_another_of_its_grips():
    """empty_cup_place seed 2 stands the cup beyond the right arm's reach from the front: a plan naming the cup's
    "side" grip (approached along the cup's x) found a goal but no way in on 5 of 10 seeds; the cup's other
    grasp (its right flank) is the last resort, with an event that says so."""
    env, planner = _planner("empty_cup_place", seed=2)
    cup = env.scene.object("cup", 0)
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints("cup", 0, "grasp", "right", point="side")
    gen = c[0].meta
    assert "side" in gen.constraints[0].name and "side_right" not in gen.constraints[0].name
    later = [a for a in gen.alternatives if any("at 'side_right' instead" in n for n in a.notes)]
    assert later and gen.alternatives[-len(later):] == later  # the named point's own ways come first
    _, pose = planner.generate_end_effector_pose(c, "right")
    assert any("at 'side' as asked" in e and "'side_right' instead" in e for e in planner.events)
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="cup", obj_id=0)
    assert planner.holding["right"] is cup


def test_a_named_point_on_a_part_is_not_swapped_for_another():
    # On an articulated object the point names which part (a knob's fin, not the door's handle).
    env, planner = _planner("rotate_safe_knob")
    c = planner.generate_constraints("safe", 0, "pinch", "right", point="knob_fin_right")
    assert all("knob_fin_right" in a.constraints[0].name for a in [c[0].meta, *c[0].meta.alternatives])
