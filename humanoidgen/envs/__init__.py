"""Gymnasium environments, one per built-in task: `gymnasium.make("humanoidgen/<task>-v0", ...)` once
`humanoidgen` is imported (`humanoidgen.gym_ids`), or `gymnasium.make("humanoidgen.envs:humanoidgen/<task>-v0")`
with no import of ours; keyword arguments are `TaskEnvConfig` fields or `config=`, plus `render_mode`.
A task YAML of one's own: `HumanoidTaskEnv("path/to/task.yaml")`."""

from __future__ import annotations

import os

# Off-screen rendering; it must be chosen before mujoco is first imported.
os.environ.setdefault("MUJOCO_GL", "egl")

from humanoidgen.envs.config import EVAL_SEED_BASE, TaskEnvConfig  # noqa: E402
from humanoidgen.envs.task_env import HumanoidTaskEnv  # noqa: E402

from humanoidgen.gym_ids import ENTRY_POINT, env_id, register_all  # noqa: E402

register_all()

__all__ = ["ENTRY_POINT", "EVAL_SEED_BASE", "HumanoidTaskEnv", "TaskEnvConfig", "env_id", "register_all"]
