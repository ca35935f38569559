"""Collision geometry of an imported mesh: convex parts by CoACD's approximate convex decomposition, cached on
disk by the content hash of the (normalised) mesh and the settings, so a second import of the same mesh, or a
re-fetch of the library, decomposes nothing."""

from __future__ import annotations

import hashlib
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

ENV_COLLISION_CACHE = "HGEN_COLLISION_CACHE"
COACD_FACES = 4000
COACD_SECONDS = float(os.environ.get("HGEN_COACD_SECONDS", 120))  # then hulls of clusters (below)
TIMED_OUT = object()


@dataclass(frozen=True)
class Decomposition:
    """CoACD's settings: `threshold` is its concavity bound (smaller: more, tighter parts)."""

    threshold: float = 0.08
    max_parts: int = 12
    resolution: int = 800
    version: int = 1  # bump to invalidate the cache when the way parts are made changes

    def key(self) -> str:
        return f"t{self.threshold}-p{self.max_parts}-r{self.resolution}-v{self.version}"


def cache_dir() -> Path:
    if value := os.environ.get(ENV_COLLISION_CACHE):
        return Path(value).expanduser()
    from humanoidgen.assets.robot_files import cache_dir as assets_cache

    return assets_cache().parent / "collision"


def content_hash(mesh: trimesh.Trimesh, settings: Decomposition) -> str:
    h = hashlib.sha256()
    h.update(np.ascontiguousarray(np.round(mesh.vertices, 6), dtype="<f8").tobytes())
    h.update(np.ascontiguousarray(mesh.faces, dtype="<i8").tobytes())
    h.update(settings.key().encode())
    return h.hexdigest()


def convex_parts(mesh: trimesh.Trimesh, settings: Decomposition = Decomposition(),
                 cache: Path | None = None) -> list[trimesh.Trimesh]:
    """Convex parts that cover `mesh` (metres, its frame). A single convex mesh is its own hull, undecomposed."""
    hull = mesh.convex_hull
    if mesh.is_watertight and mesh.volume > 0 and mesh.volume >= 0.97 * hull.volume:
        return [hull]
    cache = cache or cache_dir()
    path = cache / f"{content_hash(mesh, settings)}.npz"
    if path.is_file():
        try:
            return _read(path)
        except (OSError, ValueError, KeyError):
            pass  # a broken cache entry is made again
    parts = _decompose(mesh, settings)
    _write(path, parts)
    return parts


def _decompose(mesh: trimesh.Trimesh, settings: Decomposition) -> list[trimesh.Trimesh]:
    """CoACD in a child process (an assertion in its C++ aborts the process that runs it), for at most
    `COACD_SECONDS`: once as set, once with its manifold pre-processing; if both fail, or one runs out of time
    (pybullet's lego brick kept it busy for more than 300 s), hulls of the mesh's vertices split into clusters."""
    v, f = np.asarray(mesh.vertices, float), np.asarray(mesh.faces, int)
    for preprocess in ("auto", "on"):
        result = _coacd_limited(v, f, settings, preprocess, COACD_SECONDS)
        if result is TIMED_OUT:
            break
        if result is None:
            continue
        parts = [p for p in (trimesh.Trimesh(pv, pf, process=True).convex_hull for pv, pf in result)
                 if p.volume > 1e-9]
        if parts:
            return parts
    return _cluster_hulls(mesh, settings.max_parts)


def _coacd_limited(v: np.ndarray, f: np.ndarray, settings: Decomposition, preprocess: str, seconds: float):
    """CoACD's parts; None where its process died, TIMED_OUT where it ran past `seconds` (it is then killed)."""
    import multiprocessing as mp

    ctx = mp.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_coacd_child, args=(send, v, f, settings, preprocess), daemon=True)
    proc.start()
    send.close()
    try:
        if not recv.poll(seconds):
            return TIMED_OUT
        return recv.recv()
    except (EOFError, OSError):  # the child died before it sent anything
        return None
    finally:
        recv.close()
        proc.join(timeout=1.0)
        if proc.is_alive():
            proc.kill()
            proc.join()


def _coacd_child(conn, v: np.ndarray, f: np.ndarray, settings: Decomposition, preprocess: str) -> None:
    try:
        conn.send(_coacd(v, f, settings, preprocess))
    finally:
        conn.close()


def _cluster_hulls(mesh: trimesh.Trimesh, k: int) -> list[trimesh.Trimesh]:
    from scipy.cluster.vq import kmeans2

    pts = np.asarray(trimesh.sample.sample_surface(mesh, 4000, seed=0)[0])
    _, label = kmeans2(pts, min(k, 8), seed=0, minit="++")
    parts = []
    for c in np.unique(label):
        sel = pts[label == c]
        if len(sel) >= 4:
            try:
                parts.append(trimesh.convex.convex_hull(sel))
            except Exception:  # a flat cluster has no hull
                continue
    return [p for p in parts if p.volume > 1e-9] or [mesh.convex_hull]


def _coacd(v: np.ndarray, f: np.ndarray, settings: Decomposition, preprocess: str):
    import coacd

    coacd.set_log_level("error")
    result = coacd.run_coacd(coacd.Mesh(v, f), threshold=settings.threshold, max_convex_hull=settings.max_parts,
                             preprocess_mode=preprocess, preprocess_resolution=30, resolution=settings.resolution,
                             mcts_iterations=60, mcts_max_depth=2, mcts_nodes=12, seed=0)
    return [(np.asarray(pv), np.asarray(pf)) for pv, pf in result]


def _read(path: Path) -> list[trimesh.Trimesh]:
    with np.load(path) as z:
        n = int(z["count"])
        return [trimesh.Trimesh(z[f"v{i}"], z[f"f{i}"], process=False) for i in range(n)]


def _write(path: Path, parts: list[trimesh.Trimesh]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    arrays = {"count": np.array(len(parts))}
    for i, p in enumerate(parts):
        arrays[f"v{i}"], arrays[f"f{i}"] = np.asarray(p.vertices), np.asarray(p.faces)
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".part")
    try:
        with os.fdopen(fd, "wb") as fh:
            np.savez_compressed(fh, **arrays)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def coarse(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """The mesh CoACD decomposes: merged, and decimated to COACD_FACES (the parts are hulls; detail is lost)."""
    m = trimesh.Trimesh(mesh.vertices, mesh.faces, process=True)
    if len(m.faces) > COACD_FACES:
        import fast_simplification

        v, f = fast_simplification.simplify(np.asarray(m.vertices, np.float32), np.asarray(m.faces, np.int64),
                                            target_reduction=1.0 - COACD_FACES / len(m.faces))
        m = trimesh.Trimesh(v, f, process=True)
    return m
