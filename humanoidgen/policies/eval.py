"""Closed-loop evaluation: a trained policy acts in its task's environment (`envs.HumanoidTaskEnv`) and the
task's success predicates judge each episode. As the paper reports it: success rate per evaluation seed and
checkpoint, then mean and standard deviation over them.

Evaluation seed s, episode i runs scene seed EVAL_SEED_BASE + 1000 s + i (never a collection seed by default)
with the policy's sampling noise seeded by the same number, so every checkpoint meets the same scenes and a
rerun gives the same result. The baselines (`baseline_eval`: random joint targets, holding the start posture)
meet the same scenes, and the report carries their scores beside the policy's."""

from __future__ import annotations

from pathlib import Path

from humanoidgen.policies import checkpoint as ck
from humanoidgen.policies.report import EvalReport  # noqa: F401 (evaluation's names, re-exported)
from humanoidgen.policies.rollout import (  # noqa: F401 (evaluation's names, re-exported)
    MAX_EPISODES_PER_SEED,
    EpisodeOutcome,
    EvalError,
    _video,
    check_scenes,
    env_config_for,
    final_detail,
    policy_obs,
    rollout,
    run_episodes,
    run_in_task,
    with_action_steps,
)
from humanoidgen.policies.train import resolve_device


def evaluate(run: Path, task: str | None = None, episodes: int = 20, seeds: tuple[int, ...] = (0, 1, 2),
             checkpoints: list[Path] | None = None, device: str = "auto", video_dir: Path | None = None,
             progress: bool = True, max_steps: int | None = None, ray_address: str | None = None,
             ray_gpus: float = 0.0, action_steps: int | None = None, baselines: bool = True,
             randomize: bool = False, dataset: Path | None = None,
             temporal_ensemble: float | None = None) -> EvalReport:
    """Evaluate a run's checkpoints (all kept ones, or `checkpoints`) on its task; `max_steps` shortens
    episodes below the task's time limit (for quick checks); `action_steps`: actions executed per prediction
    (default: each checkpoint's n_action_steps); `ray_address`: each episode a Ray task (`ray_eval`), with the
    same outcomes; `baselines`: the random and no-op baselines on the same scenes too (`report.baselines`;
    random targets within the demonstrations' action range, as the first checkpoint's normalizer has it);
    `randomize`: the same scene seeds dressed from their seeds (`TaskEnvConfig.randomize`), baselines too;
    `temporal_ensemble`: a prediction every action, the overlapping ones averaged (`ensemble.TemporalEnsemble`,
    its weight decay; the report's `info` says it).
    A LeRobot checkpoint (`run` a `pretrained_model` folder, `lerobot_eval`) is evaluated on the task of the
    export it was trained on (`dataset`, default: the one its train_config.json names)."""
    from tqdm import tqdm

    from humanoidgen.policies.lerobot_policy import is_lerobot_checkpoint

    if is_lerobot_checkpoint(run):
        if ray_address is not None or action_steps is not None or temporal_ensemble is not None:
            raise EvalError("--ray, --action-steps and --temporal-ensemble are for this project's own policies, not "
                            "LeRobot checkpoints")
        from humanoidgen.policies.lerobot_eval import evaluate_lerobot

        return evaluate_lerobot(run, task, episodes, seeds, resolve_device(device), dataset, video_dir, progress,
                                max_steps, baselines, randomize)

    check_scenes(episodes, seeds)
    if temporal_ensemble is not None and (action_steps is not None or ray_address is not None):
        raise EvalError("--temporal-ensemble executes one action a prediction, locally: not with --action-steps "
                        "or --ray")
    device = resolve_device(device)
    paths = [Path(p) for p in checkpoints] if checkpoints else ck.run_checkpoints(run)
    loaded = [(p, *ck.load_policy(p, device)) for p in paths]
    loaded = [(p, with_action_steps(model, action_steps), meta) for p, model, meta in loaded]
    if temporal_ensemble is not None:
        from humanoidgen.policies.ensemble import TemporalEnsemble

        try:
            loaded = [(p, TemporalEnsemble(model, temporal_ensemble), meta) for p, model, meta in loaded]
        except ValueError as exc:
            raise EvalError(str(exc)) from None
    tasks = {meta["task"] for _, _, meta in loaded}
    if len(tasks) > 1:
        raise EvalError(f"the checkpoints were trained on different tasks ({', '.join(sorted(tasks))})")
    trained = tasks.pop()
    if task is not None and task != trained:
        raise EvalError(f"{paths[0]} was trained on task {trained!r}, not {task!r}")
    policy = loaded[0][1].name
    env_config = env_config_for(policy, loaded[0][1].cfg, loaded[0][2], max_steps, randomize)
    report = EvalReport(trained, policy, [str(p) for p in paths], list(seeds), episodes,
                        scenes="randomized" if randomize else "clean",
                        info={} if temporal_ensemble is None else {"temporal_ensemble": float(temporal_ensemble)})
    if ray_address is not None:
        from humanoidgen.policies.ray_eval import ray_outcomes

        with tqdm(total=len(paths) * len(seeds) * episodes, unit="episode", desc=f"eval {policy} {trained} (ray)",
                  disable=not progress, dynamic_ncols=True) as bar:
            report.outcomes = ray_outcomes(ray_address, paths, tuple(seeds), episodes, device, max_steps, video_dir,
                                           bar, ray_gpus, action_steps, randomize)
    else:
        report.outcomes = run_in_task(trained, env_config, [(str(path), model) for path, model, _ in loaded], seeds,
                                      episodes, device, video_dir, progress, f"eval {policy} {trained}")
    if baselines:
        from humanoidgen.policies.baseline_eval import baselines_beside, demo_range

        report.baselines = baselines_beside(trained, env_config, demo_range(loaded[0][1], f"demonstrations of "
                                            f"{paths[0]}"), episodes, tuple(seeds), progress)
    return report
