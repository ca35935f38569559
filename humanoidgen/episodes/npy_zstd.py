"""Image stacks in episode files: a whole `.npy` file (C order, time first) compressed with Zstandard and
stored uncompressed in the episode's zip as `<name>.npy.zst`. `zstd -d` turns a member back into a `.npy`
that `np.load` reads; `EpisodeStore.load` does it in memory.

Why not deflate, as for the other members: deflate looks back 32 kB, less than one 320x240 frame, so it
finds none of the repetition between consecutive frames. Zstandard at level `ZSTD_LEVEL` looks back 2 MB
(nine RGB frames) and finds it in time order, so a stack can be compressed frame by frame as it is rendered
and never has to be held whole. Measured on a 426-frame, six-camera handover_and_storage episode (980 MB
of images; bench/episode_compression.py, bench/results/episode_codecs.json, whole files, a loaded machine):
deflate 3 with the stacks time-fastest 68.0 MB in 4.9 s (row-major 119 MB); zstd 1 37.5 MB in 1.4 s,
3 29.3 MB in 1.4 s, 6 22.9 MB in 4.5 s, 9 21.5 MB in 4.6 s.
"""

from __future__ import annotations

import io
import zipfile
from typing import IO

import numpy as np
import zstandard

ZSTD_LEVEL = 6
SUFFIX = ".npy.zst"


class NpyZstdStream:
    """One (T, ...) array written frame by frame, in time order, as a compressed `.npy` held in memory
    (compressed, a stack is a few percent of its raw size)."""

    def __init__(self, shape: tuple[int, ...], dtype: np.dtype | str, level: int = ZSTD_LEVEL) -> None:
        self.shape, self.dtype = tuple(int(s) for s in shape), np.dtype(dtype)
        header = io.BytesIO()
        np.lib.format.write_array_header_1_0(header, {"descr": np.lib.format.dtype_to_descr(self.dtype),
                                                      "fortran_order": False, "shape": self.shape})
        size = len(header.getvalue()) + int(np.prod(self.shape)) * self.dtype.itemsize
        self._out = io.BytesIO()
        self._z = zstandard.ZstdCompressor(level=level, write_checksum=True).compressobj(size=size)
        self._out.write(self._z.compress(header.getvalue()))
        self._frames = 0

    def write(self, frame: np.ndarray) -> None:
        frame = np.asarray(frame)
        if frame.shape != self.shape[1:] or frame.dtype != self.dtype:
            raise ValueError(f"frame of {frame.shape} {frame.dtype}, the stack holds {self.shape[1:]} {self.dtype}")
        if self._frames >= self.shape[0]:
            raise ValueError(f"the stack holds {self.shape[0]} frames")
        self._out.write(self._z.compress(np.ascontiguousarray(frame).data))
        self._frames += 1

    def finish(self) -> bytes:
        if self._frames != self.shape[0]:
            raise ValueError(f"{self._frames} of {self.shape[0]} frames written")
        self._out.write(self._z.flush())
        return self._out.getvalue()


def compress_stack(array: np.ndarray, level: int = ZSTD_LEVEL) -> bytes:
    """A whole (T, ...) stack, compressed as `NpyZstdStream` would have it frame by frame."""
    array = np.asarray(array)
    stream = NpyZstdStream(array.shape, array.dtype, level)
    for frame in array:
        stream.write(frame)
    return stream.finish()


def write_member(zf: zipfile.ZipFile, key: str, data: bytes) -> None:
    """The compressed stack `data` as member `<key>.npy.zst`, stored as it is (compressing it again would
    gain nothing)."""
    info = zipfile.ZipInfo(key.replace("/", "__") + SUFFIX)
    info.compress_type = zipfile.ZIP_STORED
    with zf.open(info, "w", force_zip64=True) as member:
        member.write(data)


def read_member(fp: IO[bytes]) -> np.ndarray:
    """The array in a `.npy.zst` member, decompressed as it is read (never held twice); the frame checksum
    is verified at the end."""
    with zstandard.ZstdDecompressor().stream_reader(fp, read_across_frames=True) as reader:
        array = np.lib.format.read_array(reader, allow_pickle=False)
        if reader.read(1):
            raise ValueError("data after the array")
    return array
