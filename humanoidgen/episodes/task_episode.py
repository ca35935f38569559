"""A task episode: the task's scene for a seed, its plan, its success predicates, optional recording/video.

The parent (this module) reads the task and the plan file, starts a locked-down plan worker
(`sandbox.runner.SandboxWorker` with `episode_worker.EpisodeSetup`), sends it the plan's steps one by one
with a wall-time budget each, and gets back the step outcomes, the verdict and the recorded arrays. The
worker cannot write files, so video frames are streamed back and written here; datasets are written by the
caller (`collect`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from humanoidgen.episodes.episode_worker import FINISH, PLAN, PROGRESS, EpisodeSetup, VideoSpec
from humanoidgen.episodes.image_job import PENDING_IMAGES, ImageJob
from humanoidgen.episodes.plans import PlanFormatError
from humanoidgen.episodes.recorder import RecorderConfig
from humanoidgen.episodes.runner import EpisodeResult, StepResult
from humanoidgen.sim.env import HumanoidEnv

DEFAULT_STEP_TIMEOUT_S = 300.0
CONTROL_TIMEOUT_S = 300.0  # building the scene, judging, handing back the recording (never its images)
MEMORY_LIMIT = 4 << 30
MEMORY_LIMIT_VIDEO = 12 << 30  # the renderer's buffers (recorded images are rendered by the parent: image_job)
# The largest message the parent accepts from an episode's worker: a step's outcome is small, a recording
# is not. A worker cannot make the parent hold more than this at once.
MESSAGE_LIMIT = 256 << 20
MAX_VIDEO_S = 600.0  # frames past this much video are dropped (a worker cannot fill the disk)


@dataclass
class EpisodeRequest:
    """Everything needed to run one attempt (picklable)."""

    task: str  # a task name or a path to a task YAML
    seed: int | None
    plan_path: str | None = None  # None: the task's reference plan
    recorder: RecorderConfig | None = None
    control_hz: float = 50.0
    step_timeout_s: float = DEFAULT_STEP_TIMEOUT_S
    video: VideoSpec | None = None
    dressing: dict | None = None  # scenes.dressing.SceneDressing.to_dict(): a room and/or a randomized look


def load_spec(task: str):
    from humanoidgen.tasks.registry import load_task

    return load_task(task)


def plan_file(task: str, spec, plan_path: str | None) -> Path:
    """The plan a request runs: the given file or folder, else the task's reference plan."""
    if plan_path is not None:
        return Path(plan_path)
    if spec.plan is None:
        raise FileNotFoundError(f"task {spec.name} has no reference plan; give one with --script")
    if Path(task).suffix in (".yaml", ".yml"):  # a user's task file: its plan sits beside it
        return Path(task).parent / spec.plan
    from humanoidgen.tasks.registry import plan_path as builtin_plan

    return builtin_plan(spec)


def read_plan_text(path: Path) -> str:
    """The plan's text, read here in the parent; it is parsed in the worker."""
    path = Path(path)
    if not path.exists():
        raise PlanFormatError(f"no plan file at {path}")
    if path.is_dir():
        from humanoidgen.episodes.plans import folder_plan_text

        return folder_plan_text(path)
    try:
        return path.read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise PlanFormatError(f"{path}: cannot read the plan ({exc.strerror})") from None


def judge(spec, env: HumanoidEnv) -> list[dict]:
    out = []
    for pred in spec.success:
        r = pred.evaluate(env)
        out.append({"predicate": pred.type, "ok": bool(r.ok), "detail": r.detail})
    return out


def worker_for(req: EpisodeRequest, spec, plan_text: str, on_frame: Callable[[np.ndarray], None] | None = None):
    """A (not yet started) locked-down worker that will hold this episode."""
    from humanoidgen.sandbox import SandboxWorker

    setup = EpisodeSetup(spec.model_dump(mode="json"), plan_text, req.seed, req.recorder,
                         req.video if on_frame is not None else None, req.control_hz, req.dressing)
    limit = MEMORY_LIMIT_VIDEO if on_frame is not None else MEMORY_LIMIT

    video = setup.video
    budget = [int(MAX_VIDEO_S * video.fps) if video is not None else 0]

    def frames(payload) -> None:
        frame = payload.get("frame") if isinstance(payload, dict) else None
        if (on_frame is None or video is None or budget[0] <= 0 or not isinstance(frame, np.ndarray)
                or frame.shape != (video.height, video.width, 3) or frame.dtype != np.uint8):
            return  # only the frames the parent asked for, of the size it asked for
        budget[0] -= 1
        on_frame(frame)

    return SandboxWorker(setup, memory_limit=limit, on_stream=frames, max_message_bytes=MESSAGE_LIMIT)


def start_worker(req: EpisodeRequest):
    """`req`'s worker, started now (forked, locked down, its scene built) for a later
    `run_task_episode(req, worker=...)`: collecting starts the next attempt's worker while one runs."""
    spec = load_spec(req.task)
    worker = worker_for(req, spec, read_plan_text(plan_file(req.task, spec, req.plan_path)))
    worker.start()
    return worker


