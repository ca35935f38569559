"""The press as the API's contract states it (prompts/planner_api.yaml, issue 35 items 3-4): target1/target2 on a
one-point press, a press written as Constraint objects solved as the press (planning/press_intent.py), and what
a goal with a hand axis held exactly says when it is out of reach."""

from __future__ import annotations

import math

import numpy as np
import pytest

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning import press_intent
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.goal_checks import exact_axis_advice
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


def _planner(task: str, seed: int = 0) -> tuple:
    _, env = build_scene(load_task(task), seed)
    return env, task_planner(env, seed=seed)


def _openness(env) -> float:
    from humanoidgen.objects.describe import openness

    return float(openness(env.model, env.data, env.scene.object("toaster", 0)))


def test_target2_on_a_one_point_press_is_the_press_to_its_end() -> None:
    env, planner = _planner("press_toaster")
    planner.hand_press("right")
    for action, kwargs in (("target1", {}), ("target2", {"openness": 1.0})):
        c = planner.generate_constraints("toaster", 0, action=action, hand_name="right", **kwargs)
        _, pose = planner.generate_end_effector_pose(c, hand_name="right")
        planner.move_to_pose_with_screw(pose, "right")
    assert _openness(env) > 0.9
    assert any("target2 is the press's end" in e for e in planner.events)
    # without openness=, target2 presses all the way, and says so
    c = planner.generate_constraints("toaster", 0, action="target2", hand_name="right")
    assert c[0].meta.follow is not None and c[0].meta.follow.q_target == pytest.approx(
        c[0].meta.follow.articulation.joint_position(1.0))
    assert any("all the way; give openness= for less" in e for e in planner.events)


def test_no_target2_on_one_push_point_says_to_use_target1_with_openness() -> None:
    env, planner = _planner("open_drawer")  # its task defines no push of the drawer; the drawer has one push point
    with pytest.raises(Exception) as failure:
        planner.generate_constraints("drawer", 0, action="target2", hand_name="left")
    msg = str(failure.value)
    assert msg.startswith("generate_constraints:") and "no target2" in msg, msg
    assert "action='target1'" in msg and "openness=" in msg, msg


def _raw_press(env, lift: float, exact: bool = True, openness: float | None = None) -> list:
    lever = get_point_in_env(env, "lever_top", "toaster", 0, openness=openness)
    down = get_axis_in_env(env, "down", "toaster", 0)
    tip = get_point_in_env(env, "press_point_base_right_hand")
    axis = get_axis_in_env(env, "right_press_axis")
    turn = (Constraint(env, "parallel", "r_hand_base_link", hand_axis=axis, object_axis=down) if exact else
            Constraint(env, "angle", "r_hand_base_link", hand_axis=axis, object_axis=down, lower=0.0,
                       upper=math.radians(30)))
    return [Constraint(env, "point2point", "r_hand_base_link", hand_key_point=tip,
                       object_key_point=lever + np.array([0.0, 0.0, lift])), turn]


def test_constraints_on_a_press_point_are_read_as_that_press() -> None:
    env, planner = _planner("press_toaster")
    planner.hand_press("right")
    gen = press_intent.infer(env, "right", _raw_press(env, 0.02), planner.holding)
    assert gen is not None and gen.approach_object == "toaster_0_lever"  # the lever, not the toaster's body
    assert not gen.presses and gen.follow is None
    assert np.allclose(gen.approach_axis, [0.0, 0.0, -1.0], atol=1e-6)  # comes in along the plan's direction
    (clear,) = [c for c in gen.constraints if c.soft and np.allclose(
        c.hand_axis, get_axis_in_env(env, "right_grasp_axis"), atol=1e-6)]  # the palm away from the body
    centre, lever = get_point_in_env(env, "center", "toaster", 0), get_point_in_env(env, "lever_top", "toaster", 0)
    assert clear.object_axis[2] == 0.0 and float(clear.object_axis @ (lever - centre)) > 0
    (loose,) = gen.alternatives  # the exact press direction let within the push cone
    kinds = [(c.type, c.soft) for c in loose.constraints]
    assert ("angle", False) in kinds and ("parallel", True) in kinds and ("parallel", False) not in kinds
    pressed = press_intent.infer(env, "right", _raw_press(env, -0.005, openness=1.0), planner.holding)
    assert pressed.presses and pressed.follow is not None
    assert pressed.follow.q_target >= pressed.follow.articulation.joint_position(1.0) - 1e-9
    # not a press: the press point far from any press point, or another hand point
    assert press_intent.infer(env, "right", _raw_press(env, 0.2), planner.holding) is None
    far = _raw_press(env, 0.0)
    far[0] = Constraint(env, "point2point", "r_hand_base_link", hand_key_point=get_point_in_env(
        env, "palm_center_right_hand"), object_key_point=far[0].object_key_point)
    assert press_intent.infer(env, "right", far, planner.holding) is None


@pytest.mark.parametrize("seed", [0, 3])
def test_a_press_written_as_constraints_presses_the_lever(seed: int) -> None:
    env, planner = _planner("press_toaster", seed)
    planner.hand_press("right")
    for cons in (lambda: _raw_press(env, 0.02, exact=False), lambda: _raw_press(env, 0.0, False, openness=1.0)):
        _, pose = planner.generate_end_effector_pose(cons(), hand_name="right")
        planner.move_to_pose_with_screw(pose, "right")
    assert _openness(env) > 0.9


def test_an_exact_axis_out_of_reach_is_named_with_the_angle_to_use_instead() -> None:
    env, planner = _planner("block_stack_single")
    c = [Constraint(env, "point2point", "r_hand_base_link", hand_key_point=get_point_in_env(
             env, "press_point_base_right_hand"), object_key_point=np.array([-0.3, -0.15, 0.15])),
         Constraint(env, "parallel", "r_hand_base_link", hand_axis=get_axis_in_env(env, "right_press_axis"),
                    object_axis=np.array([-1.0, 0.0, 0.0]))]
    with pytest.raises(Exception) as failure:
        planner.generate_end_effector_pose(c, hand_name="right")
    msg = str(failure.value)
    assert msg.startswith("generate_end_effector_pose:") and "right_press_axis" in msg
    assert '"angle"' in msg and "math.radians(20)" in msg
    assert exact_axis_advice(c[:1]) == ""  # no exact axis: nothing to say
