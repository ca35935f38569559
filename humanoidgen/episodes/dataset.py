"""The episode store that collection writes, one episode at a time, and its exports.

    DIR/meta.json                 task, recorder settings, names of the action/state entries
    DIR/index.jsonl               one line per attempted seed: success, episode file, length, timings
    DIR/episodes/episode_000000.npz   arrays of one kept episode (see EpisodeRecorder)
    DIR/incoming/                 episode files written by Ray tasks, not yet indexed (`adopt`)

Episode files are zip files of `.npy` members: state, actions and point clouds deflated (level
`DEFLATE_LEVEL`), so `np.load` reads them; image stacks (rgb/*, depth/*) as whole `.npy` files compressed with
Zstandard (`rgb__head.npy.zst`, see `episodes.npy_zstd`: it sees the repetition between frames that deflate
cannot, and compresses frame by frame as they are rendered), stored as they are. `read_episode` (and
`load`) read both, and the plain npz files of format 1 and 2 (stacks deflated, in Fortran order). Depth is
stored as uint16 millimetres (`episodes.depth_units`; `load` gives float32 metres back).

Each episode file is written to a temporary name, synced and renamed, and its index line is appended only
after, so an interrupted collection loses at most the episode in flight and `--resume` continues from the index.

Files can still be damaged afterwards (a full disk, a copy cut short, bit rot). Reading tolerates that: a
broken index line is skipped (`index_problems` says which), a broken episode file raises a DatasetError that
names it, and `create(..., resume=True)` repairs the store (`repair`) so collection replaces what was lost.
Nothing is deleted: damaged episode files are renamed to `*.npz.corrupt`, the index before a repair is kept
as `index.jsonl.bak`.
"""

from __future__ import annotations

import json
import logging
import os
import re
import shutil
from collections.abc import Collection
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from humanoidgen.episodes.depth_units import decode_depth
from humanoidgen.episodes.episode_file import (  # noqa: F401 (the dataset's names, re-exported)
    DEFLATE_LEVEL,
    DatasetError,
    _atomic_write,
    _check_episode,
    _is_stored_depth,
    _read_episode,
    _reason,
    read_episode,
    write_episode,
    write_episode_file,
)

# 3: image stacks Zstandard-compressed; 2: depth in uint16 millimetres; 1: float32 metres (all are read)
FORMAT_VERSION = 3
_EPISODE_FILE = re.compile(r"^episode_(\d+)\.npz$")

log = logging.getLogger(__name__)


@dataclass
class _Index:
    """index.jsonl as read: the valid records, what was wrong with the other lines, whether the file ends
    mid-line (so the next append must start a new line)."""

    records: list[dict] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)
    torn_tail: bool = False


