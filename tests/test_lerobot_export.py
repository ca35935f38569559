"""The LeRobot (v3.0) export, checked file by file without lerobot: a small synthetic store, no simulation."""

import json

import imageio_ffmpeg
import numpy as np
import pyarrow.parquet as pq
import pytest
from typer.testing import CliRunner

from humanoidgen.cli.main import app
from humanoidgen.episodes.dataset import DatasetError, EpisodeStore
from humanoidgen.episodes.lerobot_export import export_lerobot

LENGTHS = (7, 12)
CAMERAS = {"head": (48, 64), "left_wrist": (33, 40)}  # (height, width); 33 is odd and gets padded to 34
NAMES = [f"joint_{i}" for i in range(26)]
TASK = "Put the red cube on the blue one."


def _frames(t: int, h: int, w: int, seed: int) -> np.ndarray:
    """Smooth images that change from frame to frame, so each decoded frame can be told apart."""
    y, x = np.mgrid[0:h, 0:w]
    out = np.empty((t, h, w, 3), np.uint8)
    for k in range(t):
        out[k, ..., 0] = (x * 255 // max(w - 1, 1) + 20 * k + 40 * seed) % 256
        out[k, ..., 1] = y * 255 // max(h - 1, 1)
        out[k, ..., 2] = 30 + 15 * k
    return out


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    root = tmp_path_factory.mktemp("store")
    s = EpisodeStore(root)
    s.create({"task": "synthetic_stack", "task_description": TASK, "control_hz": 50.0, "action_names": NAMES,
              "state_names": NAMES, "cameras": list(CAMERAS), "recorder": {"every": 10}})
    rng = np.random.default_rng(0)
    for i, t in enumerate(LENGTHS):
        arrays = {"action": rng.normal(size=(t, 26)).astype(np.float32),
                  "joint_pos": rng.normal(size=(t, 26)).astype(np.float32),
                  "ee_pose": rng.normal(size=(t, 14)).astype(np.float32),
                  "object_pose": rng.normal(size=(t, 2, 7)).astype(np.float32),
                  "qpos": rng.normal(size=(t, 52)), "time": 0.2 * np.arange(t)}
        for cam, (h, w) in CAMERAS.items():
            arrays[f"rgb/{cam}"] = _frames(t, h, w, i)
            arrays[f"depth/{cam}"] = np.ones((t, h, w), np.float32)
        s.add({"seed": i, "success": True}, arrays)
    s.add({"seed": 99, "success": False, "error": "failed"}, None)  # a failed attempt: not exported
    return s


@pytest.fixture(scope="module")
def exported(store, tmp_path_factory):
    out = tmp_path_factory.mktemp("lerobot") / "ds"
    info = export_lerobot(store, out)
    return out, info


def test_info_json_describes_the_dataset(exported):
    out, info = exported
    on_disk = json.loads((out / "meta" / "info.json").read_text())
    assert on_disk == info
    assert info["codebase_version"] == "v3.0"
    assert info["fps"] == 5 and isinstance(info["fps"], int)
    assert info["total_episodes"] == 2 and info["total_frames"] == sum(LENGTHS) and info["total_tasks"] == 1
    assert info["splits"] == {"train": "0:2"}
    assert info["data_path"] == "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
    assert info["video_path"] == "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4"
    for key in ("chunks_size", "data_files_size_in_mb", "video_files_size_in_mb", "robot_type"):
        assert key in info
    ft = info["features"]
    assert ft["observation.state"] == {"dtype": "float32", "shape": [26], "names": NAMES}
    assert ft["action"] == {"dtype": "float32", "shape": [26], "names": NAMES}
    assert ft["observation.ee_pose"]["shape"] == [14] and len(ft["observation.ee_pose"]["names"]) == 14
    assert ft["observation.images.head"]["dtype"] == "video"
    assert ft["observation.images.head"]["shape"] == [48, 64, 3]
    assert ft["observation.images.head"]["names"] == ["height", "width", "channels"]
    assert ft["observation.images.left_wrist"]["shape"] == [34, 40, 3]
    assert ft["observation.images.head"]["info"]["video.codec"] == "h264"
    for key, dtype in (("timestamp", "float32"), ("frame_index", "int64"), ("episode_index", "int64"),
                       ("index", "int64"), ("task_index", "int64")):
        assert ft[key] == {"dtype": dtype, "shape": [1], "names": None}


def test_tasks_and_episode_metadata(exported):
    out, _ = exported
    tasks = pq.read_table(out / "meta" / "tasks.parquet")
    assert tasks.to_pylist() == [{"task_index": 0, "__index_level_0__": TASK}]
    assert b"pandas" in tasks.schema.metadata  # pandas reads the task string back as the index
    eps = pq.read_table(out / "meta" / "episodes" / "chunk-000" / "file-000.parquet").to_pylist()
    assert [e["episode_index"] for e in eps] == [0, 1]
    assert [e["length"] for e in eps] == list(LENGTHS)
    assert all(e["tasks"] == [TASK] for e in eps)
    assert [(e["dataset_from_index"], e["dataset_to_index"]) for e in eps] == [(0, 7), (7, 19)]
    for cam in CAMERAS:
        key = f"videos/observation.images.{cam}"
        assert [(e[f"{key}/from_timestamp"], e[f"{key}/to_timestamp"]) for e in eps] == [(0.0, 1.4), (1.4, 3.8)]
        assert all(e[f"{key}/chunk_index"] == 0 and e[f"{key}/file_index"] == 0 for e in eps)
    assert eps[1]["stats/action/count"] == [12] and len(eps[1]["stats/action/mean"]) == 26
    assert np.array(eps[0]["stats/observation.images.head/mean"]).shape == (3, 1, 1)


def test_data_parquet_rows_and_indices(store, exported):
    out, info = exported
    table = pq.read_table(out / "data" / "chunk-000" / "file-000.parquet")
    assert table.column_names == ["observation.state", "action", "observation.ee_pose", "timestamp",
                                  "frame_index", "episode_index", "index", "task_index"]
    assert table.num_rows == sum(LENGTHS)
    cols = {k: np.array(table.column(k).to_pylist()) for k in table.column_names}
    assert np.array_equal(cols["index"], np.arange(sum(LENGTHS)))
    assert np.array_equal(cols["task_index"], np.zeros(sum(LENGTHS)))
    start = 0
    for ep, t in enumerate(LENGTHS):
        rows = slice(start, start + t)
        assert np.all(cols["episode_index"][rows] == ep)
        assert np.array_equal(cols["frame_index"][rows], np.arange(t))
        np.testing.assert_allclose(cols["timestamp"][rows], np.arange(t) / info["fps"], atol=1e-6)
        arrays = store.load(ep)
        np.testing.assert_array_equal(cols["action"][rows], arrays["action"])
        np.testing.assert_array_equal(cols["observation.state"][rows], arrays["joint_pos"])
        np.testing.assert_array_equal(cols["observation.ee_pose"][rows], arrays["ee_pose"])
        start += t
    assert table.schema.field("timestamp").type == "float"
    assert str(table.schema.field("action").type) == "fixed_size_list<element: float>[26]"


def test_videos_hold_every_frame_in_order(store, exported):
    out, _ = exported
    for cam, (h, w) in CAMERAS.items():
        path = out / "videos" / f"observation.images.{cam}" / "chunk-000" / "file-000.mp4"
        gen = imageio_ffmpeg.read_frames(str(path))
        meta = next(gen)
        assert meta["size"] == (w, h + h % 2) and meta["fps"] == 5
        frames = np.stack([np.frombuffer(f, np.uint8).reshape(h + h % 2, w, 3) for f in gen])
        assert len(frames) == sum(LENGTHS)
        source = np.concatenate([store.load(ep)[f"rgb/{cam}"] for ep in range(len(LENGTHS))])
        err = np.abs(frames[:, :h].astype(int) - source.astype(int)).mean(axis=(1, 2, 3))
        assert err.max() < 8, err  # lossy, but each frame matches its own source frame


def test_stats_cover_every_feature(store, exported):
    out, info = exported
    stats = json.loads((out / "meta" / "stats.json").read_text())
    assert set(stats) == set(info["features"])
    for key, s in stats.items():
        assert {"min", "max", "mean", "std", "count", "q01", "q10", "q50", "q90", "q99"} <= set(s), key
        shape = (3, 1, 1) if key.startswith("observation.images.") else tuple(info["features"][key]["shape"])
        for stat in ("min", "max", "mean", "std", "q50"):
            assert np.array(s[stat]).shape == shape, (key, stat)
    actions = np.concatenate([store.load(i)["action"] for i in range(len(LENGTHS))]).astype(np.float64)
    np.testing.assert_allclose(stats["action"]["mean"], actions.mean(0), atol=1e-6)
    np.testing.assert_allclose(stats["action"]["std"], actions.std(0), atol=1e-6)
    np.testing.assert_allclose(stats["action"]["min"], actions.min(0), atol=1e-6)
    assert stats["action"]["count"] == [sum(LENGTHS)]
    assert stats["index"]["min"] == [0] and stats["index"]["max"] == [sum(LENGTHS) - 1]
    assert all(0 <= v <= 1 for v in np.ravel(stats["observation.images.head"]["mean"]))


def test_refuses_what_it_cannot_or_should_not_write(store, tmp_path):
    with pytest.raises(DatasetError, match="no RGB images"):
        export_lerobot(store, tmp_path / "a", cameras=["front"])
    (tmp_path / "b").mkdir()
    (tmp_path / "b" / "keep.txt").write_text("mine")
    with pytest.raises(DatasetError, match="not an empty folder"):
        export_lerobot(store, tmp_path / "b")
    info = export_lerobot(store, tmp_path / "c", cameras=[])
    assert info["video_path"] is None and not (tmp_path / "c" / "videos").exists()
    again = export_lerobot(store, tmp_path / "c", cameras=["head"])  # an earlier export is replaced
    assert [k for k in again["features"] if k.startswith("observation.images.")] == ["observation.images.head"]


def test_cli_export_needs_a_target_and_writes_lerobot(store, tmp_path):
    runner = CliRunner()
    res = runner.invoke(app, ["dataset", "export", str(store.root)])
    assert res.exit_code != 0
    res = runner.invoke(app, ["dataset", "export", str(store.root), "--lerobot", str(tmp_path / "lr"),
                              "--lerobot-cameras", "left_wrist"])
    assert res.exit_code == 0, res.output
    info = json.loads((tmp_path / "lr" / "meta" / "info.json").read_text())
    assert "observation.images.left_wrist" in info["features"] and "observation.images.head" not in info["features"]


def test_a_dimension_that_never_moved_gets_a_normalisation_span(tmp_path):
    """lerobot-doctor's zero-variance finding: LeRobot divides by max - min (1e-8 when 0), so stats.json gives a
    never-moving joint MIN_SPAN around its value; the episode's own stats keep what was measured."""
    from humanoidgen.episodes.lerobot_stats import MIN_SPAN

    s = EpisodeStore(tmp_path / "store")
    s.create({"task": "synthetic_stack", "task_description": TASK, "control_hz": 50.0, "action_names": NAMES,
              "state_names": NAMES, "cameras": [], "recorder": {"every": 10}})
    action = np.random.default_rng(1).normal(size=(9, 26)).astype(np.float32)
    action[:, 3] = 0.47  # an idle joint
    s.add({"seed": 0, "success": True}, {"action": action, "joint_pos": action, "ee_pose": np.zeros((9, 14), np.float32),
                                         "qpos": np.zeros((9, 52)), "time": 0.2 * np.arange(9)})
    out = tmp_path / "lr"
    export_lerobot(s, out)
    stats = json.loads((out / "meta" / "stats.json").read_text())["action"]
    assert np.isclose(stats["max"][3] - stats["min"][3], MIN_SPAN) and np.isclose(stats["mean"][3], 0.47)
    assert np.isclose(stats["std"][3], MIN_SPAN / 2)
    np.testing.assert_allclose(stats["min"][4], action[:, 4].min(), atol=1e-6)  # a moving joint keeps its range
    episodes = pq.read_table(next((out / "meta" / "episodes").rglob("*.parquet"))).to_pylist()
    assert episodes[0]["stats/action/max"][3] == episodes[0]["stats/action/min"][3]
