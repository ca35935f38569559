"""policies/perturb.py and `hgen dataset perturb`: a collected close_drawer episode re-recorded in the gym env under
a drifting arm offset, labelled with the plan's own targets (DART). Without an offset it passes and its labels are
the recorded actions; with an offset far beyond the grip's tolerance every draw fails and the episode is left out,
each failed draw an index line with the task's words; the offsets drift with the stated spread and correlation."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from humanoidgen.cli.main import app
from humanoidgen.episodes.collect import collect
from humanoidgen.episodes.dataset import EpisodeStore
from humanoidgen.episodes.recorder import RecorderConfig
from humanoidgen.policies.perturb import Perturbation, PerturbStats, describe, perturb_store, read_perturbation


@pytest.fixture(scope="module")
def one_demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("perturb") / "close_drawer"
    stats = collect("close_drawer", 1, out, recorder=RecorderConfig(cameras=(), point_cloud=False, every=5))
    assert stats.kept == 1
    return out


def test_unperturbed_replay_keeps_the_plans_actions_and_observes_the_env(one_demo, tmp_path):
    src = EpisodeStore(one_demo)
    stats = perturb_store(one_demo, tmp_path / "zero", Perturbation(sigma=0.0, tries=1))
    assert (stats.kept, stats.left_out, stats.tries) == (1, 0, 1)
    dst = EpisodeStore(tmp_path / "zero")
    [rec] = dst.kept()
    assert rec["seed"] == src.kept()[0]["seed"] and rec["source_episode"] == 0 and rec["success"]
    got, was = dst.load(rec["episode"]), src.load(0)
    np.testing.assert_array_equal(got["action"], was["action"])  # the labels are the plan's targets
    assert got["joint_pos"].shape == was["joint_pos"].shape and got["qpos"].shape == was["qpos"].shape
    assert "point_cloud" not in got  # the source recorded none, so neither does the env
    # the first frame is the scene as built: the robot at its start posture, as recorded
    np.testing.assert_allclose(got["joint_pos"][0], was["joint_pos"][0], atol=0.05)
    meta = dst.meta()
    assert read_perturbation(dst)["sigma"] == 0.0 and meta["task"] == "close_drawer"
    assert meta["perturbation"]["source"].endswith("close_drawer") and meta["recorder"]["cameras"] == []


def test_an_offset_beyond_the_grip_leaves_the_episode_out_saying_why(one_demo, tmp_path):
    stats = perturb_store(one_demo, tmp_path / "far", Perturbation(sigma=0.4, tries=2, tau_s=5.0))
    assert (stats.kept, stats.left_out, stats.tries) == (0, 1, 2)
    attempts = EpisodeStore(tmp_path / "far").attempts()
    assert [a["try"] for a in attempts] == [0, 1] and not any(a["success"] for a in attempts)
    assert all("drawer 0" in a["error"] for a in attempts)
    assert EpisodeStore(tmp_path / "far").kept() == []


def test_the_offsets_drift_with_the_stated_spread_and_correlation():
    how = Perturbation(sigma=0.03, tau_s=1.0, side="both")
    assert len(how.joints()) == 14 and len(Perturbation(sigma=0.0).joints()) == 7
    x = how.offsets(20000, 10.0, np.random.default_rng(0))
    assert x.shape == (20000, 14)
    assert abs(x.std() - 0.03) < 0.003
    lag1 = np.mean([np.corrcoef(x[:-1, j], x[1:, j])[0, 1] for j in range(14)])
    assert abs(lag1 - math.exp(-0.1)) < 0.02  # one step at 10 Hz of a 1 s correlation time
    np.testing.assert_array_equal(how.offsets(50, 10.0, np.random.default_rng(3)),
                                  how.offsets(50, 10.0, np.random.default_rng(3)))
    for bad in (dict(sigma=-0.1), dict(sigma=float("nan")), dict(sigma=0.1, tau_s=0), dict(sigma=0.1, side="up"),
                dict(sigma=0.1, draws=0)):
        with pytest.raises(ValueError):
            Perturbation(**bad)


def test_the_command_writes_a_store_and_refuses_bad_settings_in_one_line(one_demo, tmp_path):
    runner = CliRunner()
    res = runner.invoke(app, ["dataset", "perturb", str(one_demo), "--out", str(tmp_path / "d"), "--sigma", "0"])
    assert res.exit_code == 0, res.output
    assert "1 perturbed episodes kept of 1 wanted" in res.output
    assert json.loads((tmp_path / "d" / "meta.json").read_text())["perturbation"]["side"] == "left"
    res = runner.invoke(app, ["dataset", "perturb", str(one_demo), "--out", str(tmp_path / "e"), "--side", "up"])
    assert res.exit_code == 1 and "side must be left, right or both" in res.output
    res = runner.invoke(app, ["dataset", "perturb", str(one_demo), "--out", str(tmp_path / "d")])
    assert res.exit_code == 1 and "already holds a dataset" in res.output


def test_the_perturbation_is_said_by_the_export_the_checkpoint_and_the_study_rows(one_demo, tmp_path):
    """Where the data came from travels with it: the store's meta.json, the zarr's attributes, the training run's
    meta (what a checkpoint keeps) and the study's rows (bench/policies.py --from-eval)."""
    from bench_scripts import load_bench

    from humanoidgen.episodes.dataset import export_zarr
    from humanoidgen.policies.data import read_demos
    from humanoidgen.policies.train import run_meta

    perturb_store(one_demo, tmp_path / "p", Perturbation(sigma=0.0, tries=1, seed=7))
    export_zarr(EpisodeStore(tmp_path / "p"), tmp_path / "p.zarr")
    export_zarr(EpisodeStore(one_demo), tmp_path / "plain.zarr")
    meta = run_meta(read_demos(tmp_path / "p.zarr", ("state", "action")), None)
    assert meta["perturbation"]["seed"] == 7 and meta["perturbation"]["sigma"] == 0.0
    assert "perturbation" not in run_meta(read_demos(tmp_path / "plain.zarr", ("state", "action")), None)
    bench = load_bench("policies")
    assert bench.training_perturbation(meta)["seed"] == 7
    assert bench.training_perturbation({"data": str(tmp_path / "p.zarr")})["side"] == "left"  # a run from before
    assert bench.training_perturbation({"data": str(tmp_path / "plain.zarr")}) is None
    assert bench.training_perturbation({}) is None