@dataclass
class EpisodeStore:
    root: Path
    # What the last `repair` fixed (one sentence each); `create(..., resume=True)` also logs them.
    repaired: list[str] = field(default_factory=list)

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
            old = self.meta()
            if not resume:
                raise DatasetError(f"{self.root} already holds a dataset ({len(self.kept())} episodes); "
                                   "use --resume to continue it or choose another --out")
            if old.get("task") != meta.get("task"):
                raise DatasetError(f"{self.root} holds task {old.get('task')!r}, not {meta.get('task')!r}")
            if old.get("robot", meta.get("robot")) != meta.get("robot"):  # stores from before robots: not checked
                raise DatasetError(f"{self.root} was collected with robot {old.get('robot')!r}, not "
                                   f"{meta.get('robot')!r} (--robot)")
            for line in self.repair():
                log.warning("%s", line)
            return
        (self.root / "episodes").mkdir(parents=True, exist_ok=True)
        _atomic_write(self.meta_path, json.dumps({"format_version": FORMAT_VERSION, **meta}, indent=2).encode())

    def update_meta(self, **fields) -> None:
        """Replace top-level fields of meta.json (atomically: a cut-short write leaves the old file)."""
        meta = self.meta()
        _atomic_write(self.meta_path, json.dumps({**meta, **fields}, indent=2).encode())

    def add(self, record: dict, arrays: dict[str, np.ndarray] | None) -> dict:
        """Append an attempt; with `arrays` (a kept episode) its file is written first."""
        record = dict(record)
        index = self._read_index()
        if arrays is not None:
            i = _next_episode(index.records)
            write_episode_file(self.episode_path(i), arrays)
            record["episode"] = i
            record["length"] = int(len(arrays["action"]))
        self._append(index, record)
        return record

    @property
    def staging_dir(self) -> Path:
        """Where Ray tasks put finished episode files (`write_episode_file`) for `adopt` to index; what is
        left there was never published, and `repair` removes it."""
        return self.root / "incoming"

    def adopt(self, record: dict, staged: Path, length: int) -> dict:
        """Append a kept attempt whose episode file was already written (synced) at `staged`, in this
        store's folder: it is renamed into place, then its index line is appended."""
        record = dict(record)
        index = self._read_index()
        i = _next_episode(index.records)
        os.replace(staged, self.episode_path(i))
        record["episode"] = i
        record["length"] = int(length)
        self._append(index, record)
        return record

    def _append(self, index: _Index, record: dict) -> None:
        with open(self.index_path, "a") as f:
            # A line cut short by an interruption must not swallow this record too.
            f.write(("\n" if index.torn_tail else "") + json.dumps(record) + "\n")
            f.flush()
            os.fsync(f.fileno())

    # -- reading ------------------------------------------------------------------------------------
    def meta(self) -> dict:
        if not self.meta_path.exists():
            raise DatasetError(f"no dataset at {self.root} (meta.json missing)")
        try:
            meta = json.loads(self.meta_path.read_text())
        except (ValueError, UnicodeDecodeError) as exc:
            raise DatasetError(f"{self.meta_path} is not valid JSON ({exc}); restore it from a copy "
                               "(the episodes are untouched)") from None
        if not isinstance(meta, dict) or not isinstance(meta.get("task"), str):
            raise DatasetError(f"{self.meta_path} is not a dataset description (no task name); restore it "
                               "from a copy (the episodes are untouched)")
        return meta

    def attempts(self) -> list[dict]:
        return self._read_index().records

    def index_problems(self) -> list[str]:
        """Lines of index.jsonl that were skipped, one sentence each (a torn last line included)."""
        return self._read_index().problems

    def kept(self) -> list[dict]:
        return [a for a in self.attempts() if a.get("episode") is not None]

    def load(self, i: int, keys: Collection[str] | None = None) -> dict[str, np.ndarray]:
        """Episode i's arrays (depth in metres), or only those named in `keys` (the others are not read)."""
        path = self.episode_path(i)
        if not path.exists():
            raise DatasetError(f"episode {i} not found ({path.name} missing; {len(self.kept())} episodes "
                               f"in {self.root})")
        return {k: decode_depth(v) if _is_stored_depth(k, v) else v for k, v in _read_episode(path, keys).items()}

    # -- checking and repairing -----------------------------------------------------------------------
    def corrupt(self) -> dict[int, str]:
        """Kept episodes whose file is missing, unreadable or not what the index says: episode -> reason.
        Reads every array of every episode (a zip's CRCs are only checked on reading)."""
        out = {}
        for rec in self.kept():
            i = rec["episode"]
            reason = _check_episode(self.episode_path(i), rec.get("length"))
            if reason is not None:
                out[i] = reason
        return out

    def verify(self) -> None:
        """Raise a DatasetError naming every damaged episode file (and the index lines skipped)."""
        bad = self.corrupt()
        if bad:
            raise DatasetError(f"{len(bad)} damaged episode file(s) in {self.root}: " + "; ".join(
                f"{self.episode_path(i).name}: {why}" for i, why in sorted(bad.items())))

    def repair(self) -> list[str]:
        """Make the store safe to append to, keeping everything readable: skipped index lines are dropped
        (the old index is kept as index.jsonl.bak), damaged kept episodes are marked not kept (their files
        renamed to *.npz.corrupt) so a resumed collection replaces them, and episode files the index does not
        name (an interruption between writing a file and its index line) are renamed to *.npz.orphan.
        Returns what was done, one sentence each (also in `self.repaired`)."""
        self.repaired = []
        if self.staging_dir.is_dir():
            shutil.rmtree(self.staging_dir)  # staged by Ray tasks of an interrupted run, never indexed
        if not self.index_path.exists():
            return self.repaired
        index = self._read_index()
        bad = self.corrupt()
        messages = list(index.problems)
        records = []
        for rec in index.records:
            i = rec.get("episode")
            if i in bad:
                rec = {**rec, "success": False, "dropped_episode": i,
                       "error": f"episode file {self.episode_path(i).name} was damaged ({bad[i]}); re-collected"}
                rec.pop("episode")
                rec.pop("length", None)
                messages.append(f"{self.episode_path(i)} is damaged ({bad[i]}): renamed to *.corrupt and "
                                "marked not kept, so it is collected again")
            records.append(rec)
        if index.problems or bad or index.torn_tail:
            shutil.copyfile(self.index_path, self.index_path.with_name("index.jsonl.bak"))
            _atomic_write(self.index_path, "".join(json.dumps(r) + "\n" for r in records).encode())
        for i in bad:
            path = self.episode_path(i)
            if path.exists():
                os.replace(path, path.with_name(path.name + ".corrupt"))
        named = {r["episode"] for r in records if r.get("episode") is not None}
        folder = self.root / "episodes"
        for path in sorted(folder.iterdir()) if folder.is_dir() else []:
            m = _EPISODE_FILE.match(path.name)
            if m and int(m.group(1)) not in named:
                os.replace(path, path.with_name(path.name + ".orphan"))
                messages.append(f"{path} is not in the index (an interrupted write?): renamed to *.orphan")
            elif path.name.endswith(".tmp.npz"):
                path.unlink()  # half-written by an interrupted collection; never published
        self.repaired = messages
        return messages

    def _read_index(self) -> _Index:
        index = _Index()
        if not self.index_path.exists():
            return index
        raw = self.index_path.read_bytes()
        index.torn_tail = bool(raw) and not raw.endswith(b"\n")
        lines = raw.decode("utf-8", errors="replace").split("\n")
        for n, line in enumerate(lines, 1):
            if not line.strip():
                continue
            rec = _parse_record(line)
            if rec is not None:
                index.records.append(rec)
            elif n == len(lines) and index.torn_tail:
                index.problems.append(f"{self.index_path} line {n} was cut short (an interrupted write); skipped")
            else:
                index.problems.append(f"{self.index_path} line {n} is not a valid attempt record; skipped")
        return index


