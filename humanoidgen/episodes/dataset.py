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
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from humanoidgen.episodes.depth_units import decode_depth
from humanoidgen.episodes.npy_zstd import SUFFIX as ZSTD_SUFFIX
from humanoidgen.episodes.npy_zstd import NpyZstdStream, compress_stack, read_member, write_member

# 3: image stacks Zstandard-compressed; 2: depth in uint16 millimetres; 1: float32 metres (all are read)
FORMAT_VERSION = 3
# Chosen by measurement on a 124-frame, six-camera 320x240 episode (287 MB of arrays; bench/episode_compression.py,
# bench/results/collection_compression.json): with image stacks time-fastest, level 1 writes 15.8 MB in 1.4 s,
# 3 writes 14.9 MB in 1.4 s, 6 writes 12.5 MB in 3.2 s, 9 writes 12.0 MB in 6.2 s (row-major: 34.4 MB at level 3);
# lzma and bzip2 (--slow) write 4-8 MB but take about 40 s, longer than the episode.
DEFLATE_LEVEL = 3
_IMAGE_PREFIXES = ("rgb/", "depth/")  # frame stacks, stored Zstandard-compressed (npy_zstd)
_EPISODE_FILE = re.compile(r"^episode_(\d+)\.npz$")

log = logging.getLogger(__name__)


class DatasetError(RuntimeError):
    pass


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
            for line in self.repair():
                log.warning("%s", line)
            return
        (self.root / "episodes").mkdir(parents=True, exist_ok=True)
        _atomic_write(self.meta_path, json.dumps({"format_version": FORMAT_VERSION, **meta}, indent=2).encode())

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

    def load(self, i: int) -> dict[str, np.ndarray]:
        path = self.episode_path(i)
        if not path.exists():
            raise DatasetError(f"episode {i} not found ({path.name} missing; {len(self.kept())} episodes "
                               f"in {self.root})")
        return {k: decode_depth(v) if _is_stored_depth(k, v) else v for k, v in _read_episode(path).items()}

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