def test_trainings_side_by_side_are_drawn_from_their_result_files(tmp_path, monkeypatch):
    """bench/compare_rows.py: one bar per result file with its interval and baselines, labelled; a label missing
    or a result file missing is one line and a non-zero exit."""
    import sys

    from bench_scripts import load_bench

    bench = load_bench("compare_rows")
    monkeypatch.setattr(bench, "ROOT", tmp_path)
    (tmp_path / "results").mkdir()
    # b: 60 of 60, whose Wilson upper bound the study writes a rounding error under the mean
    for name, mean, ci in (("a", 0.25, [0.15, 0.35]), ("b", 1.0, [0.9398260695220669, 0.9999999999999999])):
        row = {"task": "close_drawer", "policy": "dp3", "demos": 50, "epochs": 40, "success_mean": mean,
               "success_std": 0.1, "success_ci95": ci, "rates": [mean] * 3,
               "baseline_random": 0.02, "baseline_noop": 0.0, "perturbation": {"sigma": 0.03} if name == "b" else None}
        (tmp_path / "results" / f"policies_{name}.json").write_text(json.dumps({"rows": [row]}))
    monkeypatch.setattr(sys, "argv", ["compare_rows.py", "--rows", "a,b", "--labels", "recorded,DART", "--name", "c"])
    assert bench.main() == 0
    written = json.loads((tmp_path / "results" / "c.json").read_text())["rows"]
    assert [(r["label"], r["success_mean"]) for r in written] == [("recorded", 0.25), ("DART", 1.0)]
    assert written[1]["perturbation"] == {"sigma": 0.03} and (tmp_path / "results" / "c.png").stat().st_size > 0
    monkeypatch.setattr(sys, "argv", ["compare_rows.py", "--rows", "a,b", "--labels", "one", "--name", "d"])
    assert bench.main() == 2
    monkeypatch.setattr(sys, "argv", ["compare_rows.py", "--rows", "a,zzz", "--labels", "x,y", "--name", "d"])
    with pytest.raises(SystemExit, match="no results"):
        bench.main()


