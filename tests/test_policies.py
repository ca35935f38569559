"""DP and DP3: training from a real (tiny) export lowers the loss, checkpoints reload to identical actions,
an interrupted run resumes where it stopped, evaluation runs episodes judged by the task's predicates, and bad
input gets one line and a non-zero exit."""

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

torch = pytest.importorskip("torch")

from typer.testing import CliRunner  # noqa: E402

from humanoidgen.cli.main import app  # noqa: E402
from humanoidgen.episodes.dataset import EpisodeStore, export_zarr  # noqa: E402
from humanoidgen.episodes.recorder import RecorderConfig  # noqa: E402
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode  # noqa: E402
from humanoidgen.policies import checkpoint as ck  # noqa: E402
from humanoidgen.policies.data import DataError, read_demos, sequence_index  # noqa: E402
from humanoidgen.policies.eval import EvalError, evaluate, with_action_steps  # noqa: E402
from humanoidgen.policies.registry import policy_type  # noqa: E402
from humanoidgen.policies.train import train  # noqa: E402
from humanoidgen.sim.action import ARM_SLICE  # noqa: E402
from bench_scripts import load_bench  # noqa: E402

SMALL_REC = dict(every=5, cameras=("head",), width=64, height=48, point_cloud=True, num_points=128)
TINY = {"unet": {"down_dims": [32, 64], "diffusion_step_embed_dim": 32}, "horizon": 8,
        "train": {"batch_size": 32, "lr": 1e-3, "lr_warmup_steps": 0, "checkpoint_every": 2, "save_every": 1}}
TINY_DP3 = {**TINY, "num_points": 64, "encoder_output_dim": 32, "point_mlp": [32, 64], "state_mlp": [32, 32]}
TINY_DP = {**TINY, "image_size": [24, 32], "crop_size": [20, 28]}


@pytest.fixture(scope="module", autouse=True)
def _threads():
    before = torch.get_num_threads()
    torch.set_num_threads(1)  # on a shared 2-core machine a second thread makes it ~10x slower
    yield
    torch.set_num_threads(before)


@pytest.fixture(scope="module")
def demos_zarr(tmp_path_factory):
    """Two close_drawer demonstrations recorded as `hgen collect` records them (small pictures), exported."""
    root = tmp_path_factory.mktemp("demos")
    rec = RecorderConfig(**SMALL_REC)
    store = EpisodeStore(root / "store")
    store.create({"task": "close_drawer", "control_hz": 50.0, "recorder": {**rec.__dict__}})
    for seed in (0, 1):
        result, arrays = run_task_episode(EpisodeRequest("close_drawer", seed, recorder=rec))
        assert result.success
        store.add({"seed": seed, "success": True}, arrays)
    export_zarr(store, root / "cd.zarr")
    return root / "cd.zarr"


def _with(over, **train):
    return {**over, "train": {**over["train"], **train}}


def test_sequence_index_pads_like_dp():
    idx = sequence_index(np.array([5, 9]), horizon=4, n_obs_steps=2, n_action_steps=2)
    assert idx[0].tolist() == [0, 0, 1, 2]  # the first frame repeated before the episode
    assert idx[idx[:, 0] < 5][-1].tolist() == [2, 3, 4, 4]  # the last frame repeated after it, never crossing
    assert idx.min() >= 0 and all(((r < 5).all() or (r >= 5).all()) for r in idx)
    # DP's count per episode: length + (n_obs_steps - 1) + (n_action_steps - 1) - horizon + 1
    assert len(idx) == (5 + 1 + 1 - 4 + 1) + (4 + 1 + 1 - 4 + 1)


def test_config_is_validated():
    with pytest.raises(ValueError, match="exceeds horizon"):
        policy_type("dp3").config({"n_action_steps": 8})  # 3 obs steps + 8 actions do not fit in 8
    with pytest.raises(ValueError, match="n_groups"):
        policy_type("dp").config({"unet": {"down_dims": [30, 60]}})
    with pytest.raises(ValueError, match="unknown policy"):
        policy_type("act")


def test_dp3_tiny_training_lowers_the_loss_and_reloads_to_identical_actions(demos_zarr, tmp_path):
    run = tmp_path / "dp3"
    result = train("dp3", demos_zarr, run, _with(TINY_DP3, epochs=12), device="cpu", progress=False)
    assert result.epochs == 12 and len(result.losses) == 12
    assert np.mean(result.losses[-3:]) < 0.7 * np.mean(result.losses[:2]), result.losses
    demos = read_demos(demos_zarr, ("state", "point_cloud"))
    obs = {"state": torch.as_tensor(demos.arrays["state"][None, :3]),
           "point_cloud": torch.as_tensor(demos.arrays["point_cloud"][None, :3])}
    a, meta = ck.load_policy(ck.run_checkpoints(run)[-1])
    b, _ = ck.load_policy(ck.run_checkpoints(run)[-1])
    assert meta["task"] == "close_drawer" and meta["recorder"]["every"] == 5
    out_a = a.predict_action(obs, generator=torch.Generator().manual_seed(7))["action"]
    out_b = b.predict_action(obs, generator=torch.Generator().manual_seed(7))["action"]
    assert out_a.shape == (1, 6, 26)
    assert torch.equal(out_a, out_b)
    other = a.predict_action(obs, generator=torch.Generator().manual_seed(8))["action"]
    assert not torch.equal(out_a, other)  # sampling noise matters, so equality above is no accident
    # Executing fewer of the predicted actions (eval --action-steps): the same prediction, its first 3.
    fewer = with_action_steps(b, 3).predict_action(obs, generator=torch.Generator().manual_seed(7))["action"]
    assert torch.equal(fewer, out_a[:, :3])
    with pytest.raises(EvalError, match="action-steps must be in 1..6"):
        with_action_steps(b, 7)


