"""Gymnasium environments, one per built-in task: `gymnasium.make("humanoidgen/<task>-v0", ...)` after
`import humanoidgen.envs` (keyword arguments are `TaskEnvConfig` fields or `config=`, plus `render_mode`).
A task YAML of one's own: `HumanoidTaskEnv("path/to/task.yaml")`."""

from __future__ import annotations

import os

# Off-screen rendering; it must be chosen before mujoco is first imported.
os.environ.setdefault("MUJOCO_GL", "egl")

import gymnasium as gym  # noqa: E402

from humanoidgen.envs.config import EVAL_SEED_BASE, TaskEnvConfig  # noqa: E402
from humanoidgen.envs.task_env import HumanoidTaskEnv  # noqa: E402

ENTRY_POINT = "humanoidgen.envs.task_env:HumanoidTaskEnv"


def env_id(task: str) -> str:
    return f"humanoidgen/{task}-v0"


def register_all() -> list[str]:
    """Register every built-in task (again registering an id is a no-op)."""
    from humanoidgen.tasks.registry import task_names

    ids = []
    for name in task_names():
        if env_id(name) not in gym.registry:
            gym.register(env_id(name), entry_point=ENTRY_POINT, kwargs={"task": name}, disable_env_checker=False)
        ids.append(env_id(name))
    return ids


register_all()

__all__ = ["EVAL_SEED_BASE", "HumanoidTaskEnv", "TaskEnvConfig", "env_id", "register_all"]