def test_an_interrupted_run_resumes_without_replaying_what_it_has(one_demo, tmp_path, monkeypatch):
    from humanoidgen.policies import perturb

    how = Perturbation(sigma=0.0, tries=1, draws=2)
    calls = []
    real = perturb.perturbed_replay

    def counted(*args, **kwargs):
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt  # interrupted during the second draw
        return real(*args, **kwargs)

    monkeypatch.setattr(perturb, "perturbed_replay", counted)
    with pytest.raises(KeyboardInterrupt):
        perturb_store(one_demo, tmp_path / "r", how)
    assert len(EpisodeStore(tmp_path / "r").kept()) == 1  # the first draw is kept
    monkeypatch.setattr(perturb, "perturbed_replay", real)
    stats = perturb_store(one_demo, tmp_path / "r", how, resume=True)
    assert (stats.kept, stats.left_out, stats.tries) == (2, 0, 1)  # only the second draw replayed
    assert sorted(a["draw"] for a in EpisodeStore(tmp_path / "r").kept()) == [0, 1]
    with pytest.raises(perturb.DatasetError, match="perturbed otherwise"):
        perturb_store(one_demo, tmp_path / "r", Perturbation(sigma=0.01, tries=1, draws=2), resume=True)
    with pytest.raises(perturb.DatasetError, match="perturbed otherwise"):  # fewer draws than it holds
        perturb_store(one_demo, tmp_path / "r", Perturbation(sigma=0.0, tries=1, draws=1), resume=True)
    # more draws extend the finished store: only the new draw is replayed, and its meta says three
    stats = perturb_store(one_demo, tmp_path / "r", Perturbation(sigma=0.0, tries=1, draws=3), resume=True)
    assert (stats.kept, stats.tries) == (3, 1)
    assert sorted(a["draw"] for a in EpisodeStore(tmp_path / "r").kept()) == [0, 1, 2]
    assert read_perturbation(EpisodeStore(tmp_path / "r"))["draws"] == 3
    with pytest.raises(perturb.DatasetError, match="already holds a dataset"):
        perturb_store(one_demo, tmp_path / "r", how)


def test_a_cloud_focused_on_the_hands_is_recorded_kept_on_resume_and_refused_when_bad(one_demo, tmp_path):
    from humanoidgen.policies import perturb

    how = Perturbation(sigma=0.0, tries=1)
    perturb_store(one_demo, tmp_path / "f", how, cloud_near_hands=0.5)
    assert EpisodeStore(tmp_path / "f").meta()["recorder"]["point_cloud_near_hands"] == 0.5
    assert EpisodeStore(one_demo).meta()["recorder"].get("point_cloud_near_hands", 0.0) == 0.0  # the source's
    # resumed without the option, the store goes on as it was begun; with another share it is refused
    perturb_store(one_demo, tmp_path / "f", how, resume=True)
    assert EpisodeStore(tmp_path / "f").meta()["recorder"]["point_cloud_near_hands"] == 0.5
    with pytest.raises(perturb.DatasetError, match="point_cloud_near_hands 0.5"):
        perturb_store(one_demo, tmp_path / "f", how, resume=True, cloud_near_hands=0.0)
    res = CliRunner().invoke(app, ["dataset", "perturb", str(one_demo), "--out", str(tmp_path / "g"),
                                   "--cloud-near-hands", "1.5"])
    assert res.exit_code == 1 and "point_cloud_near_hands must be in [0, 1)" in res.output
    assert len(res.output.strip().splitlines()) == 1


