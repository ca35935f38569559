"""Closed-loop evaluation of a LeRobot checkpoint in its task: the same scenes, seeds, report and baselines as
this project's own policies (`eval.evaluate`), with the environment observing what the export held
(`lerobot_policy`)."""

from __future__ import annotations

from pathlib import Path

from humanoidgen.envs.config import TaskEnvConfig
from humanoidgen.policies.lerobot_policy import LeRobotPolicy, checkpoint_folder, dataset_of, source_meta
from humanoidgen.policies.report import EvalReport
from humanoidgen.policies.rollout import EvalError, check_scenes, run_in_task


def lerobot_env_config(meta: dict, model: LeRobotPolicy, max_steps: int | None, randomize: bool) -> TaskEnvConfig:
    """The export's recorder settings, observing only the cameras the policy reads (no depth, no cloud)."""
    recorded = set((meta.get("recorder") or {}).get("cameras") or [])
    missing = [c for c in model.cameras if c not in recorded]
    if missing:
        raise EvalError(f"the policy reads camera(s) {', '.join(missing)}, which the export did not record "
                        f"({', '.join(sorted(recorded)) or 'none'})")
    return TaskEnvConfig.from_recorder(dict(meta.get("recorder") or {}), float(meta.get("control_hz", 50.0)),
                                       cameras=model.cameras, depth=False, point_cloud=False, max_steps=max_steps,
                                       randomize=randomize)


def evaluate_lerobot(path: Path, task: str | None = None, episodes: int = 20, seeds: tuple[int, ...] = (0, 1, 2),
                     device: str = "cpu", dataset: Path | None = None, video_dir: Path | None = None,
                     progress: bool = True, max_steps: int | None = None, baselines: bool = True,
                     randomize: bool = False) -> EvalReport:
    """Evaluate the LeRobot checkpoint at `path` (a `pretrained_model` folder or one holding it) on the task of
    the export it was trained on (`dataset`, default: its train_config.json's dataset.root)."""
    check_scenes(episodes, seeds)
    folder = checkpoint_folder(path)
    if folder is None:
        raise EvalError(f"{path} is not a LeRobot checkpoint (no config.json with a policy type)")
    data = dataset_of(folder, dataset)
    meta = source_meta(data)
    trained = meta["task"]
    if task is not None and task != trained:
        raise EvalError(f"{path} was trained on {data}, which holds task {trained!r}, not {task!r}")
    model = LeRobotPolicy(folder, device)
    env_config = lerobot_env_config(meta, model, max_steps, randomize)
    report = EvalReport(trained, model.name, [str(folder)], list(seeds), episodes,
                        scenes="randomized" if randomize else "clean", info={"dataset": str(data)})
    report.outcomes = run_in_task(trained, env_config, [(str(folder), model)], seeds, episodes, device, video_dir,
                                  progress, f"eval {model.name} {trained}")
    if baselines:
        from humanoidgen.policies.baseline_eval import baselines_beside

        report.baselines = baselines_beside(trained, env_config, model.action_range(data), episodes, tuple(seeds),
                                            progress)
    return report
