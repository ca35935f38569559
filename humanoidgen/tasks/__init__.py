"""HGen-Bench tasks: specs (objects, randomization, success predicates), loaded from YAML."""

from humanoidgen.tasks.registry import TaskSpecError, list_tasks, load_task, task_names
from humanoidgen.tasks.scene import build_scene
from humanoidgen.tasks.spec import ObjectSpec, Randomization, ResolvedObject, TaskSpec

__all__ = [
           "ObjectSpec",
           "Randomization",
           "ResolvedObject",
           "TaskSpec",
           "TaskSpecError",
           "build_scene",
           "list_tasks",
           "load_task",
           "task_names",
]
