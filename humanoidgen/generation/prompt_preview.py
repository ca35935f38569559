"""The exact prompt an LLM would get for a task, built here without an endpoint (`hgen generate prompt`).

The plan worker describes the scene to the prompt after its reset; the same description is built here from
trusted code only (the task's scene for the seed, the planner's starting hand poses), so what is printed is
what `generate script` sends on its first attempt, and what the tree search's root expansion shows."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any

from humanoidgen.generation import prompts


@dataclass(frozen=True)
class SceneView:
    """What the prompts show of a task's scene: the objects as described to the author, the hands' poses."""

    task: str
    description: str
    seed: int | None
    spec_data: dict
    scene: Any
    hands: dict


def scene_view(task: str, seed: int | None = None) -> SceneView:
    """Build the task's scene for `seed` and describe it as the plan worker's reset does."""
    os.environ.setdefault("MUJOCO_GL", "egl")
    from humanoidgen.generation.worker import hand_poses
    from humanoidgen.objects.describe import describe_scene
    from humanoidgen.planning.planner import HumanoidMotionPlanner
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    spec = load_task(task)
    scene, env = build_scene(spec, seed)
    planner = HumanoidMotionPlanner(env, seed=seed or 0, targets=scene.targets)
    return SceneView(spec.name, spec.description, seed, spec.model_dump(mode="json"),
                     describe_scene(env, as_json=False), hand_poses(planner))


def script_prompt(view: SceneView) -> str:
    """The first prompt of `hgen generate script` for this scene."""
    from humanoidgen.generation.script_gen import step_names

    return prompts.script_prompt(view.description, view.scene, view.hands, step_names())
