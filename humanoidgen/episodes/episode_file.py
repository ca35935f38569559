"""One episode file: a zip of `.npy` members, state and actions deflated, image stacks Zstandard-compressed
frame by frame (`npy_zstd`), written to a temporary name, synced and renamed; read back whole, with a damaged
file named as such. The dataset (`dataset.EpisodeStore`) keeps the index and decides what is kept."""

from __future__ import annotations

import os
import zipfile
from collections.abc import Collection
from pathlib import Path
from typing import Any

import numpy as np

from humanoidgen.episodes.npy_zstd import SUFFIX as ZSTD_SUFFIX
from humanoidgen.episodes.npy_zstd import NpyZstdStream, compress_stack, read_member, write_member

# Chosen by measurement on a 124-frame, six-camera 320x240 episode (287 MB of arrays; bench/episode_compression.py,
# bench/results/collection_compression.json): with image stacks time-fastest, level 1 writes 15.8 MB in 1.4 s,
# 3 writes 14.9 MB in 1.4 s, 6 writes 12.5 MB in 3.2 s, 9 writes 12.0 MB in 6.2 s (row-major: 34.4 MB at level 3);
# lzma and bzip2 (--slow) write 4-8 MB but take about 40 s, longer than the episode.
DEFLATE_LEVEL = 3
_IMAGE_PREFIXES = ("rgb/", "depth/")  # frame stacks, stored Zstandard-compressed (npy_zstd)


class DatasetError(RuntimeError):
    pass


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


def _read_episode(path: Path, keys: Collection[str] | None = None) -> dict[str, np.ndarray]:
    try:
        return read_episode(path, keys)
    except Exception as exc:  # noqa: BLE001 - any failure to decode the bytes means the file is damaged
        raise DatasetError(f"{path} is damaged ({_reason(exc)}); continue the collection with --resume "
                           "to collect it again") from None


def read_episode(path: Path, keys: Collection[str] | None = None) -> dict[str, np.ndarray]:
    """Every array of an episode file as stored (depth in uint16 millimetres), or only those named in `keys`:
    `.npy` members (format 1 and 2 files hold only those) and Zstandard-compressed `.npy.zst` image stacks.
    Reading a member checks its CRC (and a stack's zstd checksum)."""
    out = {}
    with zipfile.ZipFile(path) as zf:
        for name in zf.namelist():
            if name.endswith(ZSTD_SUFFIX):
                key, zstd = name[: -len(ZSTD_SUFFIX)].replace("__", "/"), True
            elif name.endswith(".npy"):
                key, zstd = name[: -len(".npy")].replace("__", "/"), False
            else:
                raise ValueError(f"unexpected member {name}")
            if keys is not None and key not in keys:
                continue
            with zf.open(name) as member:
                out[key] = read_member(member) if zstd else np.lib.format.read_array(member, allow_pickle=False)
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