def test_relative_actions_are_denoised_about_the_state_and_executed_as_joint_targets(demos_zarr, tmp_path):
    run = tmp_path / "dp3_rel"
    result = train("dp3", demos_zarr, run, {**_with(TINY_DP3, epochs=6), "action_frame": "relative"}, device="cpu",
                   progress=False)
    assert np.mean(result.losses[-2:]) < np.mean(result.losses[:2]), result.losses
    model, _ = ck.load_policy(ck.run_checkpoints(run)[-1])
    demos = read_demos(demos_zarr, ("state", "point_cloud"))
    action, state = demos.arrays["action"], demos.arrays["state"]
    # The random baseline still draws within the recorded targets' range; the U-Net's range is the smaller one
    # of the targets less the state (the arm's motion within a horizon).
    from humanoidgen.policies.baseline_eval import demo_range

    rng = demo_range(model, "demos")
    np.testing.assert_allclose(rng.low, action.min(axis=0), atol=1e-5)
    np.testing.assert_allclose(rng.high, action.max(axis=0), atol=1e-5)
    span = lambda key: 2.0 / getattr(model.normalizer, f"{key}__scale").numpy()  # noqa: E731
    arm = ARM_SLICE["left"]  # close_drawer's acting arm (the fingers' targets lead their state by up to a closing)
    assert (span("action")[arm] < 0.7 * span("target")[arm]).all(), (span("action")[arm], span("target")[arm])
    # Executed targets are the denoised offsets plus the last observed state: shifting the observed state by d
    # (the denoiser made blind to it) shifts every target by d.
    n = model.cfg.n_obs_steps
    model.global_cond = lambda obs: torch.zeros(1, model.feature_dim() * n)
    obs = {"state": torch.as_tensor(state[None, 10:10 + n]),
           "point_cloud": torch.as_tensor(demos.arrays["point_cloud"][None, 10:10 + n])}
    d = torch.linspace(-0.1, 0.1, state.shape[1])
    moved = {**obs, "state": obs["state"] + d}
    a = model.predict_action(obs, generator=torch.Generator().manual_seed(3))["action"]
    b = model.predict_action(moved, generator=torch.Generator().manual_seed(3))["action"]
    torch.testing.assert_close(b - a, d.expand_as(a), atol=1e-5, rtol=0)
    with pytest.raises(ValueError, match="one joint state per action"):
        policy_type("dp3").config({"action_frame": "relative", "state_dim": 20})


def test_hand_features_are_position_and_two_rotation_columns_whatever_the_quaternion_sign():
    from humanoidgen.policies.hands import hand_features
    from humanoidgen.sim.geometry import quat_to_mat

    rng = np.random.default_rng(0)
    q = rng.normal(size=(6, 2, 4))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    p = rng.normal(size=(6, 2, 3))
    ee = np.concatenate([p[:, 0], q[:, 0], p[:, 1], q[:, 1]], axis=-1)
    f = hand_features(ee)
    assert f.shape == (6, 18) and f.dtype == np.float32
    for i in range(6):
        for h in range(2):
            R = quat_to_mat(q[i, h])
            np.testing.assert_allclose(f[i, 9 * h: 9 * h + 3], p[i, h], atol=1e-6)
            np.testing.assert_allclose(f[i, 9 * h + 3: 9 * h + 9], np.r_[R[:, 0], R[:, 1]], atol=1e-6)
    flipped = ee.copy()
    flipped[:, 3:7] *= -1  # the same orientation
    np.testing.assert_allclose(hand_features(flipped), f, atol=1e-6)
    with pytest.raises(ValueError, match="not 14"):
        hand_features(ee[:, :7])
    with pytest.raises(ValueError, match="quaternion that is zero"):
        hand_features(np.where(np.arange(14) >= 3, 0.0, 1.0)[None])
    with pytest.raises(ValueError, match="not finite"):
        hand_features(np.where(np.arange(14) == 0, np.nan, ee[0]))


def test_a_policy_observing_the_hands_reads_their_poses_in_training_and_in_the_env(demos_zarr, tmp_path):
    run = tmp_path / "dp3_hands"
    over = {**_with(TINY_DP3, epochs=3), "action_frame": "relative", "observe_hands": True}
    result = train("dp3", demos_zarr, run, over, device="cpu", progress=False)
    assert np.isfinite(result.losses).all()
    model, _ = ck.load_policy(ck.run_checkpoints(run)[-1])
    assert model.obs_keys == ("state", "point_cloud", "hands") and model.cfg.observe_hands
    assert model.state[0].in_features == 26 + 18  # the state MLP reads the joints and the hands
    demos = read_demos(demos_zarr, ("state", "point_cloud", "hands"))
    n = model.cfg.n_obs_steps
    obs = {"state": torch.as_tensor(demos.arrays["state"][None, 10:10 + n]),
           "point_cloud": torch.as_tensor(demos.arrays["point_cloud"][None, 10:10 + n]),
           "hands": torch.as_tensor(hand_features_of(demos.arrays["hands"][10:10 + n])[None])}
    a = model.predict_action(obs, generator=torch.Generator().manual_seed(3))["action"]
    moved = {**obs, "hands": obs["hands"] + 0.05}  # the hands elsewhere, nothing else changed
    b = model.predict_action(moved, generator=torch.Generator().manual_seed(3))["action"]
    assert not torch.allclose(a, b)
    # In the env: the rollout hands the policy the env's ee_pose as the same features (a closed-loop episode).
    report = evaluate(run, "close_drawer", episodes=1, seeds=(0,), device="cpu", progress=False, max_steps=2,
                      baselines=False)
    assert report.outcomes and all(o.steps == 2 for o in report.outcomes)  # one a kept checkpoint
    # An export without the hands' poses: one line that says how to get them.
    bare = tmp_path / "bare.zarr"
    shutil.copytree(demos_zarr, bare)
    shutil.rmtree(bare / "data" / "ee_pose")
    with pytest.raises(DataError, match="no data/ee_pose.*export the dataset again"):
        train("dp3", bare, tmp_path / "bare_run", over, device="cpu", progress=False)


