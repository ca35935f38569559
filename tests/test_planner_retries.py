"""The planner tries harder before it fails, and a failure says what to change.

Each end-to-end test is a small plan in the paper's `def step(planner):` form (as a user or an LLM writes them,
not a reference plan) that used to fail, run through the real episode entry point (locked-down worker):

- a straight approach out of a goal boxed in by joint limits ("leaves the arm's reach or joint limits at 12% of
  the way"): the pre-approach pose is solved on its own and the hand comes in from there;
- a box lid's tab reachable only with a finger in the table: the wrist's freedom (a small cone) takes it;
- an open drawer's handle grasped without a hold (the pre-grasp thumb pushed the drawer shut on the way in):
  the hand comes in open and closes around the handle, and closing the drawer by it now succeeds (as does the
  plan that closes it partly and pushes the rest); but not where the fingers, opening at the pre-pose, would
  strike something (a safe's door beside its knob);
- a flip that cannot close a laptop, a push that does not carry the screen (the run used to finish with the
  laptop at 0.13), a hand stopped short against a screen: each an error that names why and what to use.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from humanoidgen.planning import approach
from humanoidgen.objects.library import add_object
from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning import goal_search
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.planner import PlanningError
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.scene import SceneBuilder
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene
from plan_runs import run_plan, task_planner


def without_push(tmp_path, task: str) -> str:
    """The task's YAML without its targets: target1/target2 then fall back to the annotated push points (the
    mechanism these tests check); with the task's push target they are its staged push (test_push_targets.py)."""
    from humanoidgen.tasks.registry import load_task

    raw = load_task(task).model_dump(mode="json", exclude={"targets", "plan"}, exclude_none=True)
    path = tmp_path / f"{task}.yaml"
    path.write_text(json.dumps(raw))  # JSON is YAML
    return str(path)


def events(result) -> str:
    return " | ".join(e for s in result.steps for e in s.events)


LAPTOP_FLIP_CLOSE = '''def step(planner):
    # Step 1: fingertip to the screen's edge
    planner.hand_press("right")
    c = planner.generate_constraints("laptop", 0, "target1", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    # Step 2: close the screen from there
    c = planner.generate_constraints("laptop", 0, "target1", "right", openness=0)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
'''


def test_approach_from_a_solved_pre_pose_and_a_flip_that_cannot_close(tmp_path):
    # Seed 0: the goal at the screen's edge has three arm joints at their limits; tracking the straight line back
    # from it failed at 12% of the way for every approach distance ("no straight approach to the target").
    result = run_plan(tmp_path, without_push(tmp_path, "close_laptop_easy"), 0, LAPTOP_FLIP_CLOSE)
    first, second = result.steps
    assert first.ok, first.error
    assert "pre-approach pose solved on its own" in events(result)
    # A flip gets under the screen and lifts it: the planner says so and what would push the right way.
    assert not second.ok
    assert "a flip gets under laptop 0" in second.error and "cannot bring it down to openness 0" in second.error
    assert "target2" in second.error and "explicit Constraints" in second.error


BOX_LID_GRASP = '''def step(planner):
    # Step 1: grasp the lid's tab
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints("box", 0, "grasp", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    planner.hand_grasp("right", grasp_object="box", obj_id=0)
    # Step 2: lift the lid to openness 0.3
    c = planner.generate_constraints("box", 0, "grasp", "right", openness=0.3)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
'''


def test_box_lid_tab_is_taken_with_the_wrists_freedom_and_the_lid_lifted(tmp_path):
    # The exact grip on the shut lid's tab needed the middle finger 2.5 mm into the table.
    result = run_plan(tmp_path, "open_box_hard", 0, BOX_LID_GRASP)
    first, second = result.steps
    assert first.ok, first.error
    assert "wrist turned" in events(result) and "grasped box 0" in events(result)
    # Lifting the held lid rides with it from the grip as it is, the lid turning in the fingers (it used to stop
    # at the arm's reach; test_part_holding covers the roll).
    assert second.ok, second.error


CLOSE_DRAWER_BY_GRASP = '''def step(planner):
    # Step 1: Left hand grasps the drawer
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints("drawer", 0, "grasp", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    # Step 2: Left hand closes the drawer to an openness of 0
    c = planner.generate_constraints("drawer", 0, "grasp", "left", openness=0)
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    # Step 3: Left hand releases the drawer
    planner.open_hand("left")
'''

