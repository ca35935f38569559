"""bench/replay_tolerance.py: a collected close_drawer episode replayed in the gym env passes as recorded and fails
with a large offset on the left arm's joint targets (the hand then misses the handle), while an offset on the right
arm, which does nothing in this task, changes nothing."""

from __future__ import annotations

import json

import pytest

from humanoidgen.episodes.collect import collect
from humanoidgen.episodes.recorder import RecorderConfig
from bench_scripts import load_bench


def _bench():
    return load_bench("replay_tolerance")


@pytest.fixture(scope="module")
def one_demo(tmp_path_factory):
    out = tmp_path_factory.mktemp("tolerance") / "close_drawer"
    stats = collect("close_drawer", 1, out, recorder=RecorderConfig(cameras=(), point_cloud=False))
    assert stats.kept == 1
    return out


def test_a_recorded_episode_passes_and_a_large_offset_on_the_acting_arm_fails(one_demo):
    bench = _bench()
    left = bench.tolerance(one_demo, "left", [0.0, 0.3], episodes=1)
    assert left["task"] == "close_drawer" and left["episodes"] == 1
    assert left["passed"] == {0.0: 1, 0.3: 0}
    assert left["failed"][0.0] == [] and len(left["failed"][0.3]) == 1  # how it failed: the task's own words
    assert "drawer 0" in left["failed"][0.3][0]["final"]
    # what the hand rested on: as recorded, the thumb on the handle (a geom of the drawer) for part of the push;
    # with the hand off the handle, less of it or none
    held, missed = left["grips"][0.0][0], left["grips"][0.3][0]
    assert held["passed"] and not missed["passed"]
    assert held["thumb"] and all(g.startswith("drawer_0_") for g in held["thumb"]) and held["fingers"]
    assert sum(missed["thumb"].values()) < sum(held["thumb"].values())
    where = max(held["thumb"], key=held["thumb"].get)
    assert bench.thumb_summary([held, held, missed]).startswith(f"{where} (passed 2")
    right = bench.tolerance(one_demo, "right", [0.3], episodes=1)
    assert right["passed"] == {0.3: 1}


def test_the_script_writes_its_results_with_their_provenance(one_demo, monkeypatch, tmp_path):
    bench = _bench()
    monkeypatch.setattr(bench, "ROOT", tmp_path)
    (tmp_path / "results").mkdir()
    monkeypatch.setattr("sys.argv", ["replay_tolerance.py", str(one_demo), "--side", "left", "--sigmas", "0",
                                     "--episodes", "1", "--name", "t"])
    assert bench.main() == 0
    report = json.loads((tmp_path / "results" / "t.json").read_text())
    assert report["rows"][0]["grips"]["0.0"][0]["thumb"]
    assert report["rows"][0]["passed"] == {"0.0": 1} and report["commit"] and "CPUs" in report["machine"]
    monkeypatch.setattr("sys.argv", ["replay_tolerance.py", str(one_demo), "--side", "up"])
    assert bench.main() == 2


def test_a_randomized_demonstration_is_replayed_in_the_room_it_was_recorded_in(tmp_path, monkeypatch):
    bench = _bench()
    out = tmp_path / "randomized"
    collect("close_drawer", 1, out, recorder=RecorderConfig(cameras=(), point_cloud=False), room="random",
            randomize_visuals=True)
    real, rooms = bench.replay, []

    def replay(env, actions, seed, side="left", dressing=None):
        result = real(env, actions, seed, side, dressing)
        rooms.append((dressing, env.sim.model.ngeom))
        return result

    monkeypatch.setattr(bench, "replay", replay)
    row = bench.tolerance(out, "left", [0.0], episodes=1)
    [(dressing, ngeom)] = rooms
    assert dressing and dressing["room"] and row["passed"] == {0.0: 1}
    monkeypatch.setattr(bench, "replay", real)
    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv

    clean = HumanoidTaskEnv("close_drawer", config=TaskEnvConfig(cameras=(), point_cloud=False))
    clean.reset(seed=0)
    assert ngeom > clean.sim.model.ngeom  # the replay's scene had the room's walls, furniture and clutter
    clean.close()