def test_a_temporally_ensembled_evaluation_predicts_at_every_action_and_says_so(demos_zarr, tmp_path, monkeypatch):
    from humanoidgen.policies.diffusion import DiffusionPolicy
    from humanoidgen.policies.study_rows import rows_from_eval

    run = tmp_path / "dp3_ens"
    train("dp3", demos_zarr, run, _with(TINY_DP3, epochs=2), device="cpu", progress=False)
    calls = []
    real = DiffusionPolicy.predict_action

    def counted(self, obs, generator=None):
        calls.append(1)
        return real(self, obs, generator=generator)

    monkeypatch.setattr(DiffusionPolicy, "predict_action", counted)
    report = evaluate(run, "close_drawer", episodes=1, seeds=(0,), device="cpu", progress=False, max_steps=5,
                      baselines=False, temporal_ensemble=0.1)
    steps = sum(o.steps for o in report.outcomes)
    assert len(report.checkpoints) == 1 and steps == 5 and len(calls) == steps  # one prediction an action
    assert report.info == {"temporal_ensemble": 0.1}
    rows = rows_from_eval(report.to_dict(), 2, "fast", 2)  # a study row says how it was executed
    assert rows[0]["temporal_ensemble"] == 0.1
    calls.clear()
    chunked = evaluate(run, "close_drawer", episodes=1, seeds=(0,), device="cpu", progress=False, max_steps=5,
                       baselines=False)
    assert len(calls) < sum(o.steps for o in chunked.outcomes) and chunked.info == {}


def hand_features_of(ee_pose):
    from humanoidgen.policies.hands import hand_features

    return hand_features(ee_pose)


def test_interrupted_training_resumes_where_it_stopped(demos_zarr, tmp_path):
    whole = train("dp3", demos_zarr, tmp_path / "whole", _with(TINY_DP3, epochs=3), device="cpu", progress=False)
    first = train("dp3", demos_zarr, tmp_path / "parts", _with(TINY_DP3, epochs=2), device="cpu", progress=False)
    assert first.epochs == 2
    with pytest.raises(ck.CheckpointError, match="--resume"):
        train("dp3", demos_zarr, tmp_path / "parts", _with(TINY_DP3, epochs=3), device="cpu", progress=False)
    rest = train("dp3", demos_zarr, tmp_path / "parts", _with(TINY_DP3, epochs=3), device="cpu", resume=True,
                 progress=False)
    assert rest.epochs == 3 and rest.new_epochs == 1
    # The cosine schedule differs (its length was 2 epochs, then 3), so only the first two epochs match.
    np.testing.assert_allclose(rest.losses[:2], first.losses, rtol=1e-6)
    assert len(rest.losses) == len(whole.losses)


def test_dp_trains_and_eval_runs_episodes_judged_by_the_predicates(demos_zarr, tmp_path):
    run = tmp_path / "dp"
    result = train("dp", demos_zarr, run, _with(TINY_DP, epochs=2), device="cpu", progress=False)
    assert np.isfinite(result.losses).all()
    report = evaluate(run, "close_drawer", episodes=1, seeds=(0, 1), device="cpu", progress=False, max_steps=4)
    assert len(report.outcomes) == 2 and {o.seed for o in report.outcomes} == {0, 1}
    assert all(o.steps == 4 and not o.success for o in report.outcomes)  # 4 actions cannot close the drawer
    assert report.success_mean == 0.0 and report.outcomes[0].scene_seed == 100_000
    assert report.outcomes[1].scene_seed == 101_000
    assert all("openness" in o.final for o in report.outcomes)  # where each episode ended, by the predicates
    # The baselines beside it, on the same scenes and episode length; random within the demonstrations' range.
    assert set(report.baselines) == {"random", "noop"}
    for b in report.baselines.values():
        assert [(o.scene_seed, o.steps) for o in b.outcomes] == [(o.scene_seed, o.steps) for o in report.outcomes]
    demo = read_demos(demos_zarr, ("state",)).arrays["action"][:]
    got = report.baselines["random"].info["action_range"]
    assert got["source"].startswith("demonstrations")
    np.testing.assert_allclose(got["low"], demo.min(axis=0), atol=1e-4)
    np.testing.assert_allclose(got["high"], demo.max(axis=0), atol=1e-4)
    assert "baselines" in report.to_dict() and "baselines on the same 2 scenes" in report.baseline_line()


