"""Running a plan text through the real episode entry point (a file in tmp_path, the locked-down worker)."""

from __future__ import annotations

from humanoidgen.episodes.result import EpisodeResult
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode


def run_plan(tmp_path, task: str, seed: int, text: str) -> EpisodeResult:
    path = tmp_path / f"{task}_{seed}.py"
    path.write_text(text)
    result, _ = run_task_episode(EpisodeRequest(task, seed=seed, plan_path=str(path)))
    return result