def run_task_episode(req: EpisodeRequest, on_frame: Callable[[np.ndarray], None] | None = None,
                     render: bool = True, worker=None) -> tuple[EpisodeResult, dict | None]:
    """Run one attempt in a locked-down worker; returns the result and, when recording, the arrays.

    A successful attempt recorded with cameras is rendered here, after its worker has ended (`image_job`):
    with `render`, into the arrays; without, the arrays carry the `ImageJob` under `PENDING_IMAGES`, for
    `EpisodeStore` to render while it writes the episode, frame by frame.
    `on_frame(rgb)` receives the frames of `req.video` (default: the front camera at 25 fps) as they are
    rendered. Raises PlanFormatError for a plan that cannot be parsed; a step that fails, times out or kills
    its worker is a failed step in the result. `worker`: one `start_worker(req)` started for this request
    (without video); this call closes it."""
    result, arrays = _run_in_worker(req, on_frame, worker)
    if arrays is None or "configurations" not in arrays:
        return result, arrays
    try:
        job = ImageJob(req.task, req.seed, req.dressing, req.recorder, arrays.pop("configurations"),
                       arrays.pop("model_stat", None))
    except ValueError as exc:  # the worker's numbers are not a recording: a failed attempt, said so
        result.success = False
        result.checks.append({"predicate": "recording", "ok": False, "detail": f"unusable recording: {exc}"})
        return result, None
    if render:
        arrays.update(job.render_arrays())
    else:
        arrays[PENDING_IMAGES] = job
    return result, arrays


def _run_in_worker(req: EpisodeRequest, on_frame: Callable[[np.ndarray], None] | None, started=None
                   ) -> tuple[EpisodeResult, dict | None]:
    from humanoidgen.sandbox import SandboxError

    spec = load_spec(req.task)
    if started is not None and on_frame is not None:
        started.close()  # started without a video stream: this episode needs one
        started = None
    if started is None:
        text = read_plan_text(plan_file(req.task, spec, req.plan_path))
        if on_frame is not None and req.video is None:
            req = replace(req, video=VideoSpec())
        started = worker_for(req, spec, text, on_frame)
    with started as worker:
        try:
            plan = worker.call(PLAN, timeout_s=CONTROL_TIMEOUT_S)
        except SandboxError as exc:
            if exc.outcome.error_type == "PlanFormatError":
                raise PlanFormatError(exc.outcome.message) from None
            raise RuntimeError(f"the plan worker could not start the episode: {exc}") from None
        try:
            plan = [(str(s["title"]), str(s["code"])) for s in plan]
        except (TypeError, KeyError) as exc:
            raise RuntimeError(f"the plan worker sent a malformed plan ({exc})") from None
        steps: list[StepResult] = []
        sim, events = 0.0, 0
        try:
            for i, (title, code) in enumerate(plan):
                out = worker.run_step(code, timeout_s=req.step_timeout_s)
                if out.worker_restarted or not worker.alive:
                    steps.append(StepResult(i, title, False, _error(out), out.seconds))
                    break
                info = worker.call(PROGRESS, timeout_s=CONTROL_TIMEOUT_S)
                now, log = float(info["sim_time"]), [str(e) for e in info["events"]]
                steps.append(StepResult(i, title, out.ok, "" if out.ok else _error(out), out.seconds, now - sim,
                                        log[events:]))
                sim, events = now, len(log)
                if not out.ok:
                    break
            if not worker.alive:  # killed by a timeout or died: nothing left to judge
                return _lost(spec.name, req.seed, steps), None
            ok = len(steps) == len(plan) and all(s.ok for s in steps)
            return _finished(spec.name, req.seed, steps, len(plan),
                             worker.call(FINISH, render=ok, timeout_s=CONTROL_TIMEOUT_S))
        except (SandboxError, TypeError, KeyError, ValueError, AttributeError) as exc:
            # The worker's own bookkeeping failed or answered nonsense (plan code can break it): a failed
            # episode that says so, not a crash of the caller.
            steps.append(StepResult(len(steps), "(episode bookkeeping)", False,
                                    f"the plan worker could not report the episode: {type(exc).__name__}: {exc}"))
            return _lost(spec.name, req.seed, steps), None


def _finished(task: str, seed: int | None, steps: list[StepResult], n_plan: int, end: dict
              ) -> tuple[EpisodeResult, dict | None]:
    checks = [{"predicate": str(c["predicate"]), "ok": c["ok"] is True, "detail": str(c["detail"])}
              for c in end["checks"]]
    ok = bool(steps) and all(s.ok for s in steps) and len(steps) == n_plan and all(c["ok"] for c in checks)
    objects = end["objects"] if isinstance(end["objects"], dict) else {}
    result = EpisodeResult(task, seed, ok, checks, steps, float(end["wall_seconds"]), float(end["sim_seconds"]),
                           float(end["plan_seconds"]), objects, [str(e) for e in end["events"]])
    arrays = end.get("arrays")
    if isinstance(arrays, dict) and arrays and all(isinstance(v, np.ndarray) for v in arrays.values()):
        return result, arrays
    return result, None


def _error(out) -> str:
    """The step's failure as one line: `call: reason`, or `Type: message (line n)`."""
    if out.error_type == "PlanningError":  # already `call: reason`
        return out.message
    if out.error_type == "CodeRejected":
        return f"rejected: {out.message}"
    line = f" (line {out.line})" if out.line else ""
    return f"{out.error_type}: {out.message}{line}"


def _lost(task: str, seed: int | None, steps: list[StepResult]) -> EpisodeResult:
    wall = sum(s.seconds for s in steps)
    return EpisodeResult(task, seed, False, [], steps, wall, sum(s.sim_seconds for s in steps), 0.0, {}, [])
