"""Export an episode store to the LeRobot dataset format, codebase version v3.0 (what `lerobot` 0.4.x reads).

    OUT/meta/info.json                                    codebase_version, fps, counts, path templates, features
    OUT/meta/stats.json                                   statistics over all frames, per feature
    OUT/meta/tasks.parquet                                task string (pandas index) -> task_index
    OUT/meta/episodes/chunk-000/file-000.parquet          one row per episode: length, tasks, where its data and
                                                          video frames lie, its own statistics (stats/<feature>/<stat>)
    OUT/data/chunk-000/file-000.parquet                   one row per frame: observation.state, action,
                                                          observation.ee_pose, timestamp, frame_index,
                                                          episode_index, index, task_index
    OUT/videos/observation.images.<camera>/chunk-000/file-000.mp4
                                                          the episodes of one camera one after another (H.264,
                                                          yuv420p), episode e at [from_timestamp, to_timestamp)

Episodes are appended to a data (video) file until it reaches `data_files_size_in_mb` (`video_files_size_in_mb`),
then the next file is started; an episode never spans two files. Frame k of an episode has timestamp k / fps, and
its video frame is at from_timestamp + k / fps in the camera's file, as LeRobotDataset decodes it.

Only pyarrow and imageio-ffmpeg are needed here; lerobot itself is not.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np

from humanoidgen.episodes.dataset import DatasetError, EpisodeStore
from humanoidgen.episodes.lerobot_stats import aggregate, dataset_stats_json, image_stats, vector_stats
from humanoidgen.robots import default_robot

CODEBASE_VERSION = "v3.0"
CHUNKS_SIZE = 1000  # files per chunk folder
DATA_FILES_SIZE_IN_MB = 100
VIDEO_FILES_SIZE_IN_MB = 200
CHUNK_FILE_PATTERN = "chunk-{chunk_index:03d}/file-{file_index:03d}"
DATA_PATH = "data/" + CHUNK_FILE_PATTERN + ".parquet"
VIDEO_PATH = "videos/{video_key}/" + CHUNK_FILE_PATTERN + ".mp4"
EPISODES_PATH = "meta/episodes/" + CHUNK_FILE_PATTERN + ".parquet"
SOURCE_META = "meta/humanoidgen.json"  # beside LeRobot's files: the task and how it was recorded
SOURCE_KEYS = ("task", "task_source", "robot", "control_hz", "recorder", "action_names")
ROBOT_TYPE = default_robot().data.robot_type

# Columns every LeRobot frame carries, after the dataset's own features.
DEFAULT_FEATURES = {
    "timestamp": {"dtype": "float32", "shape": [1], "names": None},
    "frame_index": {"dtype": "int64", "shape": [1], "names": None},
    "episode_index": {"dtype": "int64", "shape": [1], "names": None},
    "index": {"dtype": "int64", "shape": [1], "names": None},
    "task_index": {"dtype": "int64", "shape": [1], "names": None},
}


def _ee_pose_names() -> list[str]:
    return [f"{side}_{c}" for side in ("left", "right") for c in ("x", "y", "z", "qw", "qx", "qy", "qz")]


def task_description(meta: dict) -> str:
    """The task's natural-language description (the spec's `description`), else its name."""
    if meta.get("task_description"):
        return str(meta["task_description"])
    try:
        from humanoidgen.tasks.registry import load_task

        return load_task(meta.get("task_source", meta["task"])).description.strip()
    except Exception:  # a task file moved or renamed since collection: the name still identifies it
        return str(meta["task"])


def _fps(meta: dict) -> int:
    fps = float(meta["control_hz"]) / int(meta["recorder"]["every"])
    if abs(fps - round(fps)) > 1e-6 or round(fps) < 1:
        raise DatasetError(f"LeRobot needs a whole number of frames per second; this dataset records at "
                           f"{meta['control_hz']} Hz / every {meta['recorder']['every']} = {fps:g} fps")
    return int(round(fps))


def _next_file(chunk: int, file: int) -> tuple[int, int]:
    return (chunk + 1, 0) if file == CHUNKS_SIZE - 1 else (chunk, file + 1)


class _VideoFiles:
    """One camera's mp4 files: the episodes' frames appended as one H.264 stream per file."""

    def __init__(self, root: Path, key: str, fps: int, size: tuple[int, int], crf: int, gop: int):
        self.root, self.key, self.fps, self.size = root, key, fps, size  # size: (height, width) as written
        self.crf, self.gop = crf, gop
        self.chunk, self.file, self.frames_in_file = 0, 0, 0
        self.writer = None

    def path(self) -> Path:
        return self.root / VIDEO_PATH.format(video_key=self.key, chunk_index=self.chunk, file_index=self.file)

    def _open(self) -> None:
        import imageio_ffmpeg

        p = self.path()
        p.parent.mkdir(parents=True, exist_ok=True)
        h, w = self.size
        self.writer = imageio_ffmpeg.write_frames(
            str(p), (w, h), fps=self.fps, codec="libx264", pix_fmt_out="yuv420p", quality=None,
            macro_block_size=1, ffmpeg_log_level="error",
            # a key frame every `gop` frames for quick random access, no B-frames so every pts is k / fps
            output_params=["-crf", str(self.crf), "-g", str(self.gop), "-bf", "0"])
        self.writer.send(None)
        self.frames_in_file = 0

    def add_episode(self, frames: np.ndarray) -> dict:
        p = self.path()  # ffmpeg writes as it goes, so the size on disk tells when to start the next file
        if self.writer is not None and p.exists() and p.stat().st_size / 2**20 >= VIDEO_FILES_SIZE_IN_MB:
            self.close()
            self.chunk, self.file = _next_file(self.chunk, self.file)
        if self.writer is None:
            self._open()
        h, w = self.size
        if frames.shape[1:3] != (h, w):  # odd sizes padded to even ones, which yuv420p needs
            frames = np.pad(frames, ((0, 0), (0, h - frames.shape[1]), (0, w - frames.shape[2]), (0, 0)), mode="edge")
        start = self.frames_in_file
        for f in frames:
            self.writer.send(np.ascontiguousarray(f))
        self.frames_in_file += len(frames)
        return {f"videos/{self.key}/chunk_index": self.chunk, f"videos/{self.key}/file_index": self.file,
                f"videos/{self.key}/from_timestamp": start / self.fps,
                f"videos/{self.key}/to_timestamp": self.frames_in_file / self.fps}

    def close(self) -> None:
        if self.writer is not None:
            self.writer.close()
            self.writer = None


def _tasks_table(tasks: list[str]):
    """meta/tasks.parquet as pandas writes `DataFrame({"task_index": ...}, index=tasks)`: the task is the index."""
    import pyarrow as pa

    table = pa.table({"task_index": pa.array(range(len(tasks)), pa.int64()),
                      "__index_level_0__": pa.array(tasks, pa.string())})
    pandas_meta = {
        "index_columns": ["__index_level_0__"],
        "column_indexes": [{"name": None, "field_name": None, "pandas_type": "unicode", "numpy_type": "object",
                            "metadata": {"encoding": "UTF-8"}}],
        "columns": [
            {"name": "task_index", "field_name": "task_index", "pandas_type": "int64", "numpy_type": "int64",
             "metadata": None},
            {"name": None, "field_name": "__index_level_0__", "pandas_type": "unicode", "numpy_type": "object",
             "metadata": None},
        ],
        "creator": {"library": "pyarrow", "version": pa.__version__},
        "pandas_version": "2.2.3",
    }
    return table.replace_schema_metadata({b"pandas": json.dumps(pandas_meta).encode()})


def _hf_features(features: dict) -> dict:
    """The `datasets` feature description of the data files (stored in their schema, as `datasets` writes it)."""
    out = {}
    for key, ft in features.items():
        if ft["dtype"] == "video":
            continue
        value = {"dtype": ft["dtype"], "_type": "Value"}
        out[key] = value if ft["shape"] == [1] else {"feature": value, "length": ft["shape"][0], "_type": "Sequence"}
    return out


def _discard(out: Path, keep_folder: bool) -> None:
    """Remove what a failed export wrote (the folder itself too, unless it existed before)."""
    if not keep_folder:
        shutil.rmtree(out, ignore_errors=True)
        return
    for child in out.iterdir() if out.is_dir() else []:
        shutil.rmtree(child, ignore_errors=True) if child.is_dir() else child.unlink(missing_ok=True)


def export_lerobot(store: EpisodeStore, out: Path, cameras: list[str] | None = None, task: str | None = None,
                   robot_type: str = ROBOT_TYPE, crf: int = 23, gop: int = 2, overwrite: bool = False) -> dict:
    """Write `store`'s kept episodes as a LeRobot v3.0 dataset at `out`; returns the info.json written.

    `out` must be absent, empty or an earlier LeRobot export (which is replaced); `overwrite` replaces anything.

    cameras: which recorded RGB cameras become `observation.images.<camera>` videos (default: all recorded).
    task: the task string every frame carries (default: the task spec's description).
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    out = Path(out)
    meta = store.meta()
    kept = store.kept()
    if not kept:
        raise DatasetError(f"{store.root} has no episodes to export")
    if out.is_file() or (out.exists() and any(out.iterdir())):
        # a previous LeRobot export is replaced, like the zarr export replaces its store; anything else is kept
        if not (overwrite or (out / "meta" / "info.json").is_file()):
            raise DatasetError(f"{out} exists and is not an empty folder or a LeRobot dataset")
        shutil.rmtree(out) if out.is_dir() else out.unlink()
    fps = _fps(meta)
    task = task or task_description(meta)

    first = store.load(kept[0]["episode"])
    recorded = [c for c in meta.get("cameras", meta.get("recorder", {}).get("cameras", [])) if f"rgb/{c}" in first]
    cameras = recorded if cameras is None else list(cameras)
    missing = [c for c in cameras if f"rgb/{c}" not in first]
    if missing:
        raise DatasetError(f"no RGB images recorded for camera(s) {missing}; recorded: {recorded}")

    action_names = list(meta["action_names"])
    state_names = list(meta.get("state_names") or action_names)
    if len(state_names) != first["joint_pos"].shape[1]:
        state_names = action_names
    features: dict[str, dict] = {
        "observation.state": {"dtype": "float32", "shape": [first["joint_pos"].shape[1]], "names": state_names},
        "action": {"dtype": "float32", "shape": [first["action"].shape[1]], "names": action_names},
        "observation.ee_pose": {"dtype": "float32", "shape": [first["ee_pose"].shape[1]],
                                "names": _ee_pose_names() if first["ee_pose"].shape[1] == 14 else None},
    }
    columns = {"observation.state": "joint_pos", "action": "action", "observation.ee_pose": "ee_pose"}
    videos: dict[str, _VideoFiles] = {}
    for cam in cameras:
        h, w = first[f"rgb/{cam}"].shape[1:3]
        key = f"observation.images.{cam}"
        he, we = h + h % 2, w + w % 2
        features[key] = {"dtype": "video", "shape": [he, we, 3], "names": ["height", "width", "channels"],
                         "info": {"video.height": he, "video.width": we, "video.codec": "h264",
                                  "video.pix_fmt": "yuv420p", "video.is_depth_map": False, "video.fps": fps,
                                  "video.channels": 3, "has_audio": False}}
        videos[key] = _VideoFiles(out, key, fps, (he, we), crf, gop)
    features.update(DEFAULT_FEATURES)
    schema = pa.schema(
        [pa.field(k, pa.list_(pa.float32(), ft["shape"][0])) for k, ft in features.items()
         if ft["dtype"] == "float32" and ft["shape"] != [1]]
        + [pa.field("timestamp", pa.float32())]
        + [pa.field(k, pa.int64()) for k in ("frame_index", "episode_index", "index", "task_index")],
        metadata={b"huggingface": json.dumps({"info": {"features": _hf_features(features)}}).encode()})

    # From here on `out` holds only what this export writes: a failure part way (a damaged episode file, a
    # full disk) removes it again, so no half dataset is left that a later export would refuse to replace.
    existed = out.is_dir()
    try:
        (out / "meta").mkdir(parents=True, exist_ok=True)
        data_chunk, data_file, writer = 0, 0, None
        data_path = None
        episode_rows: list[dict] = []
        episode_stats: list[dict[str, dict]] = []
        total = 0
        try:
            for ep_index, rec in enumerate(kept):
                arrays = first if ep_index == 0 else store.load(rec["episode"])
                n = len(arrays["action"])
                frame_index = np.arange(n, dtype=np.int64)
                cols = {k: np.ascontiguousarray(arrays[src], np.float32) for k, src in columns.items()}
                cols.update({
                    "timestamp": (frame_index / fps).astype(np.float32),
                    "frame_index": frame_index,
                    "episode_index": np.full(n, ep_index, np.int64),
                    "index": np.arange(total, total + n, dtype=np.int64),
                    "task_index": np.zeros(n, np.int64),
                })
                table = pa.table({k: pa.FixedSizeListArray.from_arrays(pa.array(v.reshape(-1)), v.shape[1])
                                  if v.ndim == 2 else pa.array(v) for k, v in cols.items()}, schema=schema)
                if writer is not None and data_path.stat().st_size / 2**20 >= DATA_FILES_SIZE_IN_MB:
                    writer.close()
                    writer = None
                    data_chunk, data_file = _next_file(data_chunk, data_file)
                if writer is None:
                    data_path = out / DATA_PATH.format(chunk_index=data_chunk, file_index=data_file)
                    data_path.parent.mkdir(parents=True, exist_ok=True)
                    writer = pq.ParquetWriter(data_path, schema, compression="snappy")
                writer.write_table(table)

                stats = {k: vector_stats(v) for k, v in cols.items()}
                row = {"episode_index": ep_index, "tasks": [task], "length": n,
                       "data/chunk_index": data_chunk, "data/file_index": data_file,
                       "dataset_from_index": total, "dataset_to_index": total + n}
                for key, vid in videos.items():
                    frames = arrays[f"rgb/{key.removeprefix('observation.images.')}"]
                    if len(frames) != n:
                        raise DatasetError(f"episode {rec['episode']}: {len(frames)} {key} frames for {n} actions")
                    row.update(vid.add_episode(frames))
                    stats[key] = image_stats(frames)
                for key, s in stats.items():
                    for k, v in s.items():
                        row[f"stats/{key}/{k}"] = np.asarray(v).tolist()
                row["meta/episodes/chunk_index"] = 0
                row["meta/episodes/file_index"] = 0
                episode_rows.append(row)
                episode_stats.append(stats)
                total += n
        finally:
            if writer is not None:
                writer.close()
            for vid in videos.values():
                vid.close()

        ep_path = out / EPISODES_PATH.format(chunk_index=0, file_index=0)
        ep_path.parent.mkdir(parents=True, exist_ok=True)
        pq.write_table(pa.Table.from_pylist(episode_rows), ep_path, compression="snappy")
        pq.write_table(_tasks_table([task]), out / "meta" / "tasks.parquet")

        stats = {key: aggregate([s[key] for s in episode_stats]) for key in episode_stats[0]}
        (out / "meta" / "stats.json").write_text(json.dumps(dataset_stats_json(stats, columns), indent=4))
        info = {
            "codebase_version": CODEBASE_VERSION,
            "robot_type": robot_type,
            "total_episodes": len(kept),
            "total_frames": total,
            "total_tasks": 1,
            "chunks_size": CHUNKS_SIZE,
            "data_files_size_in_mb": DATA_FILES_SIZE_IN_MB,
            "video_files_size_in_mb": VIDEO_FILES_SIZE_IN_MB,
            "fps": fps,
            "splits": {"train": f"0:{len(kept)}"},
            "data_path": DATA_PATH,
            "video_path": VIDEO_PATH if videos else None,
            "features": features,
        }
        (out / "meta" / "info.json").write_text(json.dumps(info, indent=4))
        # What an evaluation of a policy trained on this export must observe (`policies.lerobot_policy`).
        (out / SOURCE_META).write_text(json.dumps({k: meta.get(k) for k in SOURCE_KEYS}, indent=2))
    except BaseException:
        _discard(out, keep_folder=existed)
        raise
    return info
