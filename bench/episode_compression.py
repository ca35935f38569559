"""How episode files compress: size and write/read time of one recorded episode for zip methods and levels,
with image stacks row-major (time-slowest) or Fortran order (time-fastest, what `EpisodeStore` writes).
Depth is converted to uint16 millimetres first if the file holds float metres.

Usage: python bench/episode_compression.py DATASET/episodes/episode_000000.npz [--json out.json] [--slow]
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

from humanoidgen.episodes.depth_units import encode_depth


def write(arrays: dict[str, np.ndarray], method: int, level: int | None) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", compression=method, compresslevel=level) as zf:
        for key, value in arrays.items():
            with zf.open(key + ".npy", "w", force_zip64=True) as f:
                np.lib.format.write_array(f, value, allow_pickle=False)
    return buf.getvalue()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("episode", type=Path)
    ap.add_argument("--json", type=Path, default=None)
    ap.add_argument("--slow", action="store_true")
    args = ap.parse_args()
    with np.load(args.episode) as z:
        arrays = {k: z[k] for k in z.files}
    for k, v in arrays.items():
        if k.startswith("depth__") and v.dtype != np.uint16:
            arrays[k] = encode_depth(v)
    arrays = {k: np.ascontiguousarray(v) for k, v in arrays.items()}
    frames = len(arrays["action"])
    methods = [("deflate", zipfile.ZIP_DEFLATED, lvl) for lvl in (1, 3, 6, 9)]
    if args.slow:
        methods += [("bzip2", zipfile.ZIP_BZIP2, 9), ("lzma", zipfile.ZIP_LZMA, None)]
    rows = []
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
