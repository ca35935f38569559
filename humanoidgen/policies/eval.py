"""Closed-loop evaluation: a trained policy acts in its task's environment (`envs.HumanoidTaskEnv`) and the
task's success predicates judge each episode. As the paper reports it: success rate per evaluation seed and
checkpoint, then mean and standard deviation over them.

Evaluation seed s, episode i runs scene seed EVAL_SEED_BASE + 1000 s + i (never a collection seed by default)
with the policy's sampling noise seeded by the same number, so every checkpoint meets the same scenes and a
rerun gives the same result."""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
import torch

from humanoidgen.envs.config import EVAL_SEED_BASE
from humanoidgen.policies import checkpoint as ck
from humanoidgen.policies.rollout import (  # noqa: F401 (evaluation's names, re-exported)
    MAX_EPISODES_PER_SEED,
    EpisodeOutcome,
    EvalError,
    _video,
    env_config_for,
    final_detail,
    policy_obs,
    rollout,
    with_action_steps,
)
from humanoidgen.policies.train import resolve_device

@dataclass
class EvalReport:
    task: str
    policy: str
    checkpoints: list[str]
    seeds: list[int]
    episodes: int
    outcomes: list[EpisodeOutcome] = field(default_factory=list)

    def rates(self) -> dict[tuple[str, int], float]:
        """Success rate of each (checkpoint, seed)."""
        out: dict[tuple[str, int], list[bool]] = {}
        for o in self.outcomes:
            out.setdefault((o.checkpoint, o.seed), []).append(o.success)
        return {k: float(np.mean(v)) for k, v in out.items()}

    @property
    def success_mean(self) -> float:
        return float(np.mean(list(self.rates().values()))) if self.outcomes else 0.0

    @property
    def success_std(self) -> float:
        return float(np.std(list(self.rates().values()))) if self.outcomes else 0.0

    def to_dict(self) -> dict:
        return {"task": self.task, "policy": self.policy, "checkpoints": self.checkpoints, "seeds": self.seeds,
                "episodes": self.episodes, "success_mean": self.success_mean, "success_std": self.success_std,
                "rates": [{"checkpoint": c, "seed": s, "success": r} for (c, s), r in self.rates().items()],
                "outcomes": [asdict(o) for o in self.outcomes]}


def evaluate(run: Path, task: str | None = None, episodes: int = 20, seeds: tuple[int, ...] = (0, 1, 2),
             checkpoints: list[Path] | None = None, device: str = "auto", video_dir: Path | None = None,
             progress: bool = True, max_steps: int | None = None, ray_address: str | None = None,
             ray_gpus: float = 0.0, action_steps: int | None = None) -> EvalReport:
    """Evaluate a run's checkpoints (all kept ones, or `checkpoints`) on its task; `max_steps` shortens
    episodes below the task's time limit (for quick checks); `action_steps`: actions executed per prediction
    (default: each checkpoint's n_action_steps); `ray_address`: each episode a Ray task (`ray_eval`), with the
    same outcomes."""
    from tqdm import tqdm

    from humanoidgen.envs.task_env import HumanoidTaskEnv

    if not 1 <= episodes <= MAX_EPISODES_PER_SEED:
        raise EvalError(f"--episodes must be in 1..{MAX_EPISODES_PER_SEED}, got {episodes}")
    if not seeds or any(s < 0 for s in seeds):
        raise EvalError("--seeds must be non-negative integers, e.g. 0,1,2")
    device = resolve_device(device)
    paths = [Path(p) for p in checkpoints] if checkpoints else ck.run_checkpoints(run)
    loaded = [(p, *ck.load_policy(p, device)) for p in paths]
    loaded = [(p, with_action_steps(model, action_steps), meta) for p, model, meta in loaded]
    tasks = {meta["task"] for _, _, meta in loaded}
    if len(tasks) > 1:
        raise EvalError(f"the checkpoints were trained on different tasks ({', '.join(sorted(tasks))})")
    trained = tasks.pop()
    if task is not None and task != trained:
        raise EvalError(f"{paths[0]} was trained on task {trained!r}, not {task!r}")
    policy = loaded[0][1].name
    report = EvalReport(trained, policy, [str(p) for p in paths], list(seeds), episodes)
    if ray_address is not None:
        from humanoidgen.policies.ray_eval import ray_outcomes

        with tqdm(total=len(paths) * len(seeds) * episodes, unit="episode", desc=f"eval {policy} {trained} (ray)",
                  disable=not progress, dynamic_ncols=True) as bar:
            report.outcomes = ray_outcomes(ray_address, paths, tuple(seeds), episodes, device, max_steps, video_dir,
                                           bar, ray_gpus, action_steps)
        return report
    env = HumanoidTaskEnv(trained, config=env_config_for(policy, loaded[0][1].cfg, loaded[0][2], max_steps),
                          render_mode="rgb_array" if video_dir is not None else None)
    bar = tqdm(total=len(paths) * len(seeds) * episodes, unit="episode", desc=f"eval {policy} {trained}",
               disable=not progress, dynamic_ncols=True)
    try:
        for path, model, _ in loaded:
            for seed in seeds:
                for i in range(episodes):
                    number = MAX_EPISODES_PER_SEED * seed + i
                    video = _video(video_dir, path, seed, i, env.config.action_hz)
                    t0 = time.perf_counter()
                    try:
                        ok, steps, final = rollout(model, env, EVAL_SEED_BASE + number,
                                                   torch.Generator().manual_seed(number), device, video)
                    finally:
                        if video is not None:
                            video.close()
                    report.outcomes.append(EpisodeOutcome(str(path), seed, EVAL_SEED_BASE + number, ok, steps,
                                                          time.perf_counter() - t0, final))
                    bar.update(1)
                    done = report.outcomes
                    bar.set_postfix_str(f"success {sum(o.success for o in done)}/{len(done)}")
    finally:
        bar.close()
        env.close()
    return report


