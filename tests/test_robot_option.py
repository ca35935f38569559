"""`--robot` on every command that builds a scene (issue 36 item 3), and a dataset that says which robot it holds."""

import pytest
from typer.testing import CliRunner

from humanoidgen.cli.main import app
from humanoidgen.episodes.dataset import DatasetError, EpisodeStore

SCENE_COMMANDS = [["run"], ["collect"], ["bench"], ["render"], ["generate", "scene"], ["generate", "script"],
                  ["generate", "prompt"], ["generate", "eval"], ["policy", "eval"], ["policy", "bench"]]


@pytest.mark.parametrize("command", SCENE_COMMANDS, ids=" ".join)
def test_every_scene_command_takes_robot(command):
    result = CliRunner().invoke(app, [*command, "--help"], terminal_width=200)
    assert result.exit_code == 0, result.output
    assert "--robot" in result.output


def test_an_unknown_robot_is_one_line_and_exit_1(tmp_path):
    result = CliRunner().invoke(app, ["collect", "close_drawer", "-n", "1", "--out", str(tmp_path / "d"),
                                      "--robot", "no_such_robot"])
    assert result.exit_code == 1
    assert "no_such_robot" in result.output and "Traceback" not in result.output
    assert not (tmp_path / "d").exists()  # nothing collected, nothing created


def test_a_dataset_is_resumed_only_with_its_robot(tmp_path):
    store = EpisodeStore(tmp_path / "d")
    store.create({"task": "close_drawer", "robot": "h1_2_inspire"})
    store.create({"task": "close_drawer", "robot": "h1_2_inspire"}, resume=True)
    with pytest.raises(DatasetError, match="collected with robot 'h1_2_inspire', not 'g1_inspire'"):
        store.create({"task": "close_drawer", "robot": "g1_inspire"}, resume=True)


def test_collection_records_the_robot(tmp_path):
    from humanoidgen.episodes.collect import open_collection
    from humanoidgen.sim.layout import ROBOT

    store, _, _ = open_collection("close_drawer", 1, tmp_path / "d")
    assert store.meta()["robot"] == ROBOT.name
