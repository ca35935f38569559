"""A task episode: the task's scene for a seed, its plan, its success predicates, optional recording/video.

The parent (this module) reads the task and the plan file, starts a locked-down plan worker
(`sandbox.runner.SandboxWorker` with `episode_worker.EpisodeSetup`) and sends it the plan's steps one by one
with a wall-time budget each. The worker streams back the robot's commands as it runs; its twin (forked with
the task's scene before any plan code ran: `episodes.replay_twin`) re-simulates them and gives the verdict
and the recorded arrays, so nothing kept rests on the plan's process. The worker cannot write files, so video
frames are streamed back and written here; datasets are written by the caller (`collect`).
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
from humanoidgen.episodes.replay import OverTime, ReplayVerdict, over_time
from humanoidgen.episodes.replay_twin import TwinReplay
from humanoidgen.episodes.result import EpisodeResult, StepResult
from humanoidgen.sandbox.outcome import plain

DEFAULT_STEP_TIMEOUT_S = 300.0
START_TIMEOUT_S = 300.0  # the worker building the task's scene and parsing the plan
MEMORY_LIMIT = 4 << 30
MEMORY_LIMIT_VIDEO = 12 << 30  # the renderer's buffers (recorded images are rendered by the parent: image_job)
# The largest message the parent accepts from an episode's worker: a video frame (640x480 RGB is 0.9 MB), a
# chunk of commands (about 40 kB), the end of the episode (its fingerprint, about 10 kB). A worker cannot
# make the parent hold more than this at once.
MESSAGE_LIMIT = 16 << 20
MAX_EVENTS = 2000  # planner events kept per episode (each cut to MAX_EVENT_CHARS)
MAX_EVENT_CHARS = 500
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


def models_record(task: str, seed: int | None) -> dict | None:
    """The record's `models` (`tasks.models.episode_models`): which model each object of the episode was on,
    when the task has imported ones; None otherwise or for a task that cannot be loaded (its attempt says why)."""
    from humanoidgen.tasks.models import episode_models

    try:
        return episode_models(load_spec(task), seed)
    except (KeyError, ValueError, FileNotFoundError):
        return None


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


def worker_for(req: EpisodeRequest, spec, plan_text: str, on_frame: Callable[[np.ndarray], None] | None = None):
    """A (not yet started) locked-down worker that will hold this episode, with its twin for the replay. What
    it streams goes to its `on_stream`, which `_run_in_worker` sets (`_Streams`): video frames and chunks of
    commands."""
    from humanoidgen.sandbox import SandboxWorker

    setup = EpisodeSetup(spec.model_dump(mode="json"), plan_text, req.seed,
                         req.video if on_frame is not None else None, req.control_hz, req.dressing, req.recorder)
    limit = MEMORY_LIMIT_VIDEO if on_frame is not None else MEMORY_LIMIT
    return SandboxWorker(setup, memory_limit=limit, max_message_bytes=MESSAGE_LIMIT, twin=True)


def start_worker(req: EpisodeRequest):
    """`req`'s worker, started now (forked, its scene built, its twin forked, locked down) for a later
    `run_task_episode(req, worker=...)`: collecting starts the next attempt's worker while one runs."""
    spec = load_spec(req.task)
    worker = worker_for(req, spec, read_plan_text(plan_file(req.task, spec, req.plan_path)))
    worker.start()
    return worker


def run_task_episode(req: EpisodeRequest, on_frame: Callable[[np.ndarray], None] | None = None,
                     render: bool = True, worker=None) -> tuple[EpisodeResult, dict | None]:
    """Run one attempt in a locked-down worker, judged and recorded by its replay in the worker's twin;
    returns the result and, when recording, the arrays (from the replay).

    A successful attempt recorded with cameras is rendered here from the replay's configurations
    (`image_job`): with `render`, into the arrays; without, the arrays carry the `ImageJob` under
    `PENDING_IMAGES`, for `EpisodeStore` to render while it writes the episode, frame by frame.
    `on_frame(rgb)` receives the frames of `req.video` (default: the front camera at 25 fps) as they are
    rendered. Raises PlanFormatError for a plan that cannot be parsed; a step that fails, times out or kills
    its worker is a failed step in the result. `worker`: one `start_worker(req)` started for this request
    (without video); this call closes it."""
    result, verdict = _run_in_worker(req, on_frame, worker)
    if verdict is None or verdict.arrays is None:
        return result, None
    arrays = dict(verdict.arrays)
    if not result.success or verdict.configurations is None:
        return result, arrays
    job = ImageJob(req.task, req.seed, req.dressing, req.recorder, verdict.configurations, verdict.model_stat)
    if render:
        arrays.update(job.render_arrays())
    else:
        arrays[PENDING_IMAGES] = job
    return result, arrays


