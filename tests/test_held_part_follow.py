"""A held articulated part follows the hand that holds it (issue 35 item 3): a knob turned by a pinch on its fin
reaches the angle asked (not short of it, at most a few degrees past) and stays there as the hand lets go; a lid
lowered in stages with one grasp stays in the fingers; a part let go where it does not stay is said to fall; a
failure names a part with a joint of its own (a safe's knob) and gives its angle in degrees."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from types import SimpleNamespace  # noqa: E402

import pytest  # noqa: E402
import yaml  # noqa: E402

from humanoidgen.planning import skills  # noqa: E402
from humanoidgen.planning.arm_moves import TURN_TOL_DEG, grip_again_advice, in_degrees, part_label  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402
from plan_runs import run_plan  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

PINCH = """
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="safe", obj_id=0)
"""
TURN = """
c = planner.generate_constraints(obj_name="safe", obj_id=0, action="pinch", hand_name="right", openness={deg} / 120)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="safe", object_id=0)
"""
LET_GO = """
planner.open_hand("right")
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
"""


def _knob_task(tmp_path, type_id: int, deg: float) -> str:
    """rotate_safe_knob on safe `type_id`, its check: the knob at `deg` or past it by at most TURN_TOL_DEG plus
    what letting go may add (5 deg)."""
    spec = load_task("rotate_safe_knob").model_dump(mode="json", exclude_none=True)
    spec["objects"][0]["type_id"] = type_id
    spec.update(name=f"knob_to_{deg:g}", plan=None, success=[
        {"type": "openness_at_least", "obj": "safe[0]", "part": "knob", "value": (deg - 1.0) / 120},
        {"type": "openness_at_most", "obj": "safe[0]", "part": "knob", "value": (deg + TURN_TOL_DEG + 5.0) / 120}])
    path = tmp_path / f"knob_{type_id}_{deg:g}.yaml"
    path.write_text(yaml.safe_dump(spec))
    return str(path)


@pytest.mark.parametrize("type_id, seed, degs", [
    (0, 0, (90,)), (1, 3, (60,)),
    # Known: stages of a small knob may end past the band (30 then 60 on seed 1: 72 deg once let go, the pinch
    # loosened on a knob the arm cannot slide off; issue 35's report).
    pytest.param(0, 1, (30, 60), marks=pytest.mark.xfail(reason="a staged turn may end up to 12 deg past", strict=False)),
])
def test_a_pinched_knob_is_turned_to_the_angle_asked_and_left_there(tmp_path, type_id, seed, degs):
    """One move or stages: the fin follows the pinching hand (before: 0-9% of the way; one move to 90 stopped at
    77; the larger safe's knob was not held at all or spun on to 105 deg when let go)."""
    text = PINCH + "".join(TURN.format(deg=d) for d in degs) + LET_GO
    result = run_plan(tmp_path, _knob_task(tmp_path, type_id, degs[-1]), seed, text)
    assert result.success, (result.checks, [s.error for s in result.steps if s.error])


def test_a_lid_lowered_in_stages_stays_in_the_grasp(tmp_path):
    """close_box_easy seed 3, the contract corpus's grasp_lower_release: the tab slid 15 mm a stage out of the
    fingers until they lost it at the second stage (0.31 of the 0.2 asked); the grip now goes back to where it
    closed on the lid as it lowers it on."""
    text = open(os.path.join(ROOT, "bench/contract_plans/close_box_easy/grasp_lower_release.py")).read()
    result = run_plan(tmp_path, "close_box_easy", 3, text)
    assert result.success, (result.checks, [s.error for s in result.steps if s.error])


def test_a_lid_let_go_where_it_does_not_stay_is_said_to_fall(tmp_path):
    text = """
planner.hand_pre_grasp("right")
c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_grasp("right", grasp_object="box", obj_id=0)
c = planner.generate_constraints(obj_name="box", obj_id=0, action="grasp", hand_name="right", openness=0.4)
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="box", object_id=0)
planner.open_hand("right")
"""
    result = run_plan(tmp_path, "open_box_hard", 1, text)
    assert any("does not stay (it stays where it is left only from openness 0.65 up)" in e for e in result.events), \
        result.events


def test_a_failure_on_a_knob_names_the_knob_in_degrees():
    from humanoidgen.objects.library import add_object
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder

    b = SceneBuilder()
    add_object(b, "safe", type_id=0, pos=(-0.22, -0.145), yaw=0.0)
    env = HumanoidEnv(b.build())
    ctx = SimpleNamespace(env=env)
    knob = skills.generate(env, {"left": None, "right": None}, "safe", 0, "pinch", "right", openness=0.5).follow
    door = skills.generate(env, {"left": None, "right": None}, "safe", 0, "grasp", "right", openness=0.5).follow
    assert part_label(ctx, knob) == "safe 0's knob" and part_label(ctx, door) == "safe 0"
    assert in_degrees(ctx, knob, 0.64) == " (77 deg)" and in_degrees(ctx, door, 0.5) == " (45 deg)"
    # The advice fits the grip: a pinched fin is pinched again, not grasped.
    assert "pinch it again" in grip_again_advice("pinch") and "grasp" not in grip_again_advice("pinch")
    assert grip_again_advice("grasp").startswith("grasp it again")


def test_a_correction_never_turns_the_knob_back():
    """The paper authors' plan asks the knob's stop (openness 1, 120 deg) in one move; the move left it at 92 deg
    and the corrections, the arm near its joint limits turning the hand back, dragged it to 76, then 0. A
    correction is now tried in the simulation first and made only where it turns the knob on."""
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    plan = os.path.join(ROOT, "bench", "foreign_plans", "rotate_safe_knob", "paper.py")
    result, _ = run_task_episode(EpisodeRequest("rotate_safe_knob", 0, plan_path=plan))
    assert result.success, [c["detail"] for c in result.checks]
