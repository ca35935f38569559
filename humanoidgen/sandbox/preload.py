"""Imported by the plan workers' fork server before it forks anyone: everything a worker needs, so that
each worker starts warm (imports cost about a second; a fork costs milliseconds). Failures are swallowed
here, because the server must come up; the worker that needs a module then reports the import error."""

from __future__ import annotations

import contextlib
import importlib
import os

os.environ.setdefault("MUJOCO_GL", "egl")

_MODULES = (
    "numpy", "mujoco", "pyseccomp", "landlock",  # pyseccomp finds libseccomp through ldconfig: not once locked
    "pydrake.solvers", "ompl",
    "humanoidgen.planning.planner", "humanoidgen.tasks.registry", "humanoidgen.tasks.scene",
    "humanoidgen.episodes.recorder", "humanoidgen.episodes.plans", "humanoidgen.episodes.runner",
    "humanoidgen.episodes.episode_worker", "humanoidgen.episodes.task_episode", "humanoidgen.sim.cameras",
    "humanoidgen.generation.worker", "humanoidgen.planning.snapshot", "humanoidgen.episodes.image_job",
)
for _name in _MODULES:
    with contextlib.suppress(Exception):
        importlib.import_module(_name)


def _warm() -> None:
    """Build the robot's scene once: MuJoCo keeps processed meshes in a process-wide cache, which every
    forked worker then inherits (compiling a scene drops from about 2.3 s to 0.6 s here); compile the
    collision checks' kernel, which a locked-down worker could not write to numba's cache.

    Not here: the recording level of detail and the point-cloud kernel. Workers hand back configurations and
    the collecting process renders and samples the clouds (`image_job`, which warms both up on its own), so
    they cost every fork server's start (about 0.75 s, before the first worker can start) for nothing."""
    import threading

    from humanoidgen.planning import broadphase
    from humanoidgen.sim.scene import SceneBuilder

    def kernel() -> None:
        with contextlib.suppress(Exception):
            broadphase.warm_up()

    # The kernel's load and the meshes' compile overlap (MuJoCo's compile releases the GIL): about 0.5 s off
    # the server's start, so off the first worker's. The thread is joined before any fork.
    loader = threading.Thread(target=kernel, name="hgen-warm-kernel")
    loader.start()
    try:
        SceneBuilder().build()
    finally:
        loader.join()


with contextlib.suppress(Exception):
    _warm()
