"""A task as a gymnasium environment: `reset(seed=s)` builds seed s's randomized scene exactly as collection
does (`tasks.scene.build_scene`, then the same control-rate switch as the episode worker), `step(action)` holds
the 26-D joint target for `every` control steps, and success is the task's own predicates.

    env = HumanoidTaskEnv("close_drawer")                       # or gymnasium.make("humanoidgen/close_drawer-v0")
    obs, info = env.reset(seed=100_000)
    obs, reward, terminated, truncated, info = env.step(obs["joint_pos"])

The reward is 1 on the step the task succeeds (which also terminates the episode), else 0; `info["checks"]`
has each predicate's verdict and detail. Episodes are truncated at the task's time limit (or `max_steps`).
"""

from __future__ import annotations

import math
import os
from typing import Any

import gymnasium as gym
import numpy as np

from humanoidgen.envs.config import EVAL_SEED_BASE, TaskEnvConfig
from humanoidgen.envs.observe import Observer, observation_space, render_model_for
from humanoidgen.sim.action import ACTION_DIM


class HumanoidTaskEnv(gym.Env):
    metadata = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, task: str, config: TaskEnvConfig | None = None, render_mode: str | None = None,
                 models: list[str] | dict[str, str] | None = None, randomize_models: bool = False,
                 robot: str | None = None, **config_fields: Any) -> None:
        """`robot` (a robot's name, folder or robot.yaml) must be the process's robot: the simulation's modules
        take theirs when first imported, so a process runs one robot (`HGEN_ROBOT=g1_inspire` before
        importing humanoidgen, as `--robot` does); another one is refused. `models` (["cup=my_mug", "bottle[1]=ketchup"] or {"cup": "my_mug"}) puts the task's objects of a family
        (or one object) on that model; `randomize_models`: each reset draws the other objects' models from their
        families' imported ones, from the seed (as `hgen collect --randomize-models` does); `info["models"]`
        names them."""
        os.environ.setdefault("MUJOCO_GL", "egl")
        from humanoidgen.tasks.models import parse_models, with_models
        from humanoidgen.tasks.registry import load_task
        from humanoidgen.tasks.scene import build_scene

        if config is not None and config_fields:
            raise TypeError("give either config or its fields, not both")
        if robot is not None:
            from humanoidgen.robots import load_robot
            from humanoidgen.sim.layout import ROBOT

            if load_robot(robot).path != ROBOT.path:
                raise ValueError(f"robot {robot!r}: this process's robot is {ROBOT.name} (its simulation modules are "
                                 f"imported); set HGEN_ROBOT={robot} before importing humanoidgen to use it")
        self.config = config if config is not None else TaskEnvConfig(**config_fields)
        if render_mode not in (None, *self.metadata["render_modes"]):
            raise ValueError(f"render_mode must be None or 'rgb_array', got {render_mode!r}")
        self.render_mode = render_mode
        self.metadata = {**self.metadata, "render_fps": self.config.action_hz}
        self.spec_task = load_task(task)
        if models or randomize_models:
            chosen = parse_models(list(models)) if not isinstance(models, dict) else dict(models)
            self.spec_task = with_models(self.spec_task, chosen, randomize_models)
        self.task = self.spec_task.name
        self._build_scene = build_scene
        self.observation_space = observation_space(self.config)
        # Bounds from a scene's actuators (the same robot in every task): what step() clips to anyway.
        _, probe = build_scene(self.spec_task, None, settle_s=0.0)
        lo, hi = probe.clip(np.full(ACTION_DIM, -np.inf)), probe.clip(np.full(ACTION_DIM, np.inf))
        self.action_space = gym.spaces.Box(lo.astype(np.float32), hi.astype(np.float32), (ACTION_DIM,), np.float32)
        self.max_steps = self.config.max_steps or math.ceil(self.spec_task.step_limit(self.config.control_hz)
                                                            / self.config.every)
        self.sim = None
        self._watch = None
        self.seed_used: int | None = None
        self._observer: Observer | None = None
        self._render_rig = None
        self._steps = 0

    # -- gymnasium API -------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict | None = None) -> tuple[dict, dict]:
        super().reset(seed=seed)
        from humanoidgen.sim.env import HumanoidEnv

        # No seed: a scene drawn from the evaluation range, never one collection uses by default.
        scene_seed = int(seed) if seed is not None else EVAL_SEED_BASE + int(self.np_random.integers(1 << 30))
        dressing = self._dressing(scene_seed, (options or {}).get("dressing"))
        _, sim = self._build_scene(self.spec_task, scene_seed, dressing=dressing)
        if self.config.control_hz != sim.control_hz:  # as the episode worker does for another control rate
            sim = HumanoidEnv(sim.scene, control_hz=self.config.control_hz)
        self._close_renderers()
        self.sim, self.seed_used, self._steps = sim, scene_seed, 0
        from humanoidgen.tasks.watch import Watch

        self._watch = Watch(self.spec_task, sim)  # the task's predicates over time see every control step
        self._observer = Observer(sim, self.config, render_model_for(self.spec_task, scene_seed, sim, self.config,
                                                                     dressing))
        info = {"seed": scene_seed, **self._verdict()}
        if dressing is not None:
            info["dressing"] = dressing.to_dict()  # what the scene looked like, as episode metadata stores it
        from humanoidgen.tasks.models import episode_models

        models = episode_models(self.spec_task, scene_seed)
        if models is not None:
            info["models"] = models  # which model each object is on (imported ones by name)
        return self._observer(), info

    def step(self, action: np.ndarray) -> tuple[dict, float, bool, bool, dict]:
        if self.sim is None:
            raise RuntimeError("call reset() before step()")
        action = np.asarray(action, dtype=np.float64)
        for _ in range(self.config.every):
            self.sim.step(action)
            self._watch.observe()
        self._steps += 1
        info = {"seed": self.seed_used, "step": self._steps, **self._verdict()}
        terminated = info["success"]
        truncated = not terminated and self._steps >= self.max_steps
        return self._observer(), float(terminated), terminated, truncated, info

    def render(self) -> np.ndarray | None:
        if self.render_mode is None or self.sim is None:
            return None
        from humanoidgen.sim.cameras import CameraRig

        cfg = self.config
        if self._render_rig is None:
            self._render_rig = CameraRig(self.sim.model, cfg.render_width, cfg.render_height, shadows=True)
        return self._render_rig.render(self.sim.data, cfg.render_camera, depth=False, segmentation=False).rgb

    def close(self) -> None:
        self._close_renderers()
        self.sim = None

    # -- helpers -------------------------------------------------------------------------------------------
    def _dressing(self, scene_seed: int, recorded: dict | None = None):
        """The randomized look and room of this scene (None: the clean tabletop), drawn from its seed; `recorded`
        (reset's `options={"dressing": ...}`, an episode record's `dressing`) replays an episode in the room and look
        it was collected in, whatever the config says; None (a clean collection's record has none) leaves the
        config to say."""
        from humanoidgen.scenes.dressing import RANDOMIZED, SceneDressing, episode_dressing

        if recorded is not None:
            return SceneDressing.from_dict(recorded)
        if not self.config.randomize:
            return None

        return SceneDressing.from_dict(episode_dressing(**RANDOMIZED, seed=scene_seed))

    def _verdict(self) -> dict:
        from humanoidgen.tasks.judge import judge

        checks = judge(self.spec_task, self.sim, self._watch)
        return {"success": all(c["ok"] for c in checks), "checks": checks}

    def _close_renderers(self) -> None:
        if self._observer is not None:
            self._observer.close()
            self._observer = None
        if self._render_rig is not None:
            self._render_rig.close()
            self._render_rig = None