CLOSE_DRAWER_AS_SUGGESTED = '''def step(planner):
    # Step 1: grasp the open drawer's handle
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints("drawer", 0, "grasp", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    # Step 2: push it in as far as the grip reaches, let go
    c = planner.generate_constraints("drawer", 0, "grasp", "left", openness=0.4)
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    planner.open_hand("left")
    # Step 3: push the rest with the fingertip
    planner.hand_press("left")
    c = planner.generate_constraints("drawer", 0, "target1", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left")
    planner.ignore_collision("drawer", 0)
    c = planner.generate_constraints("drawer", 0, "target1", "left", openness=0)
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left")
    planner.restore_collision("drawer", 0)
    planner.move_to_pose_with_screw(planner.left_hand_init_pose, "left")
'''


def test_open_drawer_handle_is_held_and_closing_it_by_the_handle_shuts_it(tmp_path):
    # The paper's open-drawer sample reversed used to fail at hand_grasp ("touching: nothing"): the pre-grasp
    # thumb, 10 cm out of the palm, hit the handle and pushed the drawer from 0.55 to 0.07 on the way in.
    result = run_plan(tmp_path, "close_drawer", 0, CLOSE_DRAWER_BY_GRASP)
    grasp, close = result.steps[0], result.steps[1]
    assert grasp.ok, grasp.error
    assert "with the fingers open" in events(result) and "grasped drawer 0 with the left hand" in events(result)
    # Closing it by the handle used to leave the arm's reach at 44% ("can move it only from openness 0.55 to
    # 0.35"); the grip now rolls about the handle on the way (test_part_holding) and the drawer shuts.
    assert close.ok, close.error
    assert result.success, result.checks


def test_the_suggested_close_drawer_plan_shuts_the_drawer_but_not_as_the_task_asks(tmp_path):
    # A grip that pushes part of the way, then a fingertip for the rest: every step runs and the drawer ends shut.
    # The task asks the drawer pushed shut by the hand holding its handle (moved_while_held): one hold moved it
    # 0.2 of the way, not the 0.4 asked, so the episode does not count.
    result = run_plan(tmp_path, "close_drawer", 0, CLOSE_DRAWER_AS_SUGGESTED)
    failed = result.failed_step
    assert failed is None, failed.error
    checks = {c["predicate"]: c["ok"] for c in result.checks}
    assert checks == {"openness_at_most": True, "moved_while_held": False}, result.checks
    assert not result.success


LAPTOP_FLIP_OPEN = '''def step(planner):
    # Step 1: fingertip to the flip point under the screen's edge
    planner.hand_press("right")
    c = planner.generate_constraints("laptop", 0, "target1", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    # Step 2: flip the screen up, riding with it
    c = planner.generate_constraints("laptop", 0, "target1", "right", openness=0.9)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
'''


def test_a_push_that_does_not_carry_the_part_is_an_error_not_a_silent_finish(tmp_path):
    result = run_plan(tmp_path, without_push(tmp_path, "open_laptop_easy"), 0, LAPTOP_FLIP_OPEN)
    failed = result.failed_step
    assert failed is not None and failed.index == 1
    assert "laptop 0 is at openness 0.1" in failed.error and "not the 0.9 (99 deg) asked" in failed.error
    assert "fingertip did not carry it" in failed.error


PRESS_SCREEN_BACK = '''def step(planner):
    # Step 1: press the back of the screen down with the palm
    planner.ignore_collision("laptop", 0)
    for o in (None, 0.3, 0.1, 0.0):
        c = [Constraint(env=planner.env, type="point2point", end_effector_frame="r_hand_base_link",
                        hand_key_point=get_point_in_env(planner.env, "palm_center_right_hand"),
                        object_key_point=get_point_in_env(planner.env, "screen_back", "laptop", 0, openness=o)
                        + np.array([0.0, 0.0, 0.05 if o is None else 0.015])),
             Constraint(env=planner.env, type="parallel", end_effector_frame="r_hand_base_link",
                        hand_axis=get_axis_in_env(planner.env, "right_grasp_axis"), object_axis=np.array([0.0, 0.0, -1.0]))]
        _, pose = planner.generate_end_effector_pose(c, "right")
        planner.move_to_pose_with_screw(pose, "right")
'''


def test_a_hand_stopped_short_names_what_it_presses_against(tmp_path):
    result = run_plan(tmp_path, "close_laptop_easy", 1, PRESS_SCREEN_BACK)
    failed = result.failed_step
    assert failed is not None
    assert "stopped" in failed.error and "pressed against laptop 0 (palm)" in failed.error
    assert "ignore_collision only stops the planner avoiding it" in failed.error


