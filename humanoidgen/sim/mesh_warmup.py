"""Processing mesh files into MuJoCo's mesh cache ahead of a compile, in threads of their own.

A MuJoCo compile processes each mesh file (its normals, convex hull, bounding-volume tree and inertia) and
keeps the result in a cache of the process, where a later compile of the same file with the same settings
finds it. The robot's collision meshes (610k faces) are most of a scene's first compile (about 0.85 of its
1.1 s here), and MuJoCo spreads them over hardware_concurrency()/2 threads: one on a two-core machine, after
everything else the scene needs has been built. `start` processes them in threads of its own, each
compiling a spec of its share of the files, and can be called as soon as the files are known (the workers'
fork server: right after importing MuJoCo, `robot.robot_collision_meshes`, while it imports the task library
and builds the scene). A compile in this process first waits for it (`SceneBuilder.build` calls `wait`), so
no file is processed twice, and then finds every file in the cache.

A file's entry is the one the scene's own compile would make: the same file under the same model directory,
with the same scale, reference frame, inertia rule, hull size and smoothing, and a collision geom on it
(MuJoCo keys entries by the file and checks scale, inertia, hull size and whether a hull was made). The
scene's compiled model is the same to the bit (tests/test_mesh_warmup.py). A warm-up that fails only costs
its time: the scene's compile processes the file itself, and reports what is wrong with it.
"""

from __future__ import annotations

import contextlib
import os
import threading

import mujoco

_pending: list[threading.Thread] = []
_lock = threading.Lock()


def default_threads() -> int:
    """One per core, up to four (MuJoCo's own compile adds its threads on bigger machines)."""
    return max(1, min(4, os.cpu_count() or 1))


def start(source: mujoco.MjSpec, meshes: list, threads: int | None = None) -> None:
    """Process `meshes` (file meshes of `source`: `mjsMesh` objects) into the cache, in `threads` threads
    with about the same share of faces each; returns at once."""
    shares = _shares(source, meshes, threads or default_threads())
    specs = [_spec_of(source, share) for share in shares if share]
    with _lock:
        for spec in specs:
            thread = threading.Thread(target=_compile, args=(spec,), name="hgen-mesh-warmup", daemon=True)
            thread.start()
            _pending.append(thread)


def wait() -> None:
    """Return once no warm-up is running in this process (at once where none was started)."""
    with _lock:
        pending, _pending[:] = list(_pending), []
    for thread in pending:
        thread.join()


def _compile(spec: mujoco.MjSpec) -> None:
    with contextlib.suppress(Exception):  # the scene's compile processes the file itself, and says what failed
        spec.compile()  # releases the GIL


def _shares(source: mujoco.MjSpec, meshes: list, threads: int) -> list[list]:
    """Largest file first, each to the share with the fewest bytes so far (a file's work follows its size)."""
    folder = os.path.join(source.modelfiledir, source.meshdir)

    def size(mesh) -> int:
        with contextlib.suppress(OSError):
            return os.path.getsize(os.path.join(folder, mesh.file))
        return 0

    shares: list[list] = [[] for _ in range(max(1, threads))]
    totals = [0] * len(shares)
    for mesh in sorted(meshes, key=size, reverse=True):
        k = totals.index(min(totals))
        shares[k].append(mesh)
        totals[k] += size(mesh)
    return shares


def _spec_of(source: mujoco.MjSpec, meshes: list) -> mujoco.MjSpec:
    """A spec of `meshes` only, as `source` would compile them: its model and mesh directories, the meshes'
    own settings, and a collision geom on each (so that its convex hull is made, as a collision geom of the
    scene asks)."""
    spec = mujoco.MjSpec()
    spec.modelfiledir = source.modelfiledir
    spec.meshdir = source.meshdir
    for mesh in meshes:
        spec.add_mesh(name=mesh.name, file=mesh.file, scale=mesh.scale, refpos=mesh.refpos, refquat=mesh.refquat,
                      inertia=mesh.inertia, maxhullvert=mesh.maxhullvert, smoothnormal=mesh.smoothnormal)
        spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=mesh.name)
    return spec