def _parse_record(line: str) -> dict | None:
    """One index line as a record, or None when it is not one (bad JSON, or fields of the wrong type)."""
    try:
        rec = json.loads(line)
    except ValueError:
        return None
    if not isinstance(rec, dict) or not isinstance(rec.get("seed"), int) or not isinstance(rec.get("success"), bool):
        return None
    ep, length = rec.get("episode"), rec.get("length")
    if ep is not None and (not isinstance(ep, int) or isinstance(ep, bool) or ep < 0):
        return None
    if length is not None and (not isinstance(length, int) or isinstance(length, bool)):
        return None
    return rec


def _next_episode(records: list[dict]) -> int:
    """The next episode number: after every number the index names (dropped ones too), so a damaged
    episode's slot is never reused by a file a reader could mistake for it."""
    used = [r[k] for r in records for k in ("episode", "dropped_episode") if isinstance(r.get(k), int)]
    return max(used, default=-1) + 1


def export_zarr(store: EpisodeStore, out: Path, image_camera: str = "head") -> dict[str, tuple]:
    """The Diffusion Policy / DP3 layout: data/{state, action, point_cloud, img, depth}, meta/episode_ends;
    root attributes task, control_hz, camera (the one in data/img) and recorder (the recording settings)."""
    import zarr

    kept = [k["episode"] for k in store.kept()]
    if not kept:
        raise DatasetError(f"{store.root} has no episodes to export")
    # One column of one episode in memory at a time: 200 close_drawer episodes with the head camera's pictures
    # and depth loaded whole took more than 23 GB and were killed for memory.
    ends = np.cumsum([len(store.load(i, ("action",))["action"]) for i in kept]).astype(np.int64)
    starts = np.concatenate([[0], ends[:-1]])
    columns = {"state": "joint_pos", "action": "action", "point_cloud": "point_cloud",
               "img": f"rgb/{image_camera}", "depth": f"depth/{image_camera}", "ee_pose": "ee_pose"}
    root = zarr.open_group(str(out), mode="w")
    # What a policy trained on this needs to meet the same task at the same rate (`policies.data`).
    info = store.meta()
    root.attrs.update({"task": info["task"], "control_hz": float(info.get("control_hz", 50.0)),
                       "camera": image_camera, "recorder": info.get("recorder", {})})
    if info.get("perturbation"):  # a re-recording under an arm offset (`hgen dataset perturb`): said downstream
        root.attrs["perturbation"] = info["perturbation"]
    data = root.create_group("data")
    shapes = {}
    for name, key in columns.items():
        head = store.load(kept[0], (key,)).get(key)  # the first episode's: the column's frame shape and type
        if head is None:
            continue
        shape = (int(ends[-1]),) + head.shape[1:]
        column = data.create_array(name, shape=shape, dtype=head.dtype, chunks=(min(shape[0], 100),) + shape[1:])
        for i, a, b in zip(kept, starts, ends):
            column[a:b] = store.load(i, (key,))[key]
        shapes[name] = shape
    meta = root.create_group("meta")
    meta.create_array("episode_ends", shape=ends.shape, dtype=ends.dtype)[:] = ends
    shapes["episode_ends"] = ends.shape
    return shapes
