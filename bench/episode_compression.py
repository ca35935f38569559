"""How episode files compress: size and write/read time of one recorded episode for zip methods and levels,
with image stacks row-major (time-slowest) or Fortran order (time-fastest, what format 2 wrote), and with
image stacks as Zstandard-compressed .npy members (what `EpisodeStore` writes since format 3, `--zstd`
levels). Depth is converted to uint16 millimetres first if the file holds float metres.

Usage: python bench/episode_compression.py DATASET/episodes/episode_000000.npz [--json out.json] [--slow]
                                          [--zstd 1,3,6,9] [--deflate 1,3,6,9]
(--slow adds bzip2 and lzma, ~40 s each on a six-camera episode.)
"""

from __future__ import annotations

import argparse
import io
import json
import time
import zipfile
from pathlib import Path

import numpy as np

from humanoidgen.episodes import npy_zstd
from humanoidgen.episodes.dataset import read_episode
from humanoidgen.episodes.depth_units import encode_depth


def write(arrays: dict[str, np.ndarray], method: int, level: int | None) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", compression=method, compresslevel=level) as zf:
        for key, value in arrays.items():
            with zf.open(key + ".npy", "w", force_zip64=True) as f:
                np.lib.format.write_array(f, value, allow_pickle=False)
    return buf.getvalue()


def zstd_row(arrays: dict[str, np.ndarray], level: int) -> dict:
    """State deflated (level 3), image stacks as zstd-compressed .npy members at `level`, frame by frame."""
    t0 = time.perf_counter()
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", compression=zipfile.ZIP_DEFLATED, compresslevel=3) as zf:
        for key, value in arrays.items():
            if key.startswith(("rgb__", "depth__")):
                npy_zstd.write_member(zf, key, npy_zstd.compress_stack(np.ascontiguousarray(value), level))
            else:
                with zf.open(key + ".npy", "w", force_zip64=True) as f:
                    np.lib.format.write_array(f, value, allow_pickle=False)
    t1 = time.perf_counter()
    back = read_episode(buf)
    t2 = time.perf_counter()
    assert all(np.array_equal(back[k.replace("__", "/")], arrays[k]) for k in arrays)
    row = {"order": "C", "method": "zstd stacks", "level": level, "mb": round(len(buf.getvalue()) / 1e6, 2),
           "write_s": round(t1 - t0, 2), "read_s": round(t2 - t1, 2)}
    print(row, flush=True)
    return row


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("episode", type=Path)
    ap.add_argument("--json", type=Path, default=None)
    ap.add_argument("--slow", action="store_true")
    ap.add_argument("--zstd", default="1,3,6,9", help="Zstandard levels for image stacks ('' for none)")
    ap.add_argument("--deflate", default="1,3,6,9", help="deflate levels for the whole file ('' for none)")
    args = ap.parse_args()
    arrays = {k.replace("/", "__"): v for k, v in read_episode(args.episode).items()}
    for k, v in arrays.items():
        if k.startswith("depth__") and v.dtype != np.uint16:
            arrays[k] = encode_depth(v)
    arrays = {k: np.ascontiguousarray(v) for k, v in arrays.items()}
    frames = len(arrays["action"])
    methods = [("deflate", zipfile.ZIP_DEFLATED, int(lvl)) for lvl in args.deflate.split(",") if lvl]
    if args.slow:
        methods += [("bzip2", zipfile.ZIP_BZIP2, 9), ("lzma", zipfile.ZIP_LZMA, None)]
    rows = [zstd_row(arrays, int(level)) for level in args.zstd.split(",") if level]
    for order in ("C", "F"):
        data = {k: np.asfortranarray(v) if order == "F" and k.startswith(("rgb__", "depth__")) else v
                for k, v in arrays.items()}
        for name, method, level in methods:
            t0 = time.perf_counter()
            blob = write(data, method, level)
            t1 = time.perf_counter()
            with np.load(io.BytesIO(blob)) as z:
                back = {k: z[k] for k in z.files}
            t2 = time.perf_counter()
            assert all(np.array_equal(back[k], arrays[k]) for k in arrays)
            row = {"order": order, "method": name, "level": level, "mb": round(len(blob) / 1e6, 2),
                   "write_s": round(t1 - t0, 2), "read_s": round(t2 - t1, 2)}
            rows.append(row)
            print(row, flush=True)
    out = {"episode": str(args.episode), "frames": frames,
           "raw_mb": round(sum(v.nbytes for v in arrays.values()) / 1e6, 1), "results": rows}
    if args.json is not None:
        args.json.write_text(json.dumps(out, indent=2) + "\n")
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
