"""Imported by the plan workers' fork server before it forks anyone: everything a worker needs, so that
each worker starts warm (imports cost about a second; a fork costs milliseconds). Failures are swallowed
here, because the server must come up; the worker that needs a module then reports the import error.

Two cores' worth of work, done side by side (bench/startup.py; `docs/results/recording.md`, start-up):
- a thread compiles a scene as soon as MuJoCo and the scene modules are imported (MuJoCo's compile releases
  the GIL; this thread waits until it has built the scene's spec and started the compile, `scene.before_compile`): what the server was started to build (`forkserver.ENV_WARM`; `hgen run`: its episode's scene,
  `episode_worker.prebuild`, which that episode's worker then takes instead of building it), or else the
  bare robot at its table. Either fills MuJoCo's process-wide cache of processed meshes, which every forked
  worker inherits (a scene's compile drops from about 1.05 s to 0.25 s);
- meanwhile this thread imports the rest (Drake, OMPL, the planner) and loads the collision checks' kernel
  from numba's cache (a locked-down worker could not write it there).
Both are done before the server forks anyone: no thread outlives this module.
"""

from __future__ import annotations

import contextlib
import importlib
import json
import os
import threading

from humanoidgen.sandbox.forkserver import ENV_WARM  # in the server's environment only (taken out here)

os.environ.setdefault("MUJOCO_GL", "egl")

# What a task's scene needs (the object families `objects.library` imports when first asked, numpy's random
# generators for the layout): imported before the scene's thread starts, so that the two threads do not
# import the same modules at once.
_FOR_THE_SCENE = (
    "numpy", "numpy.random", "mujoco", "humanoidgen.sim.scene", "humanoidgen.tasks.registry",
    "humanoidgen.tasks.scene", "humanoidgen.tasks.targets", "humanoidgen.objects.library",
    "humanoidgen.objects.articulated", "humanoidgen.objects.barrier", "humanoidgen.objects.rigid",
    "humanoidgen.objects.safe", "humanoidgen.objects.hands", "humanoidgen.objects.queries",
    "humanoidgen.scenes.dressing", "humanoidgen.episodes.episode_worker",
)
_THE_REST = (
    "pyseccomp", "landlock",  # pyseccomp finds libseccomp through ldconfig: not once locked
    "pydrake.solvers", "ompl",
    "humanoidgen.planning.planner",
    "humanoidgen.episodes.recorder", "humanoidgen.episodes.plans", "humanoidgen.episodes.runner",
    "humanoidgen.episodes.task_episode", "humanoidgen.episodes.replay_twin", "humanoidgen.episodes.action_log",
    "humanoidgen.sim.cameras", "humanoidgen.generation.worker", "humanoidgen.planning.snapshot",
    "humanoidgen.episodes.image_job",
)


def _import(names: tuple[str, ...]) -> None:
    for name in names:
        with contextlib.suppress(Exception):
            importlib.import_module(name)


def _compile_scene(warm: str | None) -> None:
    """Call the function `warm` names ({"call": "package.module:function", "data": ...}: it builds what the
    first worker needs), else compile the bare robot scene (only its meshes are kept, in MuJoCo's cache)."""
    with contextlib.suppress(Exception):
        if warm:
            with contextlib.suppress(Exception):
                what = json.loads(warm)
                module, function = what["call"].split(":")
                getattr(importlib.import_module(module), function)(what["data"])
                return
        from humanoidgen.sim.scene import SceneBuilder

        SceneBuilder().build()


def _load_kernel() -> None:
    """Load the collision checks' kernel (numba) now. Not here: the recording level of detail and the
    point-cloud kernel. Workers hand back configurations and the collecting process renders and samples the
    clouds (`image_job`, which warms both up on its own), so they would cost every server's start (about
    0.75 s) for nothing."""
    with contextlib.suppress(Exception):
        from humanoidgen.planning import broadphase

        broadphase.warm_up()


def _build_scene(warm: str | None, compiling: threading.Event) -> None:
    try:
        _compile_scene(warm)
    finally:
        compiling.set()  # (a scene that failed before its compile)


def _warm() -> None:
    warm = os.environ.pop(ENV_WARM, None)
    _import(_FOR_THE_SCENE)
    compiling = threading.Event()
    scene_module = importlib.import_module("humanoidgen.sim.scene")
    scene_module.before_compile = compiling.set
    scene = threading.Thread(target=_build_scene, args=(warm, compiling), name="hgen-warm-scene")
    scene.start()
    try:
        # The scene's spec first (Python's lock shared with these imports would take it twice as long, and the
        # compile, the longest part, would start that much later); these imports then run beside the compile.
        compiling.wait()
        scene_module.before_compile = None
        _import(_THE_REST)
        _load_kernel()
    finally:
        scene.join()


_warm()
