"""One policy episode in its task's environment: the observation history the policy reads, its action chunks
executed step by step, the task's predicates at the end (`rollout`); shared by local evaluation (`eval.py`) and
Ray evaluation (`ray_eval.py`)."""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch

from humanoidgen.envs.config import EVAL_SEED_BASE, TaskEnvConfig
from humanoidgen.policies.hands import hand_features

MAX_EPISODES_PER_SEED = 1000


class EvalError(ValueError):
    pass


def check_scenes(episodes: int, seeds) -> None:
    """The evaluation scenes asked for exist: episodes per seed in range (they number the scenes), seeds >= 0."""
    if not 1 <= episodes <= MAX_EPISODES_PER_SEED:
        raise EvalError(f"--episodes must be in 1..{MAX_EPISODES_PER_SEED}, got {episodes}")
    if not seeds or any(s < 0 for s in seeds):
        raise EvalError("--seeds must be non-negative integers, e.g. 0,1,2")


@dataclass
class EpisodeOutcome:
    checkpoint: str
    seed: int
    scene_seed: int
    success: bool
    steps: int
    seconds: float
    final: str = ""  # the success predicates' details at the episode's end (e.g. "drawer 0 openness 0.07 (max 0.05)")


def with_action_steps(model, action_steps: int | None):
    """The policy executing `action_steps` of its predicted actions per prediction (None: its config's). Fewer
    than trained with is allowed (a new prediction sooner); more than fit in the horizon is refused."""
    if action_steps is None:
        return model
    cfg = model.cfg
    most = cfg.horizon - cfg.n_obs_steps + 1
    if not 1 <= action_steps <= most:
        raise EvalError(f"--action-steps must be in 1..{most} for horizon {cfg.horizon} and {cfg.n_obs_steps} "
                        f"observation steps, got {action_steps}")
    model.cfg = cfg.model_copy(update={"n_action_steps": action_steps})
    return model


def env_config_for(policy: str, cfg, meta: dict, max_steps: int | None = None,
                   randomize: bool = False) -> TaskEnvConfig:
    """The environment observing what the policy was trained on, at the data's action rate; `randomize`: in
    scenes dressed from their seeds (`TaskEnvConfig.randomize`)."""
    rec = dict(meta.get("recorder") or {})
    hz = meta.get("control_hz", 50.0)
    if policy == "dp":
        return TaskEnvConfig.from_recorder(rec, hz, cameras=(cfg.camera,), depth=False, point_cloud=False,
                                           max_steps=max_steps, randomize=randomize)
    return TaskEnvConfig.from_recorder(rec, hz, cameras=(), depth=False, point_cloud=True, max_steps=max_steps,
                                       randomize=randomize)


def policy_obs(model, history: deque, device: str) -> dict[str, torch.Tensor]:
    """The last n_obs_steps environment observations as a batch of one, with the zarr's names (a policy with
    its own naming, a LeRobot checkpoint's, builds its batch itself: `observation_batch`)."""
    if hasattr(model, "observation_batch"):
        return model.observation_batch(history, device)
    cfg = model.cfg
    out = {"state": torch.as_tensor(np.stack([h["joint_pos"] for h in history]))[None]}
    if "point_cloud" in model.obs_keys:
        out["point_cloud"] = torch.as_tensor(np.stack([h["point_cloud"][: cfg.num_points] for h in history]))[None]
    if "hands" in model.obs_keys:
        out["hands"] = torch.as_tensor(hand_features(np.stack([h["ee_pose"] for h in history])))[None]
    if "img" in model.obs_keys:
        from humanoidgen.policies.dp.model import resize_images

        frames = np.stack([h[f"rgb/{cfg.camera}"] for h in history])
        out["img"] = resize_images(frames, cfg.image_size)[None]
    return {k: v.to(device) for k, v in out.items()}


def rollout(model, env, scene_seed: int, generator: torch.Generator, device: str, video=None
            ) -> tuple[bool, int, str]:
    """One closed-loop episode: (success, actions taken, the predicates' details at its end)."""
    obs, info = env.reset(seed=scene_seed)
    if hasattr(model, "start_episode"):  # a baseline that remembers the episode's start (`baselines.noop_policy`)
        model.start_episode(obs)
    history = deque([obs] * model.cfg.n_obs_steps, maxlen=model.cfg.n_obs_steps)
    steps, done = 0, False
    if video is not None:
        video.frame(env.render())
    while not done:
        actions = model.predict_action(policy_obs(model, history, device), generator=generator)["action"][0]
        for a in actions.cpu().numpy():
            obs, _, terminated, truncated, info = env.step(a)
            history.append(obs)
            steps += 1
            if video is not None:
                video.frame(env.render())
            if terminated or truncated:
                done = True
                break
    return bool(info["success"]), steps, final_detail(info)


def run_episodes(model, env, label: str, seeds, episodes: int, device: str, video_dir: Path | None = None,
                 bar=None) -> list[EpisodeOutcome]:
    """Evaluation seed s, episode i for each seed and i < episodes: scene EVAL_SEED_BASE + number and the
    policy's noise seeded by number (number = MAX_EPISODES_PER_SEED * s + i), so every policy, trained or
    baseline, meets the same scenes; `label` names the outcomes' checkpoint."""
    out = []
    for seed in seeds:
        for i in range(episodes):
            number = MAX_EPISODES_PER_SEED * seed + i
            video = _video(video_dir, Path(label), seed, i, env.config.action_hz)
            t0 = time.perf_counter()
            try:
                ok, steps, final = rollout(model, env, EVAL_SEED_BASE + number, torch.Generator().manual_seed(number),
                                           device, video)
            finally:
                if video is not None:
                    video.close()
            out.append(EpisodeOutcome(label, seed, EVAL_SEED_BASE + number, ok, steps, time.perf_counter() - t0,
                                      final))
            if bar is not None:
                bar.update(1)
                bar.set_postfix_str(f"success {sum(o.success for o in out)}/{len(out)}")
    return out


def run_in_task(task: str, env_config: TaskEnvConfig, policies: list[tuple[str, object]], seeds, episodes: int,
                device: str, video_dir: Path | None = None, progress: bool = True, desc: str = "eval"
                ) -> list[EpisodeOutcome]:
    """Each (label, policy) on the task's evaluation scenes (`run_episodes`), in one environment observing what
    `env_config` says, with one progress bar."""
    from tqdm import tqdm

    from humanoidgen.envs.task_env import HumanoidTaskEnv

    env = HumanoidTaskEnv(task, config=env_config, render_mode="rgb_array" if video_dir is not None else None)
    bar = tqdm(total=len(policies) * len(seeds) * episodes, unit="episode", desc=desc, disable=not progress,
               dynamic_ncols=True)
    out: list[EpisodeOutcome] = []
    try:
        for label, model in policies:
            out += run_episodes(model, env, label, seeds, episodes, device, video_dir, bar)
    finally:
        bar.close()
        env.close()
    return out


def final_detail(info: dict) -> str:
    return "; ".join(str(c.get("detail", "")) for c in info.get("checks", []))


def _video(video_dir: Path | None, ckpt: Path, seed: int, i: int, fps: float):
    if video_dir is None:
        return None
    from humanoidgen.episodes.video import VideoWriter

    w = VideoWriter(Path(video_dir) / f"{ckpt.stem}_seed{seed}_ep{i:03d}.mp4", fps=max(1, round(fps)))
    w.open()
    return w