def test_bench_recipes_are_valid_configs():
    bench = load_bench("policies")
    for recipe in bench.RECIPES.values():
        for name, over in recipe.items():
            policy_type(name).config(over)
    # Results say which code produced them: the checkout's commit, marked when tracked files differ from it.
    import re

    assert re.fullmatch(r"[0-9a-f]{7,}(\+changes)?", bench.commit())


def test_bad_input_is_one_line_and_exit_1(demos_zarr, tmp_path):
    runner = CliRunner()
    no_pc = tmp_path / "no_pc.zarr"
    shutil.copytree(demos_zarr, no_pc)
    shutil.rmtree(no_pc / "data" / "point_cloud")
    with pytest.raises(DataError, match="point_cloud"):
        read_demos(no_pc, ("state", "point_cloud"))
    r = runner.invoke(app, ["policy", "train", "--policy", "dp3", "--data", str(no_pc), "--out",
                            str(tmp_path / "x"), "--epochs", "1"])
    assert r.exit_code == 1 and "no data/point_cloud" in r.output and len(r.output.strip().splitlines()) == 1

    run = tmp_path / "small"
    r = runner.invoke(app, ["policy", "train", "--policy", "dp3", "--data", str(demos_zarr), "--out", str(run),
                            "--epochs", "1", "--config", json.dumps(TINY_DP3), "--device", "cpu"])
    assert r.exit_code == 0, r.output
    r = runner.invoke(app, ["policy", "eval", str(run), "--task", "open_box_easy", "--episodes", "1"])
    assert r.exit_code == 1 and "trained on task 'close_drawer', not 'open_box_easy'" in r.output
    assert len(r.output.strip().splitlines()) == 1
    r = runner.invoke(app, ["policy", "eval", str(run), "--episodes", "1", "--temporal-ensemble", "0.1",
                            "--action-steps", "2"])
    assert r.exit_code == 1 and "not with --action-steps" in r.output and len(r.output.strip().splitlines()) == 1
    r = runner.invoke(app, ["policy", "eval", "--policy", "random", "close_drawer", "--temporal-ensemble", "0.1"])
    assert r.exit_code == 1 and "baselines (--policy) have none" in r.output
    r = runner.invoke(app, ["policy", "train", "--policy", "dp3", "--data", str(tmp_path / "missing.zarr"),
                            "--out", str(tmp_path / "y")])
    assert r.exit_code == 1 and "no training data" in r.output
    r = runner.invoke(app, ["policy", "train", "--policy", "dp3", "--data", str(demos_zarr), "--out",
                            str(tmp_path / "z"), "--config", '{"n_action_steps": 9}'])
    assert r.exit_code == 1 and "exceeds horizon" in r.output


def test_export_says_what_training_needs_and_episodes_picks_the_first(demos_zarr):
    d = read_demos(demos_zarr, ("state", "point_cloud"))
    assert d.attrs["task"] == "close_drawer" and d.attrs["camera"] == "head"
    assert d.attrs["recorder"]["every"] == 5 and d.n_episodes == 2
    one = read_demos(demos_zarr, ("state", "img"), episodes=1)
    assert one.n_episodes == 1 and one.n_frames == d.episode_ends[0] and len(one.arrays["state"]) == one.n_frames
    with pytest.raises(DataError, match="fewer than the 3"):
        read_demos(demos_zarr, ("state",), episodes=3)


