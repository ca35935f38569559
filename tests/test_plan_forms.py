"""Plan files as others write them: the paper's `def step(planner):` with helpers, imports and early
returns, a folder of step files, and a plan that cannot even be parsed; all run in the plan worker."""

from __future__ import annotations

from pathlib import Path

import pytest

from humanoidgen.episodes.plans import PlanFormatError, load_plan, parse_plan
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode
from humanoidgen.tasks.registry import SPECS_DIR

HELPERS = '''from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
import numpy as np

HAND = "right"

def reach(planner, action, **kw):
    c = planner.generate_constraints(obj_name="cube", obj_id=1, action=action, hand_name=HAND, **kw)
    _, pose = planner.generate_end_effector_pose(c, hand_name=HAND)
    return pose

def step(planner):
    # Step 1: pinch cube 1
    planner.hand_pre_pinch(HAND)
    planner.move_to_pose_with_screw(reach(planner, "pinch"), HAND, attach_obj=False)
    planner.hand_pinch(HAND, pinch_object="cube", obj_id=1)
    # Step 2: put it on cube 0, coming from above
    for height in (0.12, 0.045):
        pose = reach(planner, "move", relative_obj_name="cube", relative_obj_id=0, relative_p=np.array([0, 0, height]))
        planner.move_to_pose_with_screw(pose, HAND, attach_obj=True, object_name="cube", object_id=1)
    planner.open_hand(HAND)

step(planner)
'''


def test_helpers_and_imports_outside_step_become_a_first_step() -> None:
    plan = parse_plan(HELPERS)
    assert [s.title for s in plan.steps] == ["definitions", "pinch cube 1", "put it on cube 0, coming from above"]
    assert "def reach" in plan.steps[0].code and "step(planner)" not in plan.code().split("def reach")[0]


def test_an_early_return_keeps_the_function_whole() -> None:
    src = "def step(planner):\n    # Step 1: a\n    if planner is None:\n        return\n    # Step 2: b\n    x = 1\n"
    (only,) = parse_plan(src).steps
    assert only.code.startswith("def step(planner):")


def test_step_marks_inside_blocks_do_not_split_them() -> None:
    src = "def step(planner):\n    # Step 1: a\n    for i in range(2):\n        # Step 2: inside\n        x = i\n"
    (only,) = parse_plan(src).steps
    assert "for i in range(2)" in only.code


def test_helper_plan_runs_and_stacks(tmp_path: Path) -> None:
    path = tmp_path / "plan.py"
    path.write_text(HELPERS)
    result, _ = run_task_episode(EpisodeRequest("block_stack_single", seed=0, plan_path=str(path)))
    assert [s.ok for s in result.steps] == [True, True, True], [s.error for s in result.steps]
    assert result.success, result.checks


def test_a_folder_of_step_files_runs_in_natural_order(tmp_path: Path) -> None:
    ref = load_plan(SPECS_DIR / "block_stack_single.py")
    folder = tmp_path / "plan"
    folder.mkdir()
    for i, s in enumerate(ref.steps):  # step10.py would sort after step2.py: natural order, not text order
        body = "\n".join("    " + ln for ln in s.code.splitlines())
        (folder / f"step{i * 5}.py").write_text(f"def step(planner):\n    # Step 1: {s.title}\n{body}\n")
    plan = load_plan(folder)
    assert [s.title for s in plan.steps] == [s.title for s in ref.steps]
    result, _ = run_task_episode(EpisodeRequest("block_stack_single", seed=0, plan_path=str(folder)))
    assert result.success and len(result.steps) == len(ref.steps)


def test_a_folder_with_numbered_steps_ignores_stray_files(tmp_path: Path) -> None:
    # Upstream's folders carry leftovers such as "step3 copy.py"; upstream runs step0, step1, ... by name.
    folder = tmp_path / "plan"
    folder.mkdir()
    (folder / "step0.py").write_text("def step(planner):\n    planner.hand_pre_pinch('right')\n")
    (folder / "step1.py").write_text("def step(planner):\n    planner.open_hand('right')\n")
    (folder / "step1 copy.py").write_text("def step(planner):\n    planner.hand_pre_grasp('left')\n")
    (folder / "helpers.py").write_text("X = 1\n")
    assert [s.code.strip() for s in load_plan(folder).steps] == ["planner.hand_pre_pinch('right')",
                                                               "planner.open_hand('right')"]
    (folder / "step0.py").unlink()
    (folder / "step1.py").unlink()  # without numbered step files, every .py is a step
    assert len(load_plan(folder).steps) == 2


def test_an_empty_folder_and_a_parser_bomb_are_clear_errors(tmp_path: Path) -> None:
    (tmp_path / "empty").mkdir()
    with pytest.raises(PlanFormatError, match="no .py step files"):
        run_task_episode(EpisodeRequest("block_stack_single", seed=0, plan_path=str(tmp_path / "empty")))
    bomb = tmp_path / "bomb.py"
    bomb.write_text("x = " + "-" * 15000 + "1\n")
    with pytest.raises(PlanFormatError, match="nested too deeply"):
        run_task_episode(EpisodeRequest("block_stack_single", seed=0, plan_path=str(bomb)))
