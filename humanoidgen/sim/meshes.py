"""Lighter visual meshes: the upstream STL files hold ~790k triangles, which a software renderer draws at
about 1.5 frames per second. Visual copies decimated to a few thousand triangles each render several times
faster and look the same at camera resolution; collision keeps the original meshes (MuJoCo uses their convex
hulls anyway). Decimated meshes are cached on disk, keyed by the source file's hash and the target size."""

from __future__ import annotations

import contextlib
import contextvars
import hashlib
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from humanoidgen.assets.robot_files import cache_dir

DEFAULT_MAX_FACES = 1500  # full detail: pictures (`hgen render`), the physics model
# Recording detail: faces per mesh for a 640x480 image, scaled with the pixel count (a link spans about the
# same share of the image at any resolution, so the triangles per pixel stay the same) and never below a
# floor that keeps fingers and joints recognisable. 320x240 gets 375 faces per mesh, about a quarter.
_FACES_AT_VGA = DEFAULT_MAX_FACES
_MIN_RECORDING_FACES = 200
_visual_faces: contextvars.ContextVar[int] = contextvars.ContextVar("visual_faces", default=DEFAULT_MAX_FACES)


def recording_faces(width: int, height: int) -> int:
    """Faces per robot visual mesh for recording images of `width` x `height` pixels."""
    scaled = round(_FACES_AT_VGA * width * height / (640 * 480))
    return int(min(DEFAULT_MAX_FACES, max(_MIN_RECORDING_FACES, scaled)))


# The floor plane's rendering grid (a MuJoCo plane's third size): the plane is drawn as squares of this
# side, lit at their corners. At full detail 5 cm: the 8 x 8 m floor is 51k triangles, more than the robot's
# 20k at the recording detail, and drawing them was a third of a recorded frame. Recorded images use 20 cm
# (bench/render_levers.py, bench/results/render_levers.json: RGB off by 0.03 levels on average, no pixel off
# by more than 8, floor depth within 0.01 mm); the physics ignores it.
FLOOR_GRID_M = 0.05
RECORDING_FLOOR_GRID_M = 0.2


def visual_faces() -> int:
    """Faces per visual mesh the scenes built now get (see `visual_detail`)."""
    return _visual_faces.get()


def floor_grid() -> float:
    """The floor's rendering grid for the scenes built now: full detail's, or the recording's below it."""
    return FLOOR_GRID_M if visual_faces() >= DEFAULT_MAX_FACES else RECORDING_FLOOR_GRID_M


@contextlib.contextmanager
def visual_detail(max_faces: int) -> Iterator[None]:
    """Scenes built inside the block get robot visual meshes of at most `max_faces` faces each, and below
    full detail the recording's coarser floor grid (`floor_grid`); the physics is the same: collision keeps
    the original meshes, visual geoms have no mass, a plane's grid is drawing only."""
    if max_faces < 4:
        raise ValueError(f"a visual mesh needs at least 4 faces, got {max_faces}")
    token = _visual_faces.set(int(max_faces))
    try:
        yield
    finally:
        _visual_faces.reset(token)
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


def cluster(verts: np.ndarray, faces: np.ndarray, max_faces: int) -> tuple[np.ndarray, np.ndarray]:
    """Vertex clustering down to at most `max_faces` triangles: vertices in one cell of a grid become their
    mean, collapsed and repeated triangles go. The finest grid (found by bisection) that fits is used.
    Unlike quadric decimation it cannot stall: some upstream meshes are many small pieces that
    `simplify` leaves at 3x the target."""
    if len(faces) <= max_faces:
        return verts, faces
    lo_v = verts.min(axis=0)
    size = float(np.ptp(verts, axis=0).max())

    def at(cell: float) -> tuple[np.ndarray, np.ndarray]:
        keys = np.floor((verts - lo_v) / cell).astype(np.int64)
        _, inverse = np.unique(keys, axis=0, return_inverse=True)
        inverse = inverse.reshape(-1)
        counts = np.bincount(inverse)
        new_v = np.stack([np.bincount(inverse, verts[:, k]) for k in range(3)], axis=1) / counts[:, None]
        f = inverse[faces]
        f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
        _, first = np.unique(np.sort(f, axis=1), axis=0, return_index=True)
        return new_v, f[np.sort(first)].astype(np.int32)

    fine, coarse = size / 4096, size  # face counts shrink as the cells grow
    best = at(coarse)
    for _ in range(14):
        mid = np.sqrt(fine * coarse)
        v, f = at(mid)
        if len(f) <= max_faces:
            coarse, best = mid, (v, f)
        else:
            fine = mid
    return best


def visual_mesh(path: Path, max_faces: int = DEFAULT_MAX_FACES, cache: Path | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The decimated mesh for `path`, from the cache when it is there. Full detail (`DEFAULT_MAX_FACES`) is
    the quadric decimation pictures always had; lighter levels hold their face budget strictly."""
    cache = cache or cache_dir().parent / "meshes"
    digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
    cached = cache / f"{Path(path).stem}-{digest}-{max_faces}.npz"
    if cached.exists():
        with np.load(cached) as z:
            return z["verts"], z["faces"]
    verts, faces = simplify(*read_binary_stl(path), max_faces)
    if max_faces < DEFAULT_MAX_FACES:
        verts, faces = cluster(verts, faces, max_faces)
    try:
        cache.mkdir(parents=True, exist_ok=True)
        tmp = cached.with_name(cached.name + ".tmp.npz")
        np.savez(tmp, verts=verts, faces=faces)
        tmp.replace(cached)  # atomic: a concurrent builder never reads a half-written file
    except OSError:
        pass  # a read-only world (the locked plan worker): the mesh is simply not cached
    return verts, faces
