"""Robots as data: the H1-2's robot file and the Inspire hand's file load, give what code used to hard-code, and
bad files fail with one line naming the file and the field (`hgen robots check` exits 1)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from humanoidgen.assets.robot_files import resolve_assets_root
from humanoidgen.cli.main import app
from humanoidgen.robots import RobotFileError, default_robot, load_robot, robot_names
from humanoidgen.robots.check import check
from humanoidgen.robots.loader import ROBOTS_DIR
from humanoidgen.sim import action, layout

runner = CliRunner()


@pytest.fixture
def robot_copy(tmp_path: Path) -> Path:
    """A copy of the packaged robots folder (robot folder and hands), to break."""
    shutil.copytree(ROBOTS_DIR / "h1_2_inspire", tmp_path / "h1_2_inspire")
    shutil.copytree(ROBOTS_DIR / "hands", tmp_path / "hands")
    return tmp_path / "h1_2_inspire"


def _edit(path: Path, change) -> None:
    data = yaml.safe_load(path.read_text())
    change(data)
    path.write_text(yaml.safe_dump(data, sort_keys=False))


def test_the_default_robot_is_the_h1_2_with_inspire_hands_and_a_26_d_action():
    r = default_robot()
    assert "h1_2_inspire" in robot_names() and r.name == "h1_2_inspire"
    assert load_robot("h1_2_inspire") is r  # cached: one read per process
    assert len(r.action_joints) == action.ACTION_DIM == 26
    assert r.action_joints[:7] == layout.ARM_JOINTS["left"] and r.action_joints[20:] == layout.HAND_JOINTS["right"]
    assert action.ARM_SLICE["right"] == slice(7, 14) and action.HAND_SLICE["left"] == slice(14, 20)
    assert layout.FINGERTIP_BODY["right"]["thumb"] == r.hand_link("right", "thumb_distal")
    # the left hand's points mirror the right's across the palm; a y of 0 stays +0.0
    left, right = r.hand.points("left"), r.hand.points("right")
    assert left["grasp_point_base_left_hand"][1] == -right["grasp_point_base_right_hand"][1] < 0
    assert str(left["base_left_hand"][1]) == "0.0"


def test_the_packaged_robot_fits_its_model_files():
    assert check(ROBOTS_DIR / "h1_2_inspire", resolve_assets_root()) == []


def test_a_schema_error_names_the_file_and_the_field(robot_copy: Path):
    _edit(robot_copy / "robot.yaml", lambda d: d["arms"]["left"][3].update(kp=-1.0))
    with pytest.raises(RobotFileError) as err:
        load_robot(robot_copy)
    msg = str(err.value)
    assert "\n" not in msg and str(robot_copy / "robot.yaml") in msg and "arms.left.3.kp" in msg


def test_a_hand_without_annotations_is_refused(robot_copy: Path):
    _edit(robot_copy.parent / "hands" / "inspire.yaml", lambda d: d.update(points=[]))
    problems = check(robot_copy)
    assert len(problems) == 1 and "inspire.yaml" in problems[0] and "points" in problems[0]


def test_an_annotation_without_a_description_is_refused(robot_copy: Path):
    _edit(robot_copy.parent / "hands" / "inspire.yaml", lambda d: d["axes"][0].pop("description"))
    problems = check(robot_copy)
    assert len(problems) == 1 and "axes.0.description" in problems[0]


def test_a_mount_the_hand_annotations_do_not_assume_is_refused(robot_copy: Path):
    _edit(robot_copy / "robot.yaml", lambda d: d["hands"]["hand_base"].update(pos=[0.06, 0.0, 0.0]))
    problems = check(robot_copy)
    assert len(problems) == 1 and "hands.hand_base" in problems[0]


def test_a_missing_joint_and_an_unwelded_joint_are_named(robot_copy: Path):
    def change(d):
        d["arms"]["left"][2]["joint"] = "left_shoulder_twist_joint"
        d["weld"].remove("torso_joint")

    _edit(robot_copy / "robot.yaml", change)
    problems = check(robot_copy, resolve_assets_root(), checksums=False)
    assert any("arms.left.2.joint: no joint 'left_shoulder_twist_joint'" in p for p in problems), problems
    assert any("weld: joint 'torso_joint'" in p for p in problems), problems
    assert all(p.startswith(str(robot_copy / "robot.yaml")) and "\n" not in p for p in problems)


def test_a_checksum_mismatch_is_named(robot_copy: Path):
    sums = robot_copy / "h1_2.sha256"
    lines = sums.read_text().splitlines()
    k = next(i for i, line in enumerate(lines) if line.endswith("./h1_2.xml"))
    lines[k] = "0" * 64 + lines[k][64:]
    sums.write_text("\n".join(lines) + "\n")
    problems = check(robot_copy, resolve_assets_root())
    assert problems == [f"{robot_copy / 'robot.yaml'}: model.checksums: h1_2.xml does not match its sha256 "
                        "(a checksum mismatch)"]


def test_hgen_robots_check_exits_1_with_one_line_per_problem(robot_copy: Path):
    _edit(robot_copy / "robot.yaml", lambda d: d["stand"].update(root_body="hips"))
    res = runner.invoke(app, ["robots", "check", str(robot_copy), "--assets", str(resolve_assets_root()),
                              "--no-checksums"])
    assert res.exit_code == 1
    assert "stand.root_body: no body 'hips'" in res.output
    res = runner.invoke(app, ["robots", "check", str(ROBOTS_DIR / "h1_2_inspire"), "--no-checksums"])
    assert res.exit_code == 0, res.output


def test_hgen_robots_list_and_show():
    res = runner.invoke(app, ["robots", "list"])
    assert res.exit_code == 0 and "* h1_2_inspire" in res.output
    res = runner.invoke(app, ["robots", "show", "h1_2_inspire"])
    assert res.exit_code == 0 and "14-19 left hand" in res.output and "head on torso_link" in res.output


def test_a_robot_outside_the_package_uses_the_packaged_hand(tmp_path: Path):
    shutil.copytree(ROBOTS_DIR / "h1_2_inspire", tmp_path / "mine")
    _edit(tmp_path / "mine" / "robot.yaml", lambda d: d.update(name="mine"))
    r = load_robot(tmp_path / "mine")
    assert r.name == "mine" and r.hand.path == ROBOTS_DIR / "hands" / "inspire.yaml"
    _edit(tmp_path / "mine" / "robot.yaml", lambda d: d["hands"].update(type="shadow"))
    assert "hands.type: no hand file" in check(tmp_path / "mine" / "robot.yaml")[0]
