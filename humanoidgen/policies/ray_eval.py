"""`hgen policy eval --ray ADDRESS`: each evaluation episode is a call to a warm Ray actor (`ray_pool`). An
actor loads the checkpoint (from its path: on a cluster a shared folder) and builds the task's environment
once, then reuses both for the episodes it is given; episode (checkpoint, seed, i) meets the same scene and
sampling noise as locally."""

from __future__ import annotations

import os
import time
from pathlib import Path

_loaded: dict[tuple, tuple] = {}  # per Ray actor process: the checkpoint in use and its environment


def _model_and_env(path: str, device: str, max_steps: int | None, render: bool, action_steps: int | None = None,
                   randomize: bool = False):
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.policies import checkpoint as ck
    from humanoidgen.policies.rollout import env_config_for, with_action_steps

    key = (path, os.path.getmtime(path), device, max_steps, render, action_steps, randomize)
    if key not in _loaded:
        for _, env in _loaded.values():
            env.close()
        _loaded.clear()
        model, meta = ck.load_policy(Path(path), device)
        model = with_action_steps(model, action_steps)
        env = HumanoidTaskEnv(meta["task"], config=env_config_for(model.name, model.cfg, meta, max_steps, randomize),
                              render_mode="rgb_array" if render else None)
        _loaded[key] = (model, env)
    return _loaded[key]


def remote_episode(path: str, seed: int, i: int, device: str, max_steps: int | None, video_dir: str | None,
                   action_steps: int | None = None, randomize: bool = False):
    """The body of one call on a Ray actor: one closed-loop episode, as an EpisodeOutcome."""
    try:  # see tests/conftest.py: torch's triton must be imported before an EGL context exists
        import diffusers.utils.torch_utils  # noqa: F401
    except ImportError:
        pass
    import torch

    from humanoidgen.envs.config import EVAL_SEED_BASE
    from humanoidgen.policies.rollout import MAX_EPISODES_PER_SEED, EpisodeOutcome, _video, rollout
    from humanoidgen.policies.train import resolve_device

    device = resolve_device(device)
    model, env = _model_and_env(path, device, max_steps, video_dir is not None, action_steps, randomize)
    number = MAX_EPISODES_PER_SEED * seed + i
    video = _video(Path(video_dir) if video_dir else None, Path(path), seed, i, env.config.action_hz)
    t0 = time.perf_counter()
    try:
        ok, steps, final = rollout(model, env, EVAL_SEED_BASE + number, torch.Generator().manual_seed(number), device,
                                   video)
    finally:
        if video is not None:
            video.close()
    return EpisodeOutcome(path, seed, EVAL_SEED_BASE + number, ok, steps, time.perf_counter() - t0, final)


def ray_outcomes(address: str, paths: list[Path], seeds: tuple[int, ...], episodes: int, device: str,
                 max_steps: int | None, video_dir: Path | None, bar, gpus_per_task: float = 0.0,
                 action_steps: int | None = None, randomize: bool = False) -> list:
    """Every (checkpoint, seed, episode) on Ray's warm actors; outcomes in the local order."""
    from humanoidgen.episodes.ray_pool import PoolRunner, pool_for
    from humanoidgen.episodes.ray_session import connect

    items = [(str(Path(p).resolve()), s, i) for p in paths for s in seeds for i in range(episodes)]
    video = str(Path(video_dir).resolve()) if video_dir is not None else None
    outcomes = []
    with connect(address) as session:
        slots = session.cpu_slots(1.0)
        runner = PoolRunner(pool_for(session.ray, slots, gpus_per_task), slots, remote_episode,
                            lambda it: (*it, device, max_steps, video, action_steps, randomize))
        for _, outcome in runner.results(items):
            outcome.checkpoint = str(paths[[str(Path(p).resolve()) for p in paths].index(outcome.checkpoint)])
            outcomes.append(outcome)
            bar.update(1)
            bar.set_postfix_str(f"success {sum(o.success for o in outcomes)}/{len(outcomes)}")
    return outcomes