def test_two_worker_processes_write_the_store_one_process_writes(one_demo, tmp_path):
    how = Perturbation(sigma=0.02, tries=2, draws=3, seed=4)
    one = perturb_store(one_demo, tmp_path / "one", how)
    two = perturb_store(one_demo, tmp_path / "two", how, workers=2)
    assert (one.kept, one.left_out, one.tries) == (two.kept, two.left_out, two.tries)
    a, b = EpisodeStore(tmp_path / "one"), EpisodeStore(tmp_path / "two")
    drop = ("time", "duration", "wall", "timings")  # per-line clocks, if the store writes any
    strip = [[{k: v for k, v in r.items() if not any(d in k for d in drop)} for r in s.attempts()] for s in (a, b)]
    assert strip[0] == strip[1] and len(strip[0]) >= 3  # the same lines in the same order
    for ra, rb in zip(a.kept(), b.kept()):
        ea, eb = a.load(ra["episode"]), b.load(rb["episode"])
        assert ea.keys() == eb.keys()
        for k in ea:
            np.testing.assert_array_equal(ea[k], eb[k])  # spawned workers simulate the same bytes
    with pytest.raises(ValueError, match="workers"):
        perturb_store(one_demo, tmp_path / "none", how, workers=0)


def test_an_interrupted_run_with_workers_keeps_what_it_wrote_and_resumes(one_demo, tmp_path):
    how = Perturbation(sigma=0.0, tries=1, draws=3)

    def interrupt(_line):
        raise KeyboardInterrupt  # Ctrl-C just after the first draw was written

    with pytest.raises(KeyboardInterrupt):
        perturb_store(one_demo, tmp_path / "w", how, progress=interrupt, workers=2)
    assert [a["draw"] for a in EpisodeStore(tmp_path / "w").kept()] == [0]
    stats = perturb_store(one_demo, tmp_path / "w", how, resume=True, workers=2)
    assert (stats.kept, stats.tries) == (3, 2)  # the two draws not written are replayed, the first is not
    assert sorted(a["draw"] for a in EpisodeStore(tmp_path / "w").kept()) == [0, 1, 2]


def test_the_summary_names_the_arms_perturbed():
    stats = PerturbStats(source_episodes=50, kept=99, left_out=1, tries=146)
    both = describe(stats, Perturbation(sigma=0.03, side="both", draws=2))
    assert "99 perturbed episodes kept of 100 wanted" in both and "on both arms" in both
    assert "on the left arm" in describe(stats, Perturbation(sigma=0.03, side="left", draws=2))


def test_a_randomized_demonstration_is_replayed_in_its_own_room(tmp_path, monkeypatch):
    """A store collected in randomized rooms (`hgen collect --room random --randomize-visuals`) is re-recorded in
    each episode's own room and look, and the new records say which: a policy trained on it sees the room the
    episode was recorded in, not the clean tabletop, and `hgen dataset replay` draws that room again."""
    from humanoidgen.policies import perturb

    src_dir = tmp_path / "randomized"
    stats = collect("close_drawer", 1, src_dir, recorder=RecorderConfig(cameras=(), point_cloud=False, every=5),
                    room="random", randomize_visuals=True)
    assert stats.kept == 1
    [was_rec] = EpisodeStore(src_dir).kept()
    assert was_rec.get("dressing")
    built = []  # the dressing of every scene the replays were run in, as the real env reports it
    make_env = perturb._make_env

    def watched_env(task, config):
        env = make_env(task, config)
        reset = env.reset

        def watched_reset(**kwargs):
            obs, info = reset(**kwargs)
            built.append(json.loads(json.dumps(info.get("dressing"))))
            return obs, info

        env.reset = watched_reset
        return env

    monkeypatch.setattr(perturb, "_make_env", watched_env)
    stats = perturb_store(src_dir, tmp_path / "zero", Perturbation(sigma=0.0, tries=1))
    assert (stats.kept, stats.left_out) == (1, 0)
    assert built == [was_rec["dressing"]]
    [rec] = EpisodeStore(tmp_path / "zero").kept()
    assert rec["dressing"] == was_rec["dressing"]
    got, was = EpisodeStore(tmp_path / "zero").load(rec["episode"]), EpisodeStore(src_dir).load(0)
    np.testing.assert_allclose(got["joint_pos"][0], was["joint_pos"][0], atol=0.05)