class _Streams:
    """The worker's stream messages: video frames of the size asked for (at most MAX_VIDEO_S of them) to
    `on_frame`, chunks of commands to the replay; anything else is dropped."""

    def __init__(self, replay: TwinReplay, video: VideoSpec | None, on_frame) -> None:
        from humanoidgen.episodes.action_log import STREAM_KEY

        self.key, self.replay, self.video, self.on_frame = STREAM_KEY, replay, video, on_frame
        self.frames_left = int(MAX_VIDEO_S * video.fps) if video is not None else 0

    def __call__(self, payload) -> None:
        if not isinstance(payload, dict):
            return
        if self.key in payload:
            self.replay.feed(payload[self.key])  # raises OverTime past the plan's time budget
            return
        frame, video = payload.get("frame"), self.video
        if (self.on_frame is None or video is None or self.frames_left <= 0 or not isinstance(frame, np.ndarray)
                or frame.shape != (video.height, video.width, 3) or frame.dtype != np.uint8):
            return
        self.frames_left -= 1
        self.on_frame(frame)


def _run_in_worker(req: EpisodeRequest, on_frame: Callable[[np.ndarray], None] | None, started=None
                   ) -> tuple[EpisodeResult, ReplayVerdict | None]:
    from humanoidgen.sandbox.twin import TwinLost

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
        worker.start()  # (at once, if started ahead) its twin is forked with it
        replay = TwinReplay(worker.twin, spec, req.control_hz)
        worker.on_stream = _Streams(replay, req.video if on_frame is not None else None, on_frame)
        result = None
        try:
            result = _steps(req, spec, worker, replay)
            if isinstance(result, EpisodeResult):  # lost: nothing left to judge
                return result, None
            steps, n_plan, end = result
            ok = bool(steps) and len(steps) == n_plan and all(s.ok for s in steps)
            verdict = replay.finish(end.get("qpos"), end.get("fingerprint"), settle=ok)
        except TwinLost as exc:  # the worker took its twin with it (it died), or the twin broke
            steps = result[0] if isinstance(result, tuple) else []
            return _lost(spec.name, req.seed, [*steps, StepResult(len(steps), "(the replay)", False, str(exc))]), None
    return _finished(spec.name, req.seed, steps, ok, end, verdict), verdict