# -- in-process checks of the mechanisms ------------------------------------------------------------------
def test_scratch_hand_posture_matches_the_simulated_fingers():
    env = HumanoidEnv(SceneBuilder().build())
    planner = task_planner(env)
    planner.hand_pre_grasp("left")
    planner.ctx.settle(0.3)
    kin, m = planner.ctx.kin, env.model
    kin.sync(env.data.qpos)
    kin.set_hand("left", np.array(HAND_POSTURES["open"]))
    kin.set_hand("left", np.array(HAND_POSTURES["pre_grasp"]))
    kin.forward()
    thumb = m.body("L_thumb_distal").id
    assert np.linalg.norm(kin.data.xpos[thumb] - env.data.xpos[thumb]) < 0.003


def _fingertip_goal(planner, env, z: float):
    c = [Constraint(env, "point2point", "r_hand_base_link", hand_key_point=get_point_in_env(env, "press_point_base_right_hand"),
                    object_key_point=np.array([-0.33, -0.15, z])),
         Constraint(env, "parallel", "r_hand_base_link", hand_axis=get_axis_in_env(env, "right_press_axis"),
                    object_axis=np.array([0.5, 0.0, -0.866]))]
    return planner.generate_end_effector_pose(c, "right")


def test_fingers_that_would_strike_the_door_as_they_open_come_in_as_they_are():
    """rotate_safe_knob, seed 9: the fin pinch's 8 cm way in fits with the fingers open, but the pre-pinch's
    tucked fingers, unfolding at the pre-pose, meet the safe's door. In simulation they stuck on it and the hand
    slid in dragging them, 41 mm short, where the thumb missed the fin (the corpus's knob plans failed there)."""
    spec = load_task("rotate_safe_knob")
    _, env = build_scene(spec, 9)
    planner = task_planner(env, seed=9)
    planner.hand_pre_pinch("right")
    _, pose = planner.generate_end_effector_pose(planner.generate_constraints("safe", 0, "pinch", "right"), "right")
    home = planner.ctx.kin.arm_q("right")
    plan = approach.plan_approach(planner.ctx, "right", home, pose)
    pre = plan.legs[-1].waypoints[0]
    assert not approach.room_to_change(planner.ctx, "right", pre, "open", pose.approach_part)
    assert approach.room_to_change(planner.ctx, "right", home, "open", pose.approach_part)
    assert plan.posture is None  # it used to be "open"
    planner.move_to_pose_with_screw(pose, "right")
    planner.ctx.kin.sync(env.data.qpos)
    planner.ctx.kin.forward()
    assert np.linalg.norm(planner.ctx.kin.ee_pose("right")[0] - pose.p) < 0.01
    planner.hand_pinch("right", "safe", 0)
    assert planner.holding["right"] is not None


def test_fingers_may_come_near_the_table_when_the_goal_needs_it_and_say_so():
    env = HumanoidEnv(SceneBuilder().build())
    planner = task_planner(env)
    planner.hand_press("right")
    _, pose = _fingertip_goal(planner, env, 0.004)  # the index within ~2 mm of the table, not the usual 5 mm
    assert pose.finger_table_slack > 0
    assert any("fingers come within" in e and "of the table" in e for e in planner.events)
    planner.move_to_pose_with_screw(pose, "right")
    with pytest.raises(PlanningError, match=r"in the way: the table\]. Suggestion: .*approach from above"):
        _fingertip_goal(planner, env, -0.002)  # into the table: still refused


def test_out_of_range_goal_names_the_range_and_the_other_hand():
    b = SceneBuilder()
    add_object(b, "cube", 0, pos=(-0.33, 0.28))
    env = HumanoidEnv(b.build())
    planner = task_planner(env)
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints("cube", 0, "pinch", "right")
    with pytest.raises(PlanningError) as err:
        planner.generate_end_effector_pose(c, "right")
    msg = str(err.value)
    assert "mm from its target" in msg
    assert "out of the right hand's range (x in [-0.42, -0.19], y in [-0.36, 0.07])" in msg and "use the left hand" in msg


def test_an_upright_screen_edge_at_the_end_of_reach_is_pinched_with_the_wrist_tilted_further():
    """close_laptop_hard, seed 4: the raised screen's edge (laptop turned 24 deg) is 139 mm out of the right hand's
    reach for a pinch from straight above and out of a 15 deg cone too; the wider cone takes it."""
    _, env = build_scene(load_task("close_laptop_hard"), 4)
    planner = task_planner(env, seed=4)
    c = planner.generate_constraints("laptop", 0, "pinch", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    turned = [e for e in planner.events if "wrist turned" in e]
    assert turned, planner.events
    angles = [float(a) for a in re.findall(r"(\d+) deg", turned[-1])]
    assert max(angles) > goal_search.CONE_DEG  # beyond the first cone: the wide one was needed
