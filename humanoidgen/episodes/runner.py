"""One episode: build the task's scene for a seed, run the plan step by step, judge success.

Step code is checked (`sandbox.checker`) and executed with a restricted namespace: the planner API, numpy,
math and a few safe builtins. A failing step ends the episode and is reported as data: which step, which call,
why. (LLM-written code runs in the sandbox worker process instead; see `sandbox.runner`.)
"""

from __future__ import annotations

import builtins
import math
import time
import traceback
from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import numpy as np

from humanoidgen.episodes.plans import Plan
from humanoidgen.objects.describe import openness
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning.arm_moves import PlanningError
from humanoidgen.planning.constraints import Const, Constraint
from humanoidgen.planning.planner import HumanoidMotionPlanner
from humanoidgen.sandbox.checker import SAFE_BUILTINS, CodeRejected, check_code
from humanoidgen.sim.env import HumanoidEnv


@dataclass
class StepResult:
    index: int
    title: str
    ok: bool
    error: str = ""  # "<call>: <reason>" or "<ExceptionType>: <message> (line n)"
    seconds: float = 0.0
    sim_seconds: float = 0.0
    events: list[str] = field(default_factory=list)


@dataclass
class EpisodeResult:
    task: str
    seed: int | None
    success: bool
    checks: list[dict]  # each success predicate: {"ok": bool, "detail": str}
    steps: list[StepResult]
    wall_seconds: float
    sim_seconds: float
    plan_seconds: float
    objects: dict[str, dict]  # final pose (and openness) of every object
    events: list[str]

    @property
    def failed_step(self) -> StepResult | None:
        return next((s for s in self.steps if not s.ok), None)

    def to_dict(self) -> dict:
        return asdict(self)


def step_namespace(planner: HumanoidMotionPlanner) -> dict:
    """What plan code may use: the planner API, numpy, math (and the names the paper's prompts use)."""
    return {
        "planner": planner,
        "np": np,
        "math": math,
        "Constraint": Constraint,
        "Const": Const,
        "get_point_in_env": get_point_in_env,
        "get_axis_in_env": get_axis_in_env,
        "HumanoidMotionPlanner": HumanoidMotionPlanner,
    }


def _safe_builtins() -> dict:
    return {name: getattr(builtins, name) for name in SAFE_BUILTINS if hasattr(builtins, name)}


def run_step(code: str, namespace: dict) -> str:
    """Check and execute one step in `namespace`; returns "" on success, else the reason."""
    try:
        checked = check_code(code, set(namespace))
    except CodeRejected as exc:
        return f"rejected: {exc}"
    except SyntaxError as exc:
        return f"SyntaxError: {exc.msg} (line {exc.lineno})"
    namespace["__builtins__"] = _safe_builtins()
    try:
        exec(checked.compile(), namespace)  # noqa: S102 - checked code, restricted builtins
        if checked.defines_step:
            namespace["step"](namespace["planner"])
    except PlanningError as exc:
        return f"{exc.call}: {exc.reason}"
    except Exception as exc:  # the plan's own bug: report it, with the line inside the step
        line = next((f.lineno for f in reversed(traceback.extract_tb(exc.__traceback__)) if f.filename == "<step>"), None)
        return f"{type(exc).__name__}: {exc}" + (f" (line {line})" if line else "")
    return ""


def object_states(env: HumanoidEnv) -> dict[str, dict]:
    out = {}
    for obj in env.scene.objects:
        p, q = env.object_pose(obj.body)
        state = {"p": np.round(p, 4).tolist(), "q": np.round(q, 4).tolist()}
        if (o := openness(env.model, env.data, obj)) is not None:
            state["openness"] = round(o, 3)
        out[f"{obj.type_name}[{obj.obj_id}]"] = state
    return out


def run_plan(env: HumanoidEnv, plan: Plan, planner: HumanoidMotionPlanner,
             judge: Callable[[HumanoidEnv], list[dict]], task: str = "", seed: int | None = None) -> EpisodeResult:
    """Execute `plan` on a built environment and judge the outcome with `judge(env)`."""
    t0, sim0 = time.perf_counter(), env.time
    namespace = step_namespace(planner)
    steps: list[StepResult] = []
    for i, step in enumerate(plan.steps):
        s0, ss0, e0 = time.perf_counter(), env.time, len(planner.events)
        error = run_step(step.code, namespace)
        steps.append(StepResult(i, step.title, not error, error, time.perf_counter() - s0, env.time - ss0,
                                planner.events[e0:]))
        if error:
            break
    checks = judge(env)
    ok = all(s.ok for s in steps) and all(c["ok"] for c in checks)
    return EpisodeResult(task, seed, ok, checks, steps, time.perf_counter() - t0, env.time - sim0,
                         float(sum(planner.plan_seconds)), object_states(env), list(planner.events))