def _steps(req: EpisodeRequest, spec, worker, replay: TwinReplay):
    """Run the plan's steps; (steps, number of plan steps, the worker's end report), or an EpisodeResult
    when the worker was lost."""
    from humanoidgen.sandbox import SandboxError

    try:
        plan = worker.call(PLAN, timeout_s=START_TIMEOUT_S)
    except SandboxError as exc:
        if exc.outcome.error_type == "PlanFormatError":
            raise PlanFormatError(exc.outcome.message) from None
        raise RuntimeError(f"the plan worker could not start the episode: {exc}") from None
    try:
        plan = [(plain(str(s["title"]), 500, newlines=False), str(s["code"])) for s in plan]
    except (TypeError, KeyError) as exc:
        raise RuntimeError(f"the plan worker sent a malformed plan ({exc})") from None
    steps: list[StepResult] = []
    events: list[str] = []
    timeout = req.step_timeout_s
    fed = 0
    current = (0, "")
    try:
        for i, (title, code) in enumerate(plan):
            current = (i, title)
            out = worker.run_step(code, timeout_s=timeout)
            if out.worker_restarted or not worker.alive:
                steps.append(StepResult(i, title, False, _error(out, timeout), out.seconds))
                break
            info = _control(worker, PROGRESS, timeout)
            new = _events(info["events"], len(events))
            events += new
            sim = (replay.fed - fed) / req.control_hz
            fed = replay.fed
            steps.append(StepResult(i, title, out.ok, "" if out.ok else _error(out, timeout), out.seconds, sim, new))
            if not out.ok:
                break
        if not worker.alive:  # killed by a timeout or died: nothing left to judge
            return _lost(spec.name, req.seed, steps)
        ok = len(steps) == len(plan) and all(s.ok for s in steps)
        end = _control(worker, FINISH, timeout, settle=ok)
        if not isinstance(end, dict):
            raise TypeError("the end of the episode is not a record")
        end["events"] = events + _events(end.get("events"), len(events))
        return steps, len(plan), end
    except OverTime:  # in a step, or in the commands it left to be sent, or while the scene came to rest
        i, title = current if len(steps) <= current[0] else (len(steps), "(the scene coming to rest)")
        steps.append(StepResult(i, title, False, over_time(spec, req.control_hz)))
        return _lost(spec.name, req.seed, steps)
    except (SandboxError, TypeError, KeyError, ValueError, AttributeError) as exc:
        # The worker's own bookkeeping failed or answered nonsense (plan code can break it): a failed
        # episode that says so, not a crash of the caller.
        steps.append(StepResult(len(steps), "(episode bookkeeping)", False,
                                f"the plan worker could not report the episode: {type(exc).__name__}: {exc}"))
        return _lost(spec.name, req.seed, steps)


def _control(worker, name: str, timeout_s: float, **kwargs):
    """A control call to the worker, within the step's time budget (the plan can slow these down too)."""
    from humanoidgen.sandbox import SandboxError

    try:
        return worker.call(name, timeout_s=timeout_s, **kwargs)
    except SandboxError as exc:
        if exc.outcome.error_type == "Timeout":
            raise SandboxError(replace(exc.outcome, message=f"no answer within the step time limit "
                                                            f"(--step-timeout {timeout_s:g} s)")) from None
        raise


def _events(raw, have: int) -> list[str]:
    """At most what is left of MAX_EVENTS planner events from the worker's list, each cut short."""
    if not isinstance(raw, list):
        return []
    return [plain(str(e), MAX_EVENT_CHARS, newlines=False) for e in raw[:max(MAX_EVENTS - have, 0)]]


def _finished(task: str, seed: int | None, steps: list[StepResult], ran: bool, end: dict,
              verdict: ReplayVerdict) -> EpisodeResult:
    """The episode's result: the steps as the worker ran them, the verdict, final poses and simulated time as
    the replay found them; the worker's wall and planning times are only its report."""
    checks = verdict.all_checks()
    ok = ran and verdict.ok

    def number(x) -> float:
        return float(x) if isinstance(x, (int, float)) and not isinstance(x, bool) and np.isfinite(x) else 0.0

    return EpisodeResult(task, seed, ok, checks, steps, number(end.get("wall_seconds")), verdict.sim_seconds,
                         number(end.get("plan_seconds")), verdict.objects, [*end["events"], *verdict.events])


def _error(out, timeout_s: float) -> str:
    """The step's failure as one line: `call: reason`, or `Type: message (line n)`."""
    if out.error_type == "PlanningError":  # already `call: reason`
        return out.message
    if out.error_type == "Timeout":
        return f"Timeout: the step ran past its time limit (--step-timeout {timeout_s:g} s); the worker was stopped"
    if out.error_type == "CodeRejected":
        return f"rejected: {out.message}"
    line = f" (line {out.line})" if out.line else ""
    return f"{out.error_type}: {out.message}{line}"


def _lost(task: str, seed: int | None, steps: list[StepResult]) -> EpisodeResult:
    wall = sum(s.seconds for s in steps)
    return EpisodeResult(task, seed, False, [], steps, wall, sum(s.sim_seconds for s in steps), 0.0, {}, [])
