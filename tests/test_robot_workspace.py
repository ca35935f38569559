"""A robot's workspace (robot.yaml `workspace`): positions the task specs and reference plans give about the arms'
reach (a mid-air hand-over target, the spot a plan hands a block over at) are placed per robot. The H1-2's map
is the identity, bit for bit; the G1's moves them out; a bad field fails with one line naming file and field."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from humanoidgen.cli.main import app
from humanoidgen.robots import RobotFileError, load_robot
from humanoidgen.robots.loader import ROBOTS_DIR
from humanoidgen.robots.schema import Workspace
from humanoidgen.robots.workspace import WorkspaceMap
from humanoidgen.sim import layout
from humanoidgen.tasks.registry import load_task, plan_path
from humanoidgen.tasks.targets import Target

runner = CliRunner()
HANDOVER_TASKS = ("block_handover", "handover_and_storage", "handover_and_storage_cooperation")


def _pos_targets(task: str) -> list:
    return [t for t in load_task(task).targets if t.pos is not None]


def test_the_h1_2_gives_every_position_back_bit_for_bit():
    ws = load_robot("h1_2_inspire").workspace
    assert ws.identity
    rng = np.random.default_rng(0)
    for p in [*rng.uniform(-0.5, 0.5, (50, 3)), np.array([-0.36, 0.0, 0.045]), np.array([-0.0, 0.0, 0.31])]:
        out = ws.point(p)
        assert out.dtype == np.float64 and out.tobytes() == np.asarray(p, float).tobytes()
        assert out is not p  # a new array: a plan may change it without changing its input


@pytest.mark.parametrize("task", HANDOVER_TASKS)
def test_a_hand_over_target_lies_where_the_spec_says_for_the_h1_2_and_elsewhere_for_a_robot_with_a_workspace(
        task: str, robot_copy: Path):
    assert layout.ROBOT.name == "h1_2_inspire"  # the process's robot in tests
    path = robot_copy / "robot.yaml"
    data = yaml.safe_load(path.read_text())
    data["workspace"] = {"offset": [0.05, 0.0, 0.0], "per_height": [0.2, 0.0, 0.0]}
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    other = load_robot(path, cached=False).workspace
    targets = _pos_targets(task)
    assert targets
    for spec in targets:
        here = Target(spec, np.zeros(3)).position(env=None)
        assert here.tobytes() == np.array(spec.pos, float).tobytes()
        there = other.point(spec.pos)
        # out from the robot's body (x; more the higher it is), on the same side (y), at the same height
        assert there[0] == pytest.approx(spec.pos[0] + 0.05 + 0.2 * spec.pos[2])
        assert there[1] == spec.pos[1] and there[2] == spec.pos[2]


def test_the_g1_keeps_the_reference_spots_as_measured():
    # docs/results/g1.md: hand-overs moved out lost episodes on the G1; its file says so with the identity.
    assert load_robot("g1_inspire").workspace.identity


def test_the_map_moves_mid_air_positions_more_than_positions_on_the_table():
    ws = WorkspaceMap.of(Workspace(offset=(0.04, 0.0, 0.0), per_height=(0.1, 0.0, -0.2)))
    on_table, up = ws.point([-0.36, 0.0, 0.0]), ws.point([-0.36, 0.0, 0.30])
    assert np.allclose(on_table, [-0.32, 0.0, 0.0])
    assert np.allclose(up, [-0.36 + 0.04 + 0.03, 0.0, 0.30 - 0.06])
    assert np.allclose(ws.point([[-0.36, 0.0, 0.0], [-0.36, 0.0, 0.30]]), [on_table, up])  # many at once
    with pytest.raises(ValueError, match="x, y and z"):
        ws.point([0.1, 0.2])


@pytest.fixture
def robot_copy(tmp_path: Path) -> Path:
    shutil.copytree(ROBOTS_DIR / "g1_inspire", tmp_path / "g1_inspire")
    shutil.copytree(ROBOTS_DIR / "hands", tmp_path / "hands")
    return tmp_path / "g1_inspire"


@pytest.mark.parametrize(("field", "value", "says"), [
    ("offset", [0.5, 0.0, 0.0], "workspace.offset: give metres"),
    ("offset", [0.0, 0.0], "workspace.offset"),
    ("per_height", [0.0, 0.0, -1.0], "workspace.per_height: z must be above -1"),
    ("per_height", [".nan", 0.0, 0.0], "workspace.per_height"),
    ("scale", 2.0, "workspace.scale: Extra inputs are not permitted"),
])
def test_a_bad_workspace_field_is_one_line_naming_the_file_and_the_field(robot_copy: Path, field, value, says):
    path = robot_copy / "robot.yaml"
    data = yaml.safe_load(path.read_text())
    data["workspace"][field] = [float("nan") if v == ".nan" else v for v in value] if isinstance(value, list) else value
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    with pytest.raises(RobotFileError) as err:
        load_robot(path, cached=False)
    msg = str(err.value)
    assert "\n" not in msg and msg.startswith(f"{path}: ") and says in msg
    res = runner.invoke(app, ["robots", "check", str(robot_copy), "--no-checksums"])
    assert res.exit_code == 1 and says in res.output


def test_the_reference_plans_ask_for_their_hand_over_spots():
    # The plans hand blocks over at spots chosen for the arms' reach: they name them as workspace positions.
    for task in HANDOVER_TASKS:
        plan = plan_path(load_task(task)).read_text()
        assert "planner.workspace_point(" in plan, task


def test_plans_ask_the_planner_for_workspace_positions():
    from humanoidgen.planning.planner import HumanoidMotionPlanner, PlanningError
    from humanoidgen.tasks.scene import build_scene

    _, env = build_scene(load_task("block_stack_single"), 0)
    planner = HumanoidMotionPlanner(env)
    p = planner.workspace_point([-0.36, 0.0, 0.045])
    assert p.tobytes() == np.array([-0.36, 0.0, 0.045]).tobytes()
    with pytest.raises(PlanningError, match="workspace_point: a workspace position has x, y and z"):
        planner.workspace_point([-0.36, 0.0])
