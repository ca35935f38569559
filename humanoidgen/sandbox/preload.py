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
    forked worker then inherits (compiling a scene drops from about 2.3 s to 0.6 s here); the decimated
    visual meshes (full and recording detail) are written to the user cache now, by a process that may
    still write."""
    from humanoidgen.sim.fps import warm_up
    from humanoidgen.sim.meshes import recording_faces, visual_detail
    from humanoidgen.sim.scene import SceneBuilder

    from humanoidgen.planning import broadphase

    with contextlib.suppress(Exception):
        warm_up()  # the point-cloud kernel, compiled once here rather than in every worker
    with contextlib.suppress(Exception):
        broadphase.warm_up()  # the collision checks' kernel: loaded or compiled once, before any fork
    SceneBuilder().build()
    with visual_detail(recording_faces(320, 240)):  # the default recording's level of detail
        SceneBuilder().build()


with contextlib.suppress(Exception):
    _warm()
