"""What plan code may use (`step_namespace`) and the final object poses an episode reports.

Plan code never runs in this process: `task_episode.run_task_episode` runs it step by step in the
locked-down plan worker (`sandbox.runner`), where `step_namespace` is built. A failing step ends the episode
and is reported as data: which step, which call, why.
"""

from __future__ import annotations

import math

import numpy as np

from humanoidgen.objects.describe import openness
from humanoidgen.objects.queries import get_axis_in_env, get_openness_in_env, get_point_in_env
from humanoidgen.planning.constraints import Const, Constraint
from humanoidgen.planning.planner import HumanoidMotionPlanner
from humanoidgen.sim.env import HumanoidEnv


def step_namespace(planner: HumanoidMotionPlanner) -> dict:
    """What plan code may use: the planner API, numpy, math (and the names the paper's prompts use)."""
    return {
        "planner": planner,
        "np": np,
        "math": math,
        "Constraint": Constraint,
        "Const": Const,
        "Cost": Const,  # upstream's name for the soft relation (its prompts say Const, its plans write Cost)
        "get_point_in_env": get_point_in_env,
        "get_axis_in_env": get_axis_in_env,
        "get_openness_in_env": get_openness_in_env,
        "HumanoidMotionPlanner": HumanoidMotionPlanner,
    }


def object_states(env: HumanoidEnv) -> dict[str, dict]:
    out = {}
    for obj in env.scene.objects:
        p, q = env.object_pose(obj.body)
        state = {"p": np.round(p, 4).tolist(), "q": np.round(q, 4).tolist()}
        if (o := openness(env.model, env.data, obj)) is not None:
            state["openness"] = round(o, 3)
        out[f"{obj.type_name}[{obj.obj_id}]"] = state
    return out
