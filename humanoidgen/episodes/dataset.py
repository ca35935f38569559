"""The episode store that collection writes, one episode at a time, and its exports.

    DIR/meta.json                 task, recorder settings, names of the action/state entries
    DIR/index.jsonl               one line per attempted seed: success, episode file, length, timings
    DIR/episodes/episode_000000.npz   arrays of one kept episode (see EpisodeRecorder)

Each episode file is written to a temporary name and renamed, and its index line is appended only after, so
an interrupted collection loses at most the episode in flight and `--resume` continues from the index.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

FORMAT_VERSION = 1


class DatasetError(RuntimeError):
    pass


@dataclass
class EpisodeStore:
    root: Path

    def __post_init__(self) -> None:
        self.root = Path(self.root)

    @property
    def meta_path(self) -> Path:
        return self.root / "meta.json"

    @property
    def index_path(self) -> Path:
        return self.root / "index.jsonl"

    def episode_path(self, i: int) -> Path:
        return self.root / "episodes" / f"episode_{i:06d}.npz"

    # -- writing ------------------------------------------------------------------------------------
    def create(self, meta: dict, resume: bool = False) -> None:
        if self.meta_path.exists():
            old = json.loads(self.meta_path.read_text())
            if not resume:
                raise DatasetError(f"{self.root} already holds a dataset ({len(self.kept())} episodes); "
                                   "use --resume to continue it or choose another --out")
            if old.get("task") != meta.get("task"):
                raise DatasetError(f"{self.root} holds task {old.get('task')!r}, not {meta.get('task')!r}")
            return
        (self.root / "episodes").mkdir(parents=True, exist_ok=True)
        _atomic_write(self.meta_path, json.dumps({"format_version": FORMAT_VERSION, **meta}, indent=2).encode())

    def add(self, record: dict, arrays: dict[str, np.ndarray] | None) -> dict:
        """Append an attempt; with `arrays` (a kept episode) its file is written first."""
        record = dict(record)
        if arrays is not None:
            i = len(self.kept())
            path = self.episode_path(i)
            tmp = path.with_name(path.name + ".tmp.npz")
            np.savez_compressed(tmp, **{k.replace("/", "__"): v for k, v in arrays.items()})
            os.replace(tmp, path)
            record["episode"] = i
            record["length"] = int(len(arrays["action"]))
        with open(self.index_path, "a") as f:
            f.write(json.dumps(record) + "\n")
            f.flush()
            os.fsync(f.fileno())
        return record

    # -- reading ------------------------------------------------------------------------------------
    def meta(self) -> dict:
        if not self.meta_path.exists():
            raise DatasetError(f"no dataset at {self.root} (meta.json missing)")
        return json.loads(self.meta_path.read_text())

    def attempts(self) -> list[dict]:
        if not self.index_path.exists():
            return []
        out = []
        for line in self.index_path.read_text().splitlines():
            if line.strip():
                try:
                    out.append(json.loads(line))
                except json.JSONDecodeError:
                    break  # a line cut short by an interruption: everything before it stands
        return out

    def kept(self) -> list[dict]:
        return [a for a in self.attempts() if a.get("episode") is not None]

    def load(self, i: int) -> dict[str, np.ndarray]:
        path = self.episode_path(i)
        if not path.exists():
            raise DatasetError(f"episode {i} not found ({len(self.kept())} episodes in {self.root})")
        with np.load(path) as z:
            return {k.replace("__", "/"): z[k] for k in z.files}


def _atomic_write(path: Path, data: bytes) -> None:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_bytes(data)
    os.replace(tmp, path)


def export_zarr(store: EpisodeStore, out: Path, image_camera: str = "head") -> dict[str, tuple]:
    """The Diffusion Policy / DP3 layout: data/{state, action, point_cloud, img, depth}, meta/episode_ends."""
    import zarr

    kept = store.kept()
    if not kept:
        raise DatasetError(f"{store.root} has no episodes to export")
    episodes = [store.load(k["episode"]) for k in kept]
    ends = np.cumsum([len(e["action"]) for e in episodes]).astype(np.int64)
    columns = {"state": "joint_pos", "action": "action", "point_cloud": "point_cloud",
               "img": f"rgb/{image_camera}", "depth": f"depth/{image_camera}", "ee_pose": "ee_pose"}
    root = zarr.open_group(str(out), mode="w")
    data = root.create_group("data")
    shapes = {}
    for name, key in columns.items():
        if key not in episodes[0]:
            continue
        arr = np.concatenate([e[key] for e in episodes])
        chunks = (min(len(arr), 100),) + arr.shape[1:]
        data.create_array(name, shape=arr.shape, dtype=arr.dtype, chunks=chunks)[:] = arr
        shapes[name] = arr.shape
    meta = root.create_group("meta")
    meta.create_array("episode_ends", shape=ends.shape, dtype=ends.dtype)[:] = ends
    shapes["episode_ends"] = ends.shape
    return shapes