def test_study_collects_in_a_child_so_training_can_follow(tmp_path):
    """`hgen policy bench` collects missing data and then trains in one process. Collecting in-process loaded
    Mesa's LLVM for the renderer, and importing diffusers afterwards (torch's triton brings its own LLVM)
    killed the process with a segfault; the collection now runs in a child process."""
    import subprocess
    import sys

    code = ("from pathlib import Path; from humanoidgen.policies.bench import StudyConfig, ensure_data; "
            f"out = ensure_data('close_drawer', 1, StudyConfig(data_root=Path({str(tmp_path)!r})), progress=False); "
            "import diffusers; from humanoidgen.policies.data import read_demos; "
            "print('episodes', read_demos(out, ('state', 'action', 'point_cloud')).n_episodes)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "episodes 1" in r.stdout
    # Randomized training data: its own folder, each episode dressed from its seed (and stored so).
    code = ("from pathlib import Path; from humanoidgen.policies.bench import StudyConfig, ensure_data; "
            f"print(ensure_data('close_drawer', 1, StudyConfig(data_root=Path({str(tmp_path)!r})), progress=False, "
            "scenes='randomized'))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip().endswith("close_drawer_randomized.zarr")
    records = [json.loads(line) for line in (tmp_path / "close_drawer_randomized" / "index.jsonl").read_text().splitlines()
               if line.strip()]
    kept = [rec for rec in records if rec.get("success")]
    assert kept and all(rec["dressing"]["room"] and rec["dressing"]["visuals"] for rec in kept)
    assert "dressing" not in json.loads((tmp_path / "close_drawer" / "index.jsonl").read_text().splitlines()[0])


def test_a_study_asked_for_more_epochs_resumes_a_finished_run(demos_zarr, tmp_path):
    from humanoidgen.policies.bench import _finished

    run = tmp_path / "run"
    assert not _finished(run)
    train("dp3", demos_zarr, run, _with(TINY_DP3, epochs=2), device="cpu", progress=False)
    assert _finished(run) and _finished(run, 2) and _finished(run, None)
    assert not _finished(run, 3)  # asked for 3 epochs: it trains one more (it used to be evaluated at 2)


def test_a_cpu_gets_the_cpu_sized_recipe_unless_paper_is_asked_for(demos_zarr, tmp_path):
    """`hgen policy train --policy dp3` with no recipe on a CPU trains `fast` (and says so in one line), not the
    paper's 259 M-parameter GPU recipe; `--recipe paper` forces the paper's; a GPU gets the paper's."""
    from humanoidgen.cli.policy_cmd import _with_recipe
    from humanoidgen.policies.recipes import default_recipe

    assert default_recipe("cpu") == "fast" and default_recipe("cuda") == "paper" and default_recipe("cuda:1") == "paper"
    run = tmp_path / "default"
    r = CliRunner().invoke(app, ["policy", "train", "--policy", "dp3", "--data", str(demos_zarr), "--out", str(run),
                                 "--device", "cpu", "--epochs", "1", "--config", '{"num_points": 64}'])
    assert r.exit_code == 0, r.output
    lines = [line for line in r.output.splitlines() if "recipe" in line]
    assert len(lines) == 1 and "no CUDA device: the CPU-sized 'fast' recipe" in lines[0]
    assert "--recipe paper" in lines[0] and "M parameters" in lines[0]
    # and, before the first step, what the run will take here, from one step timed on its own data
    [estimate] = [line for line in r.output.splitlines() if "optimizer steps at about" in line]
    steps = int(estimate.split()[0])
    assert r.output.index("recipe") < r.output.index(estimate) and steps >= 1 and estimate.endswith(("min", "h", "days"))
    cfg = json.loads((run / "config.json").read_text())
    assert cfg["train"]["batch_size"] == 64 and cfg["unet"]["down_dims"] == [64, 128, 256]
    assert cfg["n_action_steps"] == 4 and cfg["num_points"] == 64 and cfg["train"]["epochs"] == 1  # options win
    # Resumed with only --epochs, it keeps its recipe (the fast settings are not compared against the paper's).
    r = CliRunner().invoke(app, ["policy", "train", "--policy", "dp3", "--data", str(demos_zarr), "--out", str(run),
                                 "--device", "cpu", "--epochs", "2", "--resume"])
    assert r.exit_code == 0, r.output
    assert json.loads((run / "config.json").read_text())["train"]["epochs"] == 2
    paper, line = _with_recipe("dp3", "paper", {}, "cpu", False)  # forced: the configs' defaults, said nothing
    assert policy_type("dp3").config(paper).train.batch_size == 256 and line == ""
    assert policy_type("dp3").config(paper).unet.down_dims == (512, 1024, 2048)


def test_randomized_evaluation_reports_its_scenes_and_the_study_rows_say_which(demos_zarr, tmp_path):
    """`evaluate(..., randomize=True)` runs the policy and its baselines on the same scene seeds dressed from
    their seeds (issue 37 item 2); the study gives each condition a row and plots randomized dashed."""
    from humanoidgen.policies.bench import format_row, plot

    run = tmp_path / "dp3"
    train("dp3", demos_zarr, run, _with(TINY_DP3, epochs=1), device="cpu", progress=False)
    report = evaluate(run, "close_drawer", episodes=1, seeds=(0,), device="cpu", progress=False, max_steps=2,
                      randomize=True)
    assert report.scenes == "randomized" and report.to_dict()["scenes"] == "randomized"
    assert "(randomized scenes)" in report.summary()
    assert all(b.scenes == "randomized" for b in report.baselines.values())
    assert [o.scene_seed for o in report.outcomes] == [100_000]
    rows = [{"task": "close_drawer", "policy": "dp3", "demos": 2, "scenes": s, "success_mean": m,
             "success_std": 0.0, "train_seconds": None, "final_loss": 0.1, "baseline_random": 0.0} for s, m in
            (("clean", 0.5), ("randomized", 0.1))]
    assert "randomized" in format_row(rows[1]) and "clean" in format_row(rows[0])
    assert plot(rows, tmp_path / "study.png") and (tmp_path / "study.png").stat().st_size > 0


def test_a_saved_evaluation_becomes_study_rows_for_a_table_and_plot(demos_zarr, tmp_path, monkeypatch):
    """A run trained and evaluated by hand (`hgen policy eval --randomize --out`) joins the study's table:
    `rows_from_eval` makes one row per scenes with its baselines, `bench/policies.py --from-eval` writes them."""
    import sys

    from humanoidgen.policies.study_rows import rows_from_eval

    run = tmp_path / "dp3"
    train("dp3", demos_zarr, run, _with(TINY_DP3, epochs=1), device="cpu", progress=False)
    reports = [evaluate(run, "close_drawer", episodes=1, seeds=(0,), device="cpu", progress=False, max_steps=2,
                        randomize=r) for r in (False, True)]
    saved = {r.scenes: r.to_dict() for r in reports}  # the file `policy eval --randomize --out` writes
    rows = rows_from_eval(json.loads(json.dumps(saved)), demos=2, recipe="fast", epochs=1, train_scenes="randomized")
    assert [(r["scenes"], r["train_scenes"], r["demos"], r["epochs"]) for r in rows] == [
        ("clean", "randomized", 2, 1), ("randomized", "randomized", 2, 1)]
    for row, report in zip(rows, reports):
        assert row["success_mean"] == report.success_mean and row["checkpoint"] == report.to_dict()["checkpoints"][0]
        assert set(row["baselines"]) == {"random", "noop"} and row["baseline_noop"] == 0.0
        assert [e["scene_seed"] for e in row["episodes"]] == [100_000] and len(row["success_ci95"]) == 2
    assert rows_from_eval(saved["clean"], 2, "fast", 1)[0]["train_scenes"] == "clean"  # one scenes' report
    with pytest.raises(ValueError, match="not an evaluation report"):
        rows_from_eval({"rows": []}, 2, "fast", 1)

    bench = load_bench("policies")
    monkeypatch.setattr(bench, "ROOT", tmp_path)
    (tmp_path / "results").mkdir()
    report_file = tmp_path / "eval.json"
    report_file.write_text(json.dumps(saved))
    argv = ["policies.py", "--from-eval", str(report_file), "--recipe", "fast", "--epochs", "7", "--demos", "2",
            "--train-scenes", "randomized", "--name", "hand"]
    monkeypatch.setattr(sys, "argv", argv)
    assert bench.main() == 0
    written = json.loads((tmp_path / "results" / "policies_hand.json").read_text())
    assert [(r["scenes"], r["epochs"]) for r in written["rows"]] == [("clean", 1), ("randomized", 1)]  # its own
    assert {r["action_frame"] for r in written["rows"]} == {"absolute"}  # as the checkpoint was trained
    assert {r["num_points"] for r in written["rows"]} == {TINY_DP3["num_points"]}
    assert {r["observe_hands"] for r in written["rows"]} == {False}
    assert {r["point_cloud_near_hands"] for r in written["rows"]} == {0.0}
    assert written["settings"]["commit"] and written["settings"]["machine"]
    assert (tmp_path / "results" / "policies_hand.png").stat().st_size > 0
    monkeypatch.setattr(sys, "argv", argv[:-4] + ["--train-scenes", "clean,randomized", "--name", "bad"])
    assert bench.main() == 2  # one training per report
    # The same checkpoint evaluated on another seed beside it (a second process): the reports pool into one row
    # per scenes; the same seeds twice are refused.
    other = tmp_path / "eval_seed1.json"
    other.write_text(json.dumps(evaluate(run, "close_drawer", episodes=1, seeds=(1,), device="cpu", progress=False,
                                         max_steps=2).to_dict()))
    monkeypatch.setattr(sys, "argv", ["policies.py", "--from-eval", f"{report_file},{other}", *argv[3:-1], "pooled"])
    assert bench.main() == 0
    pooled = json.loads((tmp_path / "results" / "policies_pooled.json").read_text())["rows"]
    clean = next(r for r in pooled if r["scenes"] == "clean")
    assert [e["scene_seed"] for e in clean["episodes"]] == [100_000, 101_000] and len(clean["rates"]) == 2
    assert len(clean["baselines"]["random"]["rates"]) == 2 and len(pooled) == 2
    monkeypatch.setattr(sys, "argv", ["policies.py", "--from-eval", f"{report_file},{report_file}", *argv[3:-1], "x"])
    assert bench.main() == 2


def test_randomized_training_data_is_drawn_as_randomized_evaluation_draws_its_scenes():
    """The study's randomized demonstrations are dressed from each episode's seed exactly as `randomize`d
    evaluation dresses a scene of that seed: a room (background, clutter, the table's height) and a look
    (textures, lighting, camera jitter, distractors); clean data is not dressed."""
    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.policies.bench import collect_dressing
    from humanoidgen.scenes.dressing import SceneDressing, episode_dressing

    env = HumanoidTaskEnv("open_box_easy", config=TaskEnvConfig(randomize=True, cameras=(), point_cloud=False))
    heights = set()
    for seed in (0, 7, 100_000):
        collected = episode_dressing(**collect_dressing("randomized"), seed=seed)
        assert SceneDressing.from_dict(collected) == env._dressing(seed)
        drawn = SceneDressing.from_dict(collected)
        assert drawn.room is not None and drawn.visuals is not None and drawn.visuals.distractors
        heights.add(round(drawn.surface_height, 4))
    assert len(heights) > 1  # the table's height is drawn too
    assert episode_dressing(**collect_dressing("clean"), seed=3) is None


def test_a_run_says_what_it_will_take_and_timing_it_changes_nothing(demos_zarr, tmp_path):
    """The step timed before training (for the start line's estimate) leaves the run as it was: the same losses
    and weights as a run that timed nothing; the line scales the estimate to minutes, hours or days."""
    from humanoidgen.cli.policy_cmd import _start_line

    said = []
    timed = train("dp3", demos_zarr, tmp_path / "timed", _with(TINY_DP3, epochs=1), device="cpu", progress=False,
                  on_start=lambda steps, per_step: said.append((steps, per_step)))
    plain = train("dp3", demos_zarr, tmp_path / "plain", _with(TINY_DP3, epochs=1), device="cpu", progress=False)
    assert timed.losses == plain.losses
    [(steps, per_step)] = said
    assert steps == timed.steps_per_epoch and per_step > 0
    a = torch.load(tmp_path / "timed" / "checkpoints" / "epoch_0001.pt", weights_only=False)["weights"]
    b = torch.load(tmp_path / "plain" / "checkpoints" / "epoch_0001.pt", weights_only=False)["weights"]
    assert all(torch.equal(a[k], b[k]) for k in a)
    assert _start_line("", 2040, 0.4).endswith("about 14 min")
    assert _start_line("fast", 67_000, 28.0).splitlines() == ["fast", "67000 optimizer steps at about 28.00 s a step "
                                                                      "here: about 21.7 days"]
    assert _start_line("", 9000, 2.0).endswith("about 5.0 h")
    assert _start_line("", 0, 2.0) == "0 optimizer steps at about 2.00 s a step here: about 0 min"


def test_a_reset_can_replay_a_recorded_room_and_look():
    """`reset(seed=s, options={"dressing": record["dressing"]})` builds the room and look an episode was collected
    in, whatever the env's own config says (`hgen dataset perturb` re-records randomized demonstrations so)."""
    import json

    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.policies.bench import collect_dressing
    from humanoidgen.scenes.dressing import episode_dressing

    recorded = json.loads(json.dumps(episode_dressing(**collect_dressing("randomized"), seed=5)))  # as an index stores it
    clean = HumanoidTaskEnv("close_drawer", config=TaskEnvConfig(cameras=(), point_cloud=False))
    dressed = HumanoidTaskEnv("close_drawer", config=TaskEnvConfig(randomize=True, cameras=(), point_cloud=False))
    _, info = clean.reset(seed=5, options={"dressing": recorded})
    _, drawn = dressed.reset(seed=5)
    assert json.loads(json.dumps(info["dressing"])) == recorded == json.loads(json.dumps(drawn["dressing"]))
    assert clean.sim.model.ngeom == dressed.sim.model.ngeom  # the room's walls, furniture and clutter are built
    _, plain = clean.reset(seed=5)
    assert "dressing" not in plain and clean.sim.model.ngeom < dressed.sim.model.ngeom
    for env in (clean, dressed):
        env.close()


def test_the_study_trains_on_clean_and_randomized_data_and_rows_say_which(demos_zarr, tmp_path):
    """`train_scenes` x `scenes`: each training (DATA/<task>.zarr, DATA/<task>_randomized.zarr) evaluated on
    each kind of scene, a row each with the fields the committed study carries."""
    from humanoidgen.policies.bench import StudyConfig, data_name, format_row, plot, run_study

    data = tmp_path / "data"
    for scenes in ("clean", "randomized"):
        shutil.copytree(demos_zarr, data / f"{data_name('close_drawer', scenes)}.zarr")
    cfg = StudyConfig(tasks=("close_drawer",), demos=(2,), policies=("dp3",), data_root=data,
                      runs_root=tmp_path / "runs", overrides={"dp3": _with(TINY_DP3, epochs=1)}, eval_episodes=1,
                      eval_seeds=(0,), device="cpu", scenes=("clean", "randomized"),
                      train_scenes=("clean", "randomized"), recipe="tiny", eval_max_steps=2)
    rows = run_study(cfg, progress=False)
    assert [(r["train_scenes"], r["scenes"]) for r in rows] == [
        ("clean", "clean"), ("clean", "randomized"), ("randomized", "clean"), ("randomized", "randomized")]
    for r in rows:
        assert {"task", "policy", "demos", "recipe", "scenes", "success_mean", "success_std", "baseline_random",
                "baseline_noop", "success_ci95"} <= r.keys()
        assert r["success_ci95"][0] <= r["success_mean"] <= r["success_ci95"][1]
        assert all(len(b["success_ci95"]) == 2 for b in r["baselines"].values())
        assert (r["task"], r["policy"], r["demos"], r["recipe"]) == ("close_drawer", "dp3", 2, "tiny")
        assert r["baselines"]["random"]["rates"] and [e["scene_seed"] for e in r["episodes"]] == [100_000]
        trained_on = ck.load_policy(Path(r["checkpoint"]))[1]["data"]
        assert Path(trained_on).name == f"{data_name('close_drawer', r['train_scenes'])}.zarr"
        assert f"trained {r['train_scenes']}" in format_row(r)
    assert sorted(p.name for p in (tmp_path / "runs").iterdir()) == ["close_drawer_dp3_2",
                                                                      "close_drawer_dp3_2_randomized"]
    assert plot(rows, tmp_path / "bars.png") and (tmp_path / "bars.png").stat().st_size > 0
    with pytest.raises(ValueError, match="train_scenes"):
        StudyConfig(train_scenes=("foggy",))


def test_policy_bench_trains_on_randomized_data_when_asked(monkeypatch, tmp_path):
    """`hgen policy bench --train-randomized --randomize` asks the study for both trainings on both scenes."""
    import humanoidgen.policies.bench as study

    seen = []
    monkeypatch.setattr(study, "run_study", lambda cfg: seen.append(cfg) or [])
    monkeypatch.setattr(study, "write_results", lambda *a, **k: None)
    args = ["policy", "bench", "--tasks", "open_box_easy", "--policies", "dp3", "--demos", "50", "--recipe", "fast",
            "--device", "cpu", "--out", str(tmp_path / "p.json")]
    assert CliRunner().invoke(app, args + ["--train-randomized", "--randomize"]).exit_code == 0
    assert CliRunner().invoke(app, args).exit_code == 0
    assert [(c.train_scenes, c.scenes) for c in seen] == [(("clean", "randomized"), ("clean", "randomized")),
                                                          (("clean",), ("clean",))]


def test_an_interrupted_study_does_not_evaluate_a_row_again(demos_zarr, tmp_path, monkeypatch):
    """A study stopped after some rows were evaluated continues with the rest: each run keeps the rows evaluated
    so far under what decides them (checkpoint, scenes, episodes, seeds); asked for other scenes, it evaluates."""
    import humanoidgen.policies.eval as ev
    from humanoidgen.policies.bench import EVALUATED, StudyConfig, data_name, run_study

    data = tmp_path / "data"
    shutil.copytree(demos_zarr, data / f"{data_name('close_drawer', 'clean')}.zarr")
    cfg = dict(tasks=("close_drawer",), demos=(2,), policies=("dp3",), data_root=data, runs_root=tmp_path / "runs",
               overrides={"dp3": _with(TINY_DP3, epochs=1)}, eval_episodes=1, eval_seeds=(0,), device="cpu",
               scenes=("clean",), recipe="tiny", eval_max_steps=2)
    first = run_study(StudyConfig(**cfg), progress=False)
    (tmp_path / "runs" / "close_drawer_dp3_2" / EVALUATED).open("a").write('{"key": {"checkpoint"')  # cut short
    calls = []
    real = ev.evaluate
    monkeypatch.setattr(ev, "evaluate", lambda *a, **k: calls.append(k) or real(*a, **k))
    again = run_study(StudyConfig(**cfg), progress=False)
    assert again == first and calls == []
    both = run_study(StudyConfig(**{**cfg, "scenes": ("clean", "randomized")}), progress=False)
    assert both[0] == first[0] and [k["randomize"] for k in calls] == [True]
    assert both[1]["scenes"] == "randomized"
    run_study(StudyConfig(**{**cfg, "eval_seeds": (1,)}), progress=False)
    assert len(calls) == 2  # other scenes: evaluated
    rows = [json.loads(line) for line in (tmp_path / "runs" / "close_drawer_dp3_2" / EVALUATED).read_text()
            .splitlines() if line.endswith("}")]
    assert len(rows) == 3  # the line cut short did not swallow the one written after it


def test_rows_carry_a_wilson_interval_for_the_policy_and_each_baseline():
    """With 10-20 episodes a cell the spread over seeds says little; each row carries the 95% Wilson interval of
    its pooled episodes (an older row gets it from its episodes), for the policy and the baselines beside it."""
    from humanoidgen.policies.study_rows import with_intervals
    from humanoidgen.policies.report import wilson_interval

    lo, hi = wilson_interval(0, 20)
    assert lo == 0.0 and 0.15 < hi < 0.17  # 0 of 20 still allows up to ~16%
    lo, hi = wilson_interval(20, 20)
    assert 0.83 < lo < 0.84 and hi == 1.0
    lo, hi = wilson_interval(10, 20)
    assert abs((lo + hi) / 2 - 0.5) < 1e-9 and 0.29 < lo < 0.30
    assert wilson_interval(0, 0) == (0.0, 1.0)
    row = {"episodes": [{"success": k < 3} for k in range(10)],
           "baselines": {"random": {"successes": [100_001]}, "noop": {"successes": [], "success_ci95": [0.0, 0.5]}}}
    out = with_intervals(row)
    assert out["success_ci95"] == list(wilson_interval(3, 10))
    assert out["baselines"]["random"]["success_ci95"] == list(wilson_interval(1, 10))
    assert out["baselines"]["noop"]["success_ci95"] == [0.0, 0.5]  # kept where the row has it
    assert "success_ci95" not in row  # the row itself is not changed


def test_rows_of_one_checkpoint_on_other_seeds_are_pooled():
    """A study run again on another evaluation seed (`--seeds 2` beside `--seeds 0,1`) gives rows that `--combine`
    pools with the first: every seed's rate, the mean and spread over them, the baselines likewise, intervals over
    all the episodes; rows that share a seed are refused, rows of other scenes or checkpoints stay apart."""
    from humanoidgen.policies.study_rows import pool_rows
    from humanoidgen.policies.report import wilson_interval

    def row(seeds, passed, scenes="clean", ckpt="c.pt"):
        eps = [{"seed": s, "scene_seed": 100_000 + 1000 * s + i, "success": i < passed[k]}
               for k, s in enumerate(seeds) for i in range(10)]
        rates = [p / 10 for p in passed]
        base = {"success_mean": 0.0, "success_std": 0.0, "rates": [0.0] * len(seeds), "successes": []}
        return {"task": "t", "policy": "dp3", "demos": 50, "train_scenes": "clean", "scenes": scenes,
                "checkpoint": ckpt, "rates": rates, "success_mean": sum(rates) / len(rates), "success_std": 0.0,
                "episodes": eps, "eval_seconds": 1.0, "baseline_random": 0.0, "success_ci95": [0.0, 1.0],
                "baselines": {"random": {**base, "successes": [100_000 + 1000 * seeds[0]] if seeds == [2] else []},
                              "noop": base}}

    rows = pool_rows([row([0, 1], [9, 7]), row([0, 1], [5, 5], "randomized"), row([2], [8]),
                      row([0], [1], ckpt="other.pt")])
    assert [(r["scenes"], r["checkpoint"]) for r in rows] == [("clean", "c.pt"), ("randomized", "c.pt"),
                                                             ("clean", "other.pt")]
    pooled = rows[0]
    assert pooled["rates"] == [0.9, 0.7, 0.8] and abs(pooled["success_mean"] - 0.8) < 1e-9
    assert abs(pooled["success_std"] - 0.0816) < 1e-3 and len(pooled["episodes"]) == 30
    assert pooled["success_ci95"] == list(wilson_interval(24, 30)) and pooled["eval_seconds"] == 2.0
    random = pooled["baselines"]["random"]
    assert random["rates"] == [0.0, 0.0, 0.0] and random["successes"] == [102_000]
    assert random["success_ci95"] == list(wilson_interval(1, 30))
    assert rows[1]["rates"] == [0.5, 0.5]  # a lone row as it was
    with pytest.raises(ValueError, match="share seeds"):
        pool_rows([row([0, 1], [9, 7]), row([1], [8])])
