"""Verbs asked the way a new author wrote them (bench/fresh_plans, docs/results/fresh-plans.md), each failing on
every seed before: a press or push straight to an openness or a force from a hand not on the part yet
(planning/onto_point.py), a lid flipped with openness where the task defines that push (its staged push), and
action="pull" on an object that lists a pull."""

from __future__ import annotations

import pytest

from humanoidgen.objects.describe import openness
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


def _planner(task: str, seed: int = 0):
    scene, env = build_scene(load_task(task), seed)
    return env, task_planner(env, seed=seed)


def _open(env, name: str) -> float:
    return float(openness(env.model, env.data, env.scene.object(name, 0)))


def _go(planner, side: str, obj: str, action: str, **kw) -> None:
    c = planner.generate_constraints(obj, 0, action=action, hand_name=side, **kw)
    _, pose = planner.generate_end_effector_pose(c, hand_name=side)
    planner.move_to_pose_with_screw(pose, side)


@pytest.mark.parametrize("first", [{"openness": 0.0}, {"openness": 1.0}, {"force": 5.0}])
def test_a_press_asked_from_afar_comes_onto_the_lever_first(first: dict) -> None:
    env, planner = _planner("press_toaster")
    planner.hand_press("right")
    _go(planner, "right", "toaster", "press", **first)
    assert any("came onto toaster 0's lever_top first" in e for e in planner.events)
    if "force" not in first:
        _go(planner, "right", "toaster", "press", openness=1.0)
    assert _open(env, "toaster") > 0.9


def test_a_lid_flipped_in_stages_with_openness_follows_the_tasks_push() -> None:
    env, planner = _planner("open_box_easy")
    planner.hand_press("right")
    for o in (_open(env, "box"), 0.4, 0.7, 1.0):
        _go(planner, "right", "box", "flip", openness=o)
    assert _open(env, "box") > 0.95


def test_pull_grips_the_handle_and_pulls_the_drawer_out() -> None:
    env, planner = _planner("open_drawer")
    start = _open(env, "drawer")
    planner.hand_pre_grasp("left")
    _go(planner, "left", "drawer", "grasp")
    planner.hand_grasp("left", "drawer", 0)
    _go(planner, "left", "drawer", "pull", openness=0.8)
    assert any(e.startswith("pull: the left hand's grasp of drawer 0") for e in planner.events)
    assert _open(env, "drawer") > max(start, 0.7)


def test_pull_on_an_object_without_one_says_what_it_has() -> None:
    from humanoidgen.planning.planner import PlanningError

    env, planner = _planner("press_toaster")
    with pytest.raises(PlanningError, match="toaster has no 'pull' annotation; actions for it: .*target1"):
        planner.generate_constraints("toaster", 0, action="pull", hand_name="right", openness=1.0)


def test_a_push_the_way_the_tasks_push_goes_is_that_push_at_its_point() -> None:
    # The laptop's annotated push is at the screen's back (out of reach); the task shuts it pushing at its edge.
    env, planner = _planner("close_laptop_easy", 1)
    planner.hand_press("right")
    _go(planner, "right", "laptop", "push", openness=0.0)
    assert _open(env, "laptop") < 0.1
