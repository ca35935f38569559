"""bench/cloud_coverage.py: points counted near a part by their distance to its geoms' boxes, in each geom's own
frame; and on close_drawer's scene the count grows with the points read, the handle always among them."""

from __future__ import annotations

import json
import math
import sys
from types import SimpleNamespace

import numpy as np
import pytest
from bench_scripts import load_bench


def test_the_distance_is_to_the_box_in_its_own_frame():
    bench = load_bench("cloud_coverage")
    c, s = math.cos(math.pi / 4), math.sin(math.pi / 4)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])  # the box turned 45 degrees about z
    model = SimpleNamespace(geom_aabb=np.array([[0, 0, 0, 0.05, 0.01, 0.01]]))
    data = SimpleNamespace(geom_xpos=np.array([[1.0, 0, 0]]), geom_xmat=rot.reshape(1, 9))
    long_axis = rot[:, 0]
    points = np.array([[1.0, 0, 0],                            # the centre
                       [1.0, 0, 0] + 0.05 * long_axis,          # the end of the long side: on the box
                       [1.0, 0, 0] + 0.07 * long_axis,          # 2 cm past it
                       [1.0, 0, 0.03]])                         # 2 cm above the top
    np.testing.assert_allclose(bench.distance_to_geoms(points, data, model, [0]), [0, 0, 0.02, 0.02], atol=1e-9)
    assert bench.distance_to_geoms(points, data, model, []).tolist() == [math.inf] * 4


def test_close_drawers_handle_is_counted_more_often_in_more_points(tmp_path, monkeypatch):
    bench = load_bench("cloud_coverage")
    monkeypatch.setattr(bench, "ROOT", tmp_path)
    (tmp_path / "results").mkdir()
    monkeypatch.setattr(sys, "argv", ["cloud_coverage.py", "--task", "close_drawer", "--near", "handle",
                                      "--points", "64,1024", "--scenes", "2", "--name", "t"])
    assert bench.main() == 0
    got = json.loads((tmp_path / "results" / "cloud_coverage_t.json").read_text())
    assert [r["scene_seed"] for r in got["scenes"]] == [100000, 100001] and got["scenes"][0]["geoms"] == 3
    for row in got["scenes"]:
        assert 0 <= row["within"]["64"] <= row["within"]["1024"] and row["within"]["1024"] >= 5
    monkeypatch.setattr(sys, "argv", ["cloud_coverage.py", "--task", "close_drawer", "--near", "no_such_part",
                                      "--scenes", "1"])
    with pytest.raises(SystemExit, match="no geom"):
        bench.main()


def test_at_the_grip_a_cloud_focused_on_the_hands_puts_more_points_on_the_handle(tmp_path, monkeypatch):
    """--dataset counts at the recorded frames where a hand closes on the part; --near-hands draws half the cloud
    near the hands, and the handle gets more of it than from the even sample of the same frames."""
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.recorder import RecorderConfig

    data = tmp_path / "cd"
    assert collect("close_drawer", 1, data, recorder=RecorderConfig(cameras=(), point_cloud=False, every=10)).kept == 1
    bench = load_bench("cloud_coverage")
    monkeypatch.setattr(bench, "ROOT", tmp_path)
    (tmp_path / "results").mkdir()
    got = {}
    for share in ("0", "0.5"):
        monkeypatch.setattr(sys, "argv", ["cloud_coverage.py", "--near", "handle", "--points", "256", "--dataset",
                                          str(data), "--near-hands", share, "--name", share])
        assert bench.main() == 0
        got[share] = json.loads((tmp_path / "results" / f"cloud_coverage_{share}.json").read_text())
    assert got["0"]["task"] == "close_drawer" and got["0.5"]["near_hands"] == 0.5
    [even], [focused] = got["0"]["scenes"], got["0.5"]["scenes"]
    assert even["frames"] == focused["frames"] >= 3
    assert focused["within"]["256"] > 1.5 * even["within"]["256"], (even, focused)


def test_a_randomized_dataset_is_counted_in_the_rooms_it_was_recorded_in(tmp_path, monkeypatch):
    """--dataset on a store collected in randomized rooms draws each episode's clouds in its recorded room."""
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.episodes.recorder import RecorderConfig

    data = tmp_path / "cd"
    assert collect("close_drawer", 1, data, recorder=RecorderConfig(cameras=(), point_cloud=False, every=10),
                   room="random", randomize_visuals=True).kept == 1
    real, built = HumanoidTaskEnv.reset, []

    def reset(self, **kwargs):
        obs, info = real(self, **kwargs)
        built.append(json.loads(json.dumps(info.get("dressing"))))
        return obs, info

    monkeypatch.setattr(HumanoidTaskEnv, "reset", reset)
    rows = load_bench("cloud_coverage").coverage_at_grip(data, "handle", 0.01, [256], 1, 0.0, 0.05)
    assert len(rows) == 1 and built == [EpisodeStore(data).kept()[0]["dressing"]]