def write_episode_file(path: Path, arrays: dict[str, np.ndarray]) -> None:
    """An episode file at `path`, written to a temporary name, synced and renamed: never seen half-written."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp.npz")
    with open(tmp, "wb") as f:
        write_episode(f, arrays)
        f.flush()
        os.fsync(f.fileno())  # the rename must never publish a file whose bytes are not on disk
    os.replace(tmp, path)


def write_episode(f, arrays: dict) -> None:
    """An episode file: state arrays as deflated `.npy` members (`DEFLATE_LEVEL`), image stacks as
    Zstandard-compressed ones (`npy_zstd`). Arrays holding an `ImageJob` under `PENDING_IMAGES` have their
    images rendered now, frame by frame, each frame compressed as it comes: no stack is ever held whole."""
    from humanoidgen.episodes.image_job import PENDING_IMAGES

    job = arrays.get(PENDING_IMAGES)
    with zipfile.ZipFile(f, "w", compression=zipfile.ZIP_DEFLATED, compresslevel=DEFLATE_LEVEL) as zf:
        for key, value in arrays.items():
            if key == PENDING_IMAGES:
                continue
            value = np.asarray(value)
            if _is_image_stack(key, value):
                write_member(zf, key, compress_stack(value))
            else:
                _write_npy(zf, key, value)
        if job is not None:
            _write_rendered(zf, job)


def _write_rendered(zf: zipfile.ZipFile, job) -> None:
    layout = job.layout()
    stacks = {k: NpyZstdStream((job.frames, *shape), dtype) for k, (shape, dtype) in layout.items()
              if k.startswith(_IMAGE_PREFIXES)}
    small = {k: np.empty((job.frames, *shape), dtype) for k, (shape, dtype) in layout.items() if k not in stacks}
    for t, frame in job.iter_frames():
        for key, value in frame.items():
            if key in stacks:
                stacks[key].write(value)
            else:
                small[key][t] = value
    for key, stream in stacks.items():
        write_member(zf, key, stream.finish())
    for key, value in small.items():
        _write_npy(zf, key, value)


def _write_npy(zf: zipfile.ZipFile, key: str, value: np.ndarray) -> None:
    with zf.open(key.replace("/", "__") + ".npy", "w", force_zip64=True) as member:
        np.lib.format.write_array(member, value, allow_pickle=False)


def _is_image_stack(key: str, value: np.ndarray) -> bool:
    return key.startswith(_IMAGE_PREFIXES) and value.ndim >= 3


def _is_stored_depth(key: str, value: np.ndarray) -> bool:
    return key.startswith("depth/") and value.dtype == np.uint16


def _read_episode(path: Path) -> dict[str, np.ndarray]:
    try:
        return read_episode(path)
    except Exception as exc:  # noqa: BLE001 - any failure to decode the bytes means the file is damaged
        raise DatasetError(f"{path} is damaged ({_reason(exc)}); continue the collection with --resume "
                           "to collect it again") from None


def read_episode(path: Path) -> dict[str, np.ndarray]:
    """Every array of an episode file as stored (depth in uint16 millimetres): `.npy` members (format 1 and
    2 files hold only those) and Zstandard-compressed `.npy.zst` image stacks. Reading a member checks its
    CRC (and a stack's zstd checksum)."""
    out = {}
    with zipfile.ZipFile(path) as zf:
        for name in zf.namelist():
            with zf.open(name) as member:
                if name.endswith(ZSTD_SUFFIX):
                    out[name[: -len(ZSTD_SUFFIX)].replace("__", "/")] = read_member(member)
                elif name.endswith(".npy"):
                    out[name[: -len(".npy")].replace("__", "/")] = np.lib.format.read_array(member,
                                                                                        allow_pickle=False)
                else:
                    raise ValueError(f"unexpected member {name}")
    return out


def _check_episode(path: Path, length: Any) -> str | None:
    """Why the episode file at `path` is unusable, or None."""
    if not path.exists():
        return "file missing"
    try:
        arrays = read_episode(path)
    except Exception as exc:  # noqa: BLE001
        return _reason(exc)
    if "action" not in arrays:
        return "no action array"
    if isinstance(length, int) and len(arrays["action"]) != length:
        return f"{len(arrays['action'])} frames, the index says {length}"
    return None


def _reason(exc: Exception) -> str:
    text = str(exc).split(". ")[0]  # numpy's pickle message goes on about trusting the file
    if isinstance(exc, ValueError) and "pickled" in text:
        text = "not an episode file"
    return f"{type(exc).__name__}: {text}"[:200]


def _atomic_write(path: Path, data: bytes) -> None:
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def export_zarr(store: EpisodeStore, out: Path, image_camera: str = "head") -> dict[str, tuple]:
    """The Diffusion Policy / DP3 layout: data/{state, action, point_cloud, img, depth}, meta/episode_ends;
    root attributes task, control_hz, camera (the one in data/img) and recorder (the recording settings)."""
    import zarr

    kept = store.kept()
    if not kept:
        raise DatasetError(f"{store.root} has no episodes to export")
    episodes = [store.load(k["episode"]) for k in kept]
    ends = np.cumsum([len(e["action"]) for e in episodes]).astype(np.int64)
    columns = {"state": "joint_pos", "action": "action", "point_cloud": "point_cloud",
               "img": f"rgb/{image_camera}", "depth": f"depth/{image_camera}", "ee_pose": "ee_pose"}
    root = zarr.open_group(str(out), mode="w")
    # What a policy trained on this needs to meet the same task at the same rate (`policies.data`).
    info = store.meta()
    root.attrs.update({"task": info["task"], "control_hz": float(info.get("control_hz", 50.0)),
                       "camera": image_camera, "recorder": info.get("recorder", {})})
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
