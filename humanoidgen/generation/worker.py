"""The sandbox worker's side of script generation: one long-lived worker process serves many attempts (and
tasks), because starting one costs seconds. `setup` (module level, so it pickles for "spawn") returns the step
namespace around a *handle* to the planner; `__hgen_reset__` builds a fresh scene and planner behind the handle.

The control functions have dunder names: the runner hides such names from step code and the checker rejects
them, so LLM code cannot reset the scene or call the judge; only the parent can, through `SandboxWorker.call`.
Nothing this process says decides a verdict: `__hgen_judge__` hands back the robot's commands since the
reset (and, for comparison, what this process believes), and the parent replays them (`replay_judge`).
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

RESET, JUDGE = "__hgen_reset__", "__hgen_judge__"
SNAPSHOT, RESTORE = "__hgen_snapshot__", "__hgen_restore__"


class PlannerHandle:
    """Stands in for the current HumanoidMotionPlanner; forwards every attribute to it."""

    def __init__(self) -> None:
        object.__setattr__(self, "_target", None)

    def _bind(self, planner: Any) -> None:
        object.__setattr__(self, "_target", planner)

    def __getattr__(self, name: str) -> Any:
        target = object.__getattribute__(self, "_target")
        if target is None:
            raise RuntimeError("no scene is loaded (the worker restarted); this attempt cannot continue")
        return getattr(target, name)

    def __setattr__(self, name: str, value: Any) -> None:
        setattr(object.__getattribute__(self, "_target"), name, value)

    def __repr__(self) -> str:
        return "<HumanoidMotionPlanner>"


def _round(x: Any, nd: int = 3) -> list[float]:
    return [round(float(v), nd) for v in np.asarray(x).ravel()]


def _log(actions: list[np.ndarray]) -> np.ndarray:
    return np.stack(actions) if actions else np.zeros((0, 26))


def hand_poses(planner: Any) -> dict[str, dict[str, list[float]]]:
    """The hands' starting poses as the prompts show them (position and quaternion, rounded to 1 mm)."""
    return {s: {"p": _round(p.p), "q": _round(p.q)}
            for s, p in (("left", planner.left_hand_init_pose), ("right", planner.right_hand_init_pose))}


def setup() -> dict[str, Any]:
    os.environ.setdefault("MUJOCO_GL", "egl")
    from humanoidgen.episodes.action_log import packed
    from humanoidgen.tasks.judge import judge
    from humanoidgen.episodes.runner import step_namespace
    from humanoidgen.objects.describe import describe_scene
    from humanoidgen.sim.action import validate_action
    from humanoidgen.sim.fingerprint import fingerprint
    from humanoidgen.planning.planner import HumanoidMotionPlanner
    from humanoidgen.planning.settling import wait_until_still
    from humanoidgen.tasks.registry import parse_task
    from humanoidgen.tasks.scene import build_scene

    handle = PlannerHandle()
    state: dict[str, Any] = {}

    def reset(spec_data: dict, seed: int | None) -> dict:
        """Build the task's scene for `seed` and a fresh planner; return the scene as the prompt shows it."""
        spec = parse_task(spec_data, "<generated>")
        scene, env = build_scene(spec, seed)
        actions: list[np.ndarray] = []  # the robot's commands since the reset, for the parent's replay
        # (checked as they come, as the episode's log does: an odd command is refused in the plan's step)
        planner = HumanoidMotionPlanner(env, seed=seed or 0,
                                        on_step=lambda a: actions.append(validate_action(a).copy()),
                                        targets=scene.targets)
        handle._bind(planner)
        state.update(spec=spec, env=env, planner=planner, actions=actions)
        return {"scene": describe_scene(env, as_json=False), "hands": hand_poses(planner)}

    def judge_now() -> dict:
        """The task's predicates on the current state, plus the planner's event log."""
        if "env" not in state:
            raise RuntimeError("no scene is loaded")
        wait_until_still(state["planner"].ctx)  # as an episode is judged: what the last move set going lands first
        env = state["env"]
        return {"checks": judge(state["spec"], env), "events": [str(e) for e in state["planner"].events[:2000]],
                "actions": packed(_log(state["actions"])), "qpos": env.data.qpos.copy(),
                "fingerprint": fingerprint(env.model, env.data)}

    def snapshot() -> dict:
        """The episode's full state (physics and planner bookkeeping), JSON-ready, for a tree search node."""
        from humanoidgen.planning.snapshot import take_snapshot

        return {**take_snapshot(state["planner"].ctx).to_dict(), "actions": packed(_log(state["actions"]))}

    def restore(snap: dict) -> None:
        from humanoidgen.episodes.action_log import unpack
        from humanoidgen.planning.snapshot import Snapshot, restore_snapshot

        restore_snapshot(state["planner"].ctx, Snapshot.from_dict(snap))
        state["actions"][:] = list(unpack(snap.get("actions", packed(np.zeros((0, 26)))), 1 << 22))

    ns = step_namespace(handle)  # type: ignore[arg-type]
    ns[RESET], ns[JUDGE], ns[SNAPSHOT], ns[RESTORE] = reset, judge_now, snapshot, restore
    return ns
