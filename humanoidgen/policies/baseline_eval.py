"""The baselines evaluated on a task's scenes: `hgen policy eval --policy random|noop TASK`, and beside every
trained policy's evaluation (`baselines_beside`), on the same scenes (`rollout.run_episodes`' numbering) at
the same action rate.

A baseline observes only the joint positions, so its environment renders nothing (the scenes and the physics
do not depend on what is observed). The random baseline's range: beside a trained policy, the action range
of the demonstrations it was trained on (its action normalizer's); alone, a zarr's (`--data`) or else the
joint limits (the environment's action space)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import torch

from humanoidgen.envs.config import TaskEnvConfig
from humanoidgen.policies.baselines import ActionRange
from humanoidgen.policies.registry import BASELINE_NAMES, baseline_policy
from humanoidgen.policies.report import EvalReport
from humanoidgen.policies.rollout import EvalError, check_scenes, run_episodes


def blind(cfg: TaskEnvConfig) -> TaskEnvConfig:
    """The same task timing with nothing rendered: what a baseline observes."""
    return dataclasses.replace(cfg, cameras=(), depth=False, point_cloud=False)


def joint_limits(env) -> ActionRange:
    return ActionRange.of(env.action_space.low, env.action_space.high, "joint limits")


def demo_range(model, source: str) -> ActionRange:
    """The action range a trained policy's normalizer was fitted on (`normalizer.MinMaxNormalizer`): x =
    (y - offset) / scale at y = -1 and 1; a feature that never changed (scale 1, offset -value) is its value.
    A feature spanning exactly 2.0 has scale 1 too and would read as constant; measured actions never do."""
    norm = model.normalizer
    key = "target" if "target" in norm.keys else "action"  # a relative-frame policy's "action" is target - state
    scale = getattr(norm, f"{key}__scale").detach().cpu().double().numpy()
    offset = getattr(norm, f"{key}__offset").detach().cpu().double().numpy()
    flat = scale == 1.0
    low = np.where(flat, -offset, (-1.0 - offset) / scale)
    high = np.where(flat, -offset, (1.0 - offset) / scale)
    return ActionRange.of(low, high, source)


def zarr_range(path: Path, episodes: int | None = None) -> tuple[ActionRange, dict]:
    """(the action range of a zarr's first `episodes` episodes (all: None), its root attributes)."""
    import zarr

    root = zarr.open_group(str(path), mode="r")
    ends = np.asarray(root["meta/episode_ends"][:])
    stop = int(ends[min(episodes, len(ends)) - 1]) if episodes else int(ends[-1])
    action = np.asarray(root["data/action"][:stop])
    return ActionRange.of(action.min(axis=0), action.max(axis=0), f"demonstrations ({path})"), dict(root.attrs)


def evaluate_baseline(name: str, task: str, episodes: int = 20, seeds: tuple[int, ...] = (0, 1, 2),
                      env_config: TaskEnvConfig | None = None, action_range: ActionRange | None = None,
                      hold: int | None = None, video_dir: Path | None = None, progress: bool = True,
                      env=None) -> EvalReport:
    """One baseline on `task`'s evaluation scenes; `env_config`'s timing is kept and its observations dropped
    (default: the recordings' 10 Hz); `env`: an open blind environment of the task to reuse."""
    from tqdm import tqdm

    from humanoidgen.envs.task_env import HumanoidTaskEnv

    if name not in BASELINE_NAMES:
        raise EvalError(f"unknown baseline {name!r}; baselines: {', '.join(BASELINE_NAMES)}")
    check_scenes(episodes, seeds)
    own = env is None
    if own:
        env = HumanoidTaskEnv(task, config=blind(env_config or TaskEnvConfig()),
                              render_mode="rgb_array" if video_dir is not None else None)
    try:
        if name == "random" and action_range is None:
            action_range = joint_limits(env)
        model = baseline_policy(name, action_range, hold)
        info = {"hold_actions": model.cfg.n_action_steps} if name == "random" else {}
        if name == "random":
            info["action_range"] = action_range.to_dict()
        report = EvalReport(env.task, name, [name], list(seeds), episodes, info=info,
                            scenes="randomized" if env.config.randomize else "clean")
        with tqdm(total=len(seeds) * episodes, unit="episode", desc=f"baseline {name} {env.task}",
                  disable=not progress, dynamic_ncols=True) as bar:
            with torch.no_grad():
                report.outcomes = run_episodes(model, env, name, seeds, episodes, "cpu", video_dir, bar)
    finally:
        if own:
            env.close()
    return report


def baselines_beside(task: str, env_config: TaskEnvConfig, action_range: ActionRange | None, episodes: int,
                     seeds: tuple[int, ...], progress: bool = True, names: tuple[str, ...] = BASELINE_NAMES
                     ) -> dict[str, EvalReport]:
    """Every baseline on the scenes a trained policy was evaluated on, at its action rate and episode length."""
    from humanoidgen.envs.task_env import HumanoidTaskEnv

    env = HumanoidTaskEnv(task, config=blind(env_config))
    try:
        return {n: evaluate_baseline(n, task, episodes, seeds, action_range=action_range, progress=progress, env=env)
                for n in names}
    finally:
        env.close()
