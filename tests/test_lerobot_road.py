"""The LeRobot road end to end (issue 37 item 4), in LeRobot's own environment (scripts/setup_lerobot.sh makes
.venv-lerobot; HGEN_LEROBOT_VENV points elsewhere): our export loads with `LeRobotDataset`, `lerobot-train`
trains LeRobot's diffusion policy on it for a step, and `hgen policy eval` runs that checkpoint closed-loop in the
task with the observations named and sized as the export holds them.

Without that environment the test fails and says how to make it; HGEN_NO_LEROBOT=1 is the explicit opt-out
(machines set up with HGEN_NO_POLICY=1 or HGEN_NO_LEROBOT=1 by scripts/setup.sh)."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from humanoidgen.episodes.dataset import EpisodeStore
from humanoidgen.episodes.lerobot_export import export_lerobot

ROOT = Path(__file__).resolve().parents[1]
VENV = Path(os.environ.get("HGEN_LEROBOT_VENV", ROOT / ".venv-lerobot"))
SIZE = (48, 64)  # (height, width) of the head camera, small: LeRobot's ResNet-18 runs on a CPU here

pytestmark = pytest.mark.skipif(os.environ.get("HGEN_NO_LEROBOT") == "1",
                                reason="HGEN_NO_LEROBOT=1: the LeRobot environment was not set up on purpose")


def _venv_bin(name: str) -> Path:
    path = VENV / "bin" / name
    if not path.exists():
        pytest.fail(f"LeRobot's environment is missing ({path}): run scripts/setup_lerobot.sh "
                    f"(or set HGEN_NO_LEROBOT=1 to leave the LeRobot road untested)")
    return path


def _run(args: list, timeout: int = 600) -> str:
    env = dict(os.environ, PYTHONPATH=str(ROOT), MUJOCO_GL="egl", WANDB_MODE="disabled", HF_HUB_OFFLINE="1")
    out = subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=timeout, env=env)
    assert out.returncode == 0, f"{args[0]} failed:\n{out.stdout[-3000:]}\n{out.stderr[-3000:]}"
    return out.stdout


@pytest.fixture(scope="module")
def export(tmp_path_factory):
    """A close_drawer store whose actions sweep the arm slowly (a stand-in for demonstrations: the road, not the
    policy's skill, is under test), exported as LeRobot writes it."""
    root = tmp_path_factory.mktemp("road")
    store = EpisodeStore(root / "store")
    names = [f"joint_{i}" for i in range(26)]
    store.create({"task": "close_drawer", "task_description": "Push the drawer shut.", "control_hz": 50.0,
                  "action_names": names, "state_names": names, "cameras": ["head"],
                  "recorder": {"every": 5, "cameras": ["head"], "width": SIZE[1], "height": SIZE[0],
                               "depth": False, "point_cloud": False}})
    rng = np.random.default_rng(0)
    for seed, t in enumerate((30, 26)):
        sweep = np.linspace(0.0, 0.3, t, dtype=np.float32)[:, None] * rng.normal(size=26).astype(np.float32)
        store.add({"seed": seed, "success": True}, {
            "action": sweep, "joint_pos": sweep, "ee_pose": rng.normal(size=(t, 14)).astype(np.float32),
            "rgb/head": rng.integers(0, 255, size=(t, *SIZE, 3), dtype=np.uint8),
            "qpos": np.zeros((t, 52)), "time": 0.1 * np.arange(t)})
    out = root / "lerobot"
    export_lerobot(store, out)
    return out


def test_export_names_what_an_evaluation_must_observe(export):
    meta = json.loads((export / "meta" / "humanoidgen.json").read_text())
    assert meta["task"] == "close_drawer" and meta["control_hz"] == 50.0
    assert meta["recorder"]["cameras"] == ["head"] and meta["recorder"]["width"] == SIZE[1]


def test_lerobot_trains_on_the_export_and_its_checkpoint_runs_in_the_task(export, tmp_path):
    python = _venv_bin("python")
    # LeRobotDataset reads every frame's features with the shapes info.json gives (video through PyAV: no
    # FFmpeg shared libraries needed).
    got = _run([python, "-c", f"""
from lerobot.datasets.lerobot_dataset import LeRobotDataset
ds = LeRobotDataset("local/road", root={str(export)!r}, video_backend="pyav")
x = ds[len(ds) - 1]
print(len(ds), ds.num_episodes, ds.fps, tuple(x["observation.images.head"].shape), tuple(x["action"].shape))
"""]).strip().splitlines()[-1]
    assert got == f"56 2 10 (3, {SIZE[0]}, {SIZE[1]}) (26,)"

    out = tmp_path / "train"
    _run([_venv_bin("lerobot-train"), "--dataset.repo_id=local/road", f"--dataset.root={export}",
          "--dataset.video_backend=pyav", "--policy.type=diffusion", "--policy.device=cpu",
          "--policy.push_to_hub=false", "--policy.down_dims=[32,64]", "--policy.num_inference_steps=2",
          "--steps=1", "--save_freq=1", "--batch_size=2", "--num_workers=0", "--wandb.enable=false",
          f"--output_dir={out}"])
    ckpt = out / "checkpoints" / "last" / "pretrained_model"
    assert (ckpt / "model.safetensors").is_file()

    report = tmp_path / "eval.json"
    text = _run([_venv_bin("hgen"), "policy", "eval", ckpt, "--episodes", "1", "--seeds", "0", "--max-steps", "6",
                 "--threads", "1", "--out", report])
    body = json.loads(report.read_text())
    assert body["task"] == "close_drawer" and body["policy"] == "lerobot-diffusion"
    (outcome,) = body["outcomes"]
    # the policy acted every step to the cut (a policy that produced nothing would end the episode at 0 steps)
    assert outcome["steps"] == 6 and outcome["scene_seed"] == 100000
    assert set(body["baselines"]) == {"random", "noop"}
    assert "lerobot-diffusion on close_drawer" in text


def test_a_lerobot_checkpoint_needs_its_export(tmp_path):
    """Evaluated without the export it was trained on: one line naming what to give."""
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app

    ckpt = tmp_path / "pretrained_model"
    ckpt.mkdir()
    (ckpt / "config.json").write_text(json.dumps({"type": "diffusion"}))
    result = CliRunner().invoke(app, ["policy", "eval", str(ckpt), "--episodes", "1"])
    assert result.exit_code == 1
    assert "--data EXPORT" in result.output
