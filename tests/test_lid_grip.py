"""A lid's tab held by one grasp through a lowering in stages (issue 35 item 3): the box's grasp centres under the
tab's tip (`lid_grip`), where the closing fingers meet the 3 mm tab; centred on the tip they curled past it, the
hand slid 15 mm along the tab as it closed and the lid came out of the grasp at the first stage."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402
from plan_runs import run_plan  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def test_the_box_grasp_centres_under_the_tab_tip():
    _, env = build_scene(load_task("close_box_easy"), 0)
    box = env.scene.object("box", 0)
    grasp = next(op for op in box.annotations.operations if op.operation == "grasp")
    assert grasp.point == "lid_grip"
    tip, grip = (get_point_in_env(env, p, "box", 0) for p in ("lid_front", "lid_grip"))
    lid_in = get_axis_in_env(env, "lid_in", obj_type="box", obj_id=0)
    assert np.isclose(float((grip - tip) @ lid_in), 0.01, atol=1e-4)  # 1 cm under the tip, toward the inner side
    assert np.linalg.norm(grip - tip) < 0.0101


def test_a_lid_lowered_in_stages_by_its_tab_stays_in_the_grasp(tmp_path):
    """close_box_easy seed 5, the contract corpus's grasp_lower_release up to its release (0.35, 0.2, 0.08, let
    go): before, `box 0 is at openness 0.54 (54 deg) after the move, not the 0.35 (35 deg) asked (it moved 0% of
    the way from 0.52): the right hand's grip on it came off`. (The plan's fingertip push after it is left out: its
    path search is time-limited, and on a loaded machine it may find no path.)"""
    text = open(os.path.join(ROOT, "bench/contract_plans/close_box_easy/grasp_lower_release.py")).read()
    text = text[:text.index("# step: press the lid closed")]
    result = run_plan(tmp_path, "close_box_easy", 5, text)
    assert all(s.ok for s in result.steps), [s.error for s in result.steps]
    assert result.objects["box[0]"]["openness"] < 0.15


LIFT_AND_LET_GO = """
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="box", obj_id=0)
for o in [0.3, 0.5]:
    c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right", openness=o)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
planner.open_hand("right")
"""


def test_a_lid_let_go_where_it_falls_is_shut_when_open_hand_returns(tmp_path):
    """open_box_hard seed 1 (the contract corpus's grasp_lift_flip up to its release): the storage box's lid let
    go at 0.5 falls shut, as its description says. Before, the release's trials took the way that left it
    highest, shoving it up to 0.63, where it balanced until a fingertip came under it to flip it open and it fell
    to 0.39 in the push; now it is let go the usual way and open_hand returns once it has come to rest."""
    result = run_plan(tmp_path, "open_box_hard", 1, LIFT_AND_LET_GO)
    assert all(s.ok for s in result.steps), [s.error for s in result.steps]
    assert any("came to rest shut" in e for e in result.events), result.events
    assert result.objects["box[0]"]["openness"] < 0.02


def test_a_pre_push_goal_after_a_twisting_grip_is_solved_from_the_nominal_posture():
    """goal_search.push_seed: target1 of a task's push, with the arm twisted far from its nominal posture by a grip
    before (open_box_hard seed 1 after lifting the lid by its tab: the third joint 2.5 rad off), is solved from
    the nominal posture, as in a fresh episode; any other goal, or an arm near nominal, from the arm's own."""
    from types import SimpleNamespace

    from humanoidgen.planning.goal_search import TWISTED_RAD, push_seed
    from plan_runs import task_planner

    _, env = build_scene(load_task("open_box_hard"), 1)
    ctx = task_planner(env).ctx
    nominal = ctx.nominal["right"].copy()
    twisted = nominal + np.array([0.0, 0.0, TWISTED_RAD + 0.5, 0.0, 0.0, 0.0, 0.0])
    pre = SimpleNamespace(push=SimpleNamespace(phase="pre"))
    ctx.kin.arm_q = lambda side: twisted.copy()
    assert np.allclose(push_seed(ctx, "right", pre), nominal)
    assert np.allclose(push_seed(ctx, "right", SimpleNamespace(push=SimpleNamespace(phase="push"))), twisted)
    assert np.allclose(push_seed(ctx, "right", None), twisted)
    near = nominal + 0.3
    ctx.kin.arm_q = lambda side: near.copy()
    assert np.allclose(push_seed(ctx, "right", pre), near)
