"""Depth as stored in episode files: uint16 millimetres along the optical axis, 0 where the camera saw
nothing within 65.534 m (the background: MuJoCo reports its far clipping plane, about 98 m here).

Rendered depth is float32 metres; millimetres keep every surface within 0.5 mm (the rounding) at a third of
the size, and compress far better. Reading an episode (`EpisodeStore.load`, the exports) turns them back into
float32 metres, with +inf for "nothing seen" (what `sim.pointcloud.depth_to_points` treats as invalid).
"""

from __future__ import annotations

import numpy as np

MM_PER_M = 1000.0
NO_DEPTH = 0
_MAX_MM = np.iinfo(np.uint16).max - 1  # 65534 mm: the deepest surface stored


def encode_depth(depth_m: np.ndarray) -> np.ndarray:
    """float metres -> uint16 millimetres (rounded; 0 for nothing seen, non-finite or beyond 65.534 m)."""
    mm = np.rint(np.asarray(depth_m, np.float64) * MM_PER_M)
    out = np.where(np.isfinite(mm) & (mm > 0) & (mm <= _MAX_MM), mm, NO_DEPTH)
    return out.astype(np.uint16)


def decode_depth(depth_mm: np.ndarray) -> np.ndarray:
    """uint16 millimetres -> float32 metres, +inf where nothing was seen."""
    mm = np.asarray(depth_mm)
    if mm.dtype != np.uint16:
        raise ValueError(f"stored depth is uint16 millimetres, got {mm.dtype}")
    m = mm.astype(np.float32) / np.float32(MM_PER_M)
    m[mm == NO_DEPTH] = np.inf
    return m
