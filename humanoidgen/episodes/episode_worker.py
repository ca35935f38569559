"""The plan worker's side of one episode (runs inside the locked-down worker; see `sandbox.runner`).

`EpisodeSetup` is what the parent hands the worker: the task spec as data (the parent read the YAML), the
plan's text (the parent read the file; parsing it happens here, so a parser bomb only hits the worker), the
seed and whether to stream video frames. Calling it builds the scene and the planner and returns the step
namespace plus control functions with dunder names: step code cannot name them (the checker refuses dunder
names) and, were it to reach them anyway, could only spoil its own episode.

Nothing this process says is believed: it streams the robot's commands (`action_log`) and the parent
re-simulates them and judges the task there (`episodes.replay`); what the worker reports of its own checks,
state and model is only compared with that replay, to explain a rejection.
"""

from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

PLAN, PROGRESS, FINISH = "__hgen_plan__", "__hgen_progress__", "__hgen_finish__"
MAX_EVENTS_PER_STEP = 200  # planner events handed back per step (the parent caps them again)


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
    video: VideoSpec | None = None
    control_hz: float = 50.0
    dressing: dict | None = None  # scenes.dressing.SceneDressing.to_dict(): a room and/or a look
    recorder: Any = None  # RecorderConfig or None: what the replay in the twin records

    def __call__(self) -> dict[str, Any]:
        os.environ.setdefault("MUJOCO_GL", "egl")
        from humanoidgen.episodes.action_log import ActionLog
        from humanoidgen.episodes.plans import parse_plan
        from humanoidgen.episodes.replay_twin import twin_main
        from humanoidgen.episodes.runner import step_namespace
        from humanoidgen.planning.planner import HumanoidMotionPlanner
        from humanoidgen.planning.settling import wait_until_still
        from humanoidgen.sandbox.runner import stream
        from humanoidgen.sandbox.twin import TWIN
        from humanoidgen.scenes.dressing import SceneDressing
        from humanoidgen.sim.env import HumanoidEnv
        from humanoidgen.sim.fingerprint import fingerprint
        from humanoidgen.tasks.registry import parse_task
        from humanoidgen.tasks.scene import build_scene

        spec = parse_task(self.spec_data, "<task>")
        env = _PREBUILT.pop(scene_key(self.spec_data, self.seed, self.dressing), None)
        if env is None:
            dressing = SceneDressing.from_dict(self.dressing) if self.dressing else None
            _, env = build_scene(spec, self.seed, dressing=dressing)
        if self.control_hz != env.control_hz:
            env = HumanoidEnv(env.scene, control_hz=self.control_hz)
        twin = twin_main(spec, env, self.recorder)  # the replay, forked with this scene before the lockdown
        from humanoidgen.sandbox import runner

        # Outside a worker (bench/sandbox.py runs this in-process to time it) there is nobody to stream to.
        log = ActionLog(env.data, send=stream if runner._channel is not None else None)
        frames = _FrameStream(env, self.video) if self.video is not None else None
        hooks = [h for h in (log, frames) if h is not None]
        planner = HumanoidMotionPlanner(env, seed=self.seed or 0, on_step=lambda a: [h(a) for h in hooks],
                                        targets=env.scene.targets)  # the task's scene carries them
        clock = [time.perf_counter()]
        said = [0]  # events already handed to the parent

        def plan() -> list[dict]:
            clock[0] = time.perf_counter()  # the episode starts now: a worker may be started ahead of its turn
            return [{"title": s.title, "code": s.code} for s in parse_plan(self.plan_text).steps]

        def progress() -> dict:
            """The planner's events since the last call; the commands so far are streamed first."""
            log.flush()
            new = [str(e) for e in planner.events[said[0]:said[0] + MAX_EVENTS_PER_STEP]]
            said[0] = len(planner.events)
            return {"steps": len(log), "events": new}

        def finish(settle: bool = True) -> dict:
            """Hand back the last commands and what this process believes (its checks, final configuration and
            model fingerprint), for the parent to compare with its replay. With `settle` (every step
            succeeded) the robot first holds its command until the scene is still, as the replay checks."""
            if settle is True:
                wait_until_still(planner.ctx)
            log.flush()
            if frames is not None:
                frames.close()
            from humanoidgen.tasks.judge import judge

            return {"task": spec.name, "checks": judge(spec, env), "wall_seconds": time.perf_counter() - clock[0],
                    "plan_seconds": float(sum(planner.plan_seconds)), "steps": len(log),
                    "events": [str(e) for e in planner.events[said[0]:said[0] + MAX_EVENTS_PER_STEP]],
                    "qpos": env.data.qpos.copy(), "fingerprint": fingerprint(env.model, env.data)}

        ns = step_namespace(planner)
        ns[PLAN], ns[PROGRESS], ns[FINISH], ns[TWIN] = plan, progress, finish, twin
        return ns


# The scene the fork server built for the episode it was started for (`prebuild`), by `scene_key`: the one
# worker of that episode takes it instead of building it again (each forked worker has its own copy).
_PREBUILT: dict[str, Any] = {}


def scene_key(spec_data: dict, seed: int | None, dressing: dict | None) -> str:
    """What a task's scene is built from: the task spec as data, the seed and the dressing."""
    return json.dumps([spec_data, seed, dressing], sort_keys=True, separators=(",", ":"))


def prebuild(hint: dict) -> None:
    """In the plan workers' fork server, before any fork (`sandbox.preload`): build the scene of the episode
    `hint` names ({"task": a name or a YAML path, "seed": ..., "dressing": ... as `EpisodeSetup` holds it}),
    exactly as `EpisodeSetup` would, and keep it for the worker whose setup asks for the same scene. Trusted
    data in a process that runs no plan code; a hint that matches no later setup costs only this build
    (which fills MuJoCo's mesh cache all the same)."""
    from humanoidgen.scenes.dressing import SceneDressing
    from humanoidgen.tasks.registry import load_task, parse_task
    from humanoidgen.tasks.scene import build_scene

    seed, dressing = hint.get("seed"), hint.get("dressing")
    spec_data = load_task(str(hint["task"])).model_dump(mode="json")
    spec = parse_task(spec_data, "<task>")  # as the worker gets it: from data
    _, env = build_scene(spec, seed, dressing=SceneDressing.from_dict(dressing) if dressing else None)
    _PREBUILT[scene_key(spec_data, seed, dressing)] = env


class _FrameStream:
    """Renders one camera at the video's frame rate and streams each frame to the parent, which writes the
    file (the worker cannot write files)."""

    def __init__(self, env, video: VideoSpec) -> None:
        self.env, self.video = env, video
        self.every = max(1, int(round(env.control_hz / video.fps)))
        self.rig = None  # made at the first frame: after the twin is forked, no GL context is shared with it
        self.count = 0
        self.closed = False

    def __call__(self, _action: np.ndarray) -> None:
        self.count += 1
        if (self.count - 1) % self.every == 0 and not self.closed:
            from humanoidgen.sandbox.runner import stream
            from humanoidgen.sim.cameras import CameraRig

            if self.rig is None:
                self.rig = CameraRig(self.env.model, self.video.width, self.video.height, shadows=True)
            frame = self.rig.render(self.env.data, self.video.camera, depth=False, segmentation=False).rgb
            stream({"frame": frame})

    def close(self) -> None:
        self.closed = True
        if self.rig is not None:
            self.rig.close()
            self.rig = None
