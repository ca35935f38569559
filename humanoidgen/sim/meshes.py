"""Lighter visual meshes: the upstream STL files hold ~790k triangles, which a software renderer draws at
about 1.5 frames per second. Visual copies decimated to a few thousand triangles each render several times
faster and look the same at camera resolution; collision keeps the original meshes (MuJoCo uses their convex
hulls anyway). Decimated meshes are cached on disk, keyed by the source file's hash and the target size."""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from humanoidgen.assets.robot_files import cache_dir

DEFAULT_MAX_FACES = 1500
_STL_RECORD = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])


def read_binary_stl(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (N, 3) float64 and triangles (M, 3) int32 of a binary STL, shared vertices merged."""
    data = Path(path).read_bytes()
    if len(data) < 84:
        raise ValueError(f"{path}: too short to be a binary STL")
    n = int(np.frombuffer(data, np.uint32, 1, 80)[0])
    if len(data) < 84 + 50 * n:
        raise ValueError(f"{path}: not a binary STL (expected {n} triangles)")
    rec = np.frombuffer(data, dtype=_STL_RECORD, count=n, offset=84)
    verts, inverse = np.unique(rec["v"].reshape(-1, 3), axis=0, return_inverse=True)
    return verts.astype(np.float64), inverse.reshape(-1, 3).astype(np.int32)


def simplify(verts: np.ndarray, faces: np.ndarray, max_faces: int) -> tuple[np.ndarray, np.ndarray]:
    """Quadric decimation down to about `max_faces` triangles (meshes already that small are kept)."""
    if len(faces) <= max_faces:
        return verts, faces
    import fast_simplification

    v, f = fast_simplification.simplify(verts.astype(np.float32), faces, target_reduction=1 - max_faces / len(faces))
    return np.asarray(v, np.float64), np.asarray(f, np.int32)


def visual_mesh(path: Path, max_faces: int = DEFAULT_MAX_FACES, cache: Path | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The decimated mesh for `path`, from the cache when it is there."""
    cache = cache or cache_dir().parent / "meshes"
    digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
    cached = cache / f"{Path(path).stem}-{digest}-{max_faces}.npz"
    if cached.exists():
        with np.load(cached) as z:
            return z["verts"], z["faces"]
    verts, faces = simplify(*read_binary_stl(path), max_faces)
    try:
        cache.mkdir(parents=True, exist_ok=True)
        tmp = cached.with_name(cached.name + ".tmp.npz")
        np.savez(tmp, verts=verts, faces=faces)
        tmp.replace(cached)  # atomic: a concurrent builder never reads a half-written file
    except OSError:
        pass  # a read-only world (the locked plan worker): the mesh is simply not cached
    return verts, faces
