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
