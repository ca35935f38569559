"""A task episode: the task's scene for a seed, its plan, its success predicates, optional recording/video."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from humanoidgen.episodes.plans import Plan, load_plan
from humanoidgen.episodes.recorder import EpisodeRecorder, RecorderConfig
from humanoidgen.episodes.runner import EpisodeResult, run_plan
from humanoidgen.planning.planner import HumanoidMotionPlanner
from humanoidgen.sim.env import HumanoidEnv

@dataclass
class EpisodeRequest:
    """Everything a worker process needs to run one attempt (picklable)."""

    task: str  # a task name or a path to a task YAML
    seed: int | None
    plan_path: str | None = None  # None: the task's reference plan
    recorder: RecorderConfig | None = None
    control_hz: float = 50.0


def load_spec(task: str):
    from humanoidgen.tasks.registry import load_task

    return load_task(task)


def plan_for(task: str, spec, plan_path: str | None) -> Plan:
    if plan_path is not None:
        return load_plan(Path(plan_path))
    if spec.plan is None:
        raise FileNotFoundError(f"task {spec.name} has no reference plan; give one with --script")
    if Path(task).suffix in (".yaml", ".yml"):  # a user's task file: its plan sits beside it
        return load_plan(Path(task).parent / spec.plan)
    from humanoidgen.tasks.registry import plan_path as builtin_plan

    return load_plan(builtin_plan(spec))


def judge(spec, env: HumanoidEnv) -> list[dict]:
    out = []
    for pred in spec.success:
        r = pred.evaluate(env)
        out.append({"predicate": pred.type, "ok": bool(r.ok), "detail": r.detail})
    return out


def run_task_episode(req: EpisodeRequest, observers: tuple = ()) -> tuple[EpisodeResult, dict | None]:
    """Run one attempt; returns the result and, when recording, the episode's arrays.

    `observers` are called after every control step with the action (e.g. a VideoWriter); each gets
    `attach(env)` first when it has that method."""
    from humanoidgen.tasks.scene import build_scene

    spec = load_spec(req.task)
    plan = plan_for(req.task, spec, req.plan_path)
    _, env = build_scene(spec, req.seed)
    if req.control_hz != env.control_hz:
        env = HumanoidEnv(env.scene, control_hz=req.control_hz)
    recorder = EpisodeRecorder(env, req.recorder) if req.recorder is not None else None
    for obs in observers:
        if hasattr(obs, "attach"):
            obs.attach(env)
    hooks = [h for h in (recorder, *observers) if h is not None]
    planner = HumanoidMotionPlanner(env, seed=req.seed or 0,
                                    on_step=(lambda a: [h(a) for h in hooks]) if hooks else None)
    try:
        result = run_plan(env, plan, planner, lambda e: judge(spec, e), task=spec.name, seed=req.seed)
        arrays = recorder.arrays() if recorder is not None and recorder.frames else None
    finally:
        if recorder is not None:
            recorder.close()
    return result, arrays
