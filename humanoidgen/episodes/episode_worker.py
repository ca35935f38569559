"""The plan worker's side of one episode (runs inside the locked-down worker; see `sandbox.runner`).

`EpisodeSetup` is what the parent hands the worker: the task spec as data (the parent read the YAML), the
plan's text (the parent read the file; parsing it happens here, so a parser bomb only hits the worker), the
seed, what to record and whether to stream video frames. Calling it builds the scene, the planner and the
recorders and returns the step namespace plus control functions with dunder names: step code cannot name
them (the checker refuses dunder names) and, were it to reach them anyway, could only spoil its own episode.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

PLAN, PROGRESS, FINISH = "__hgen_plan__", "__hgen_progress__", "__hgen_finish__"


@dataclass(frozen=True)
class VideoSpec:
    camera: str = "front"
    width: int = 640
    height: int = 480
    fps: int = 25


@dataclass(frozen=True)
class EpisodeSetup:
    """Picklable: runs in the worker as `setup()` of a SandboxWorker."""

    spec_data: dict
    plan_text: str
    seed: int | None
    recorder: Any = None  # RecorderConfig or None
    video: VideoSpec | None = None
    control_hz: float = 50.0
    dressing: dict | None = None  # scenes.dressing.SceneDressing.to_dict(): a room and/or a look

    def __call__(self) -> dict[str, Any]:
        os.environ.setdefault("MUJOCO_GL", "egl")
        from humanoidgen.episodes.plans import parse_plan
        from humanoidgen.episodes.recorder import EpisodeRecorder
        from humanoidgen.episodes.runner import object_states, step_namespace
        from humanoidgen.episodes.task_episode import judge
        from humanoidgen.planning.planner import HumanoidMotionPlanner
        from humanoidgen.planning.settling import wait_until_still
        from humanoidgen.sim.env import HumanoidEnv
        from humanoidgen.tasks.registry import parse_task
        from humanoidgen.tasks.scene import build_scene

        from humanoidgen.scenes.dressing import SceneDressing

        spec = parse_task(self.spec_data, "<task>")
        dressing = SceneDressing.from_dict(self.dressing) if self.dressing else None
        _, env = build_scene(spec, self.seed, dressing=dressing)
        if self.control_hz != env.control_hz:
            env = HumanoidEnv(env.scene, control_hz=self.control_hz)
        recorder = EpisodeRecorder(env, self.recorder) if self.recorder is not None else None
        frames = _FrameStream(env, self.video) if self.video is not None else None
        hooks = [h for h in (recorder, frames) if h is not None]
        planner = HumanoidMotionPlanner(env, seed=self.seed or 0,
                                        on_step=(lambda a: [h(a) for h in hooks]) if hooks else None)
        clock = [time.perf_counter(), env.time]

        def plan() -> list[dict]:
            clock[0] = time.perf_counter()  # the episode starts now: a worker may be started ahead of its turn
            return [{"title": s.title, "code": s.code} for s in parse_plan(self.plan_text).steps]

        def progress() -> dict:
            """The clock and the planner's events so far (the parent asks after each step)."""
            return {"sim_time": env.time, "events": list(planner.events)}

        def finish(render: bool = True) -> dict:
            """Judge the task, close the recorders and hand back everything the parent keeps. When images are
            recorded, `render` (the parent: every step succeeded) and every success check holds, the arrays
            also hold what the parent renders them from (`image_job`): the recorded configurations and the
            model's clipping-plane statistics. A failed attempt is never rendered."""
            if render is True:  # every step ran: judge the scene once what the last move set going has landed
                wait_until_still(planner)
            checks = judge(spec, env)
            arrays = None
            if recorder is not None and recorder.frames:
                arrays = recorder.arrays(images=False)
                if render is True and all(c["ok"] for c in checks) and recorder.config.renders:
                    from humanoidgen.episodes.image_job import model_stat

                    arrays["configurations"] = np.stack(recorder.configurations)
                    arrays["model_stat"] = model_stat(env.model)
            if recorder is not None:
                recorder.close()
            if frames is not None:
                frames.close()
            return {"task": spec.name, "checks": checks, "wall_seconds": time.perf_counter() - clock[0],
                    "sim_seconds": env.time - clock[1], "plan_seconds": float(sum(planner.plan_seconds)),
                    "objects": object_states(env), "events": list(planner.events), "arrays": arrays}

        ns = step_namespace(planner)
        ns[PLAN], ns[PROGRESS], ns[FINISH] = plan, progress, finish
        return ns


class _FrameStream:
    """Renders one camera at the video's frame rate and streams each frame to the parent, which writes the
    file (the worker cannot write files)."""

    def __init__(self, env, video: VideoSpec) -> None:
        from humanoidgen.sim.cameras import CameraRig

        self.env, self.video = env, video
        self.every = max(1, int(round(env.control_hz / video.fps)))
        self.rig = CameraRig(env.model, video.width, video.height, shadows=True)
        self.count = 0

    def __call__(self, _action: np.ndarray) -> None:
        self.count += 1
        if (self.count - 1) % self.every == 0 and self.rig is not None:
            from humanoidgen.sandbox.runner import stream

            frame = self.rig.render(self.env.data, self.video.camera, depth=False, segmentation=False).rgb
            stream({"frame": frame})

    def close(self) -> None:
        if self.rig is not None:
            self.rig.close()
            self.rig = None
