"""Randomized evaluation (issue 37 item 2): `TaskEnvConfig.randomize` dresses each reset's scene from its seed,
on RoboTwin 2.0's axes, without changing the task; `hgen policy eval --randomize` reports clean and randomized
side by side."""

import json

import numpy as np
import pytest

pytest.importorskip("gymnasium")
torch = pytest.importorskip("torch")

from typer.testing import CliRunner  # noqa: E402

from humanoidgen.cli.main import app  # noqa: E402
from humanoidgen.envs.config import TaskEnvConfig  # noqa: E402
from humanoidgen.envs.task_env import HumanoidTaskEnv  # noqa: E402


def _first(randomize: bool, seed: int):
    env = HumanoidTaskEnv("close_drawer", config=TaskEnvConfig(cameras=("head",), width=64, height=48,
                                                               point_cloud=False, randomize=randomize))
    try:
        obs, info = env.reset(seed=seed)
        return obs, info
    finally:
        env.close()


def test_randomized_reset_dresses_the_scene_from_its_seed():
    clean, info_c = _first(False, 100_000)
    rand, info_r = _first(True, 100_000)
    again, info_a = _first(True, 100_000)
    other, info_o = _first(True, 100_001)
    assert "dressing" not in info_c
    d = info_r["dressing"]
    assert d["room"] is not None and d["visuals"] is not None  # background and table height, and the look
    assert d == info_a["dressing"] and d != info_o["dressing"]  # drawn from the seed: the same scene again
    assert np.array_equal(rand["rgb/head"], again["rgb/head"])
    assert not np.array_equal(rand["rgb/head"], clean["rgb/head"])  # the policy sees another picture
    # The robot starts in the same posture: only the look and the table's height under it change.
    assert np.allclose(rand["joint_pos"], clean["joint_pos"], atol=1e-6)
    assert info_r["success"] == info_c["success"] is False


def test_policy_eval_reports_clean_and_randomized_side_by_side(tmp_path):
    out = tmp_path / "eval.json"
    r = CliRunner().invoke(app, ["policy", "eval", "--policy", "noop", "close_drawer", "--episodes", "1",
                                 "--seeds", "0", "--max-steps", "3", "--randomize", "--out", str(out)])
    assert r.exit_code == 0, r.output
    assert "noop on close_drawer: success 0.0%" in r.output
    assert "noop on close_drawer (randomized scenes): success 0.0%" in r.output
    rep = json.loads(out.read_text())
    assert set(rep) == {"clean", "randomized"}
    assert rep["clean"]["scenes"] == "clean" and rep["randomized"]["scenes"] == "randomized"
    # the same scene seeds, dressed or not
    assert [o["scene_seed"] for o in rep["clean"]["outcomes"]] == [o["scene_seed"] for o in
                                                                  rep["randomized"]["outcomes"]] == [100_000]
