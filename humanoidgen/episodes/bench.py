"""The benchmark report: each task's reference plan on N randomized seeds; a table and a bar chart grouped
like the paper's figure 5 (single-arm / bimanual, short / long horizon)."""

from __future__ import annotations

import tempfile
from concurrent.futures import ThreadPoolExecutor
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from humanoidgen.episodes.task_episode import EpisodeRequest, models_record, run_task_episode


@dataclass
class TaskReport:
    task: str
    arms: str
    horizon: str
    episodes: int
    successes: int
    mean_wall_s: float  # per successful episode: planning + simulation, no cameras
    mean_plan_s: float  # motion planning per episode
    mean_sim_s: float
    failures: list[str]
    # One record per episode, in seed order, as collection's index.jsonl has them: seed, success, error, and the
    # episode's dressing (room and/or randomized look) when it had one, so that it re-runs exactly.
    records: list[dict] = field(default_factory=list)

    @property
    def success_rate(self) -> float:
        return self.successes / self.episodes if self.episodes else 0.0

    def to_dict(self) -> dict:
        return {**asdict(self), "success_rate": self.success_rate}


def _one(req: EpisodeRequest) -> dict:
    try:
        r, _ = run_task_episode(req)
    except Exception as exc:  # a crash is a failure of that episode, reported
        return {"success": False, "error": f"{type(exc).__name__}: {exc}", "wall": 0.0, "plan": 0.0, "sim": 0.0}
    failed = r.failed_step
    error = (f"step {failed.index} ({failed.title}): {failed.error}" if failed else
             "; ".join(c["detail"] for c in r.checks if not c["ok"]))
    return {"success": r.success, "error": error, "wall": r.wall_seconds, "plan": r.plan_seconds, "sim": r.sim_seconds}


def run_bench(tasks: list, episodes: int, seed: int = 0, workers: int = 1,
              progress: Callable[[str, int, int], None] | None = None,
              ray_address: str | None = None, room: str | int | None = None,
              randomize_visuals: bool = False, models: list[str] | None = None,
              randomize_models: bool = False) -> list[TaskReport]:
    """`ray_address`: run every episode on Ray's warm workers (`ray_pool`), all tasks' episodes at once.
    `room`: a room seed or "random" (each episode its own room); `randomize_visuals`: each episode's look drawn
    from its seed (`scenes.dressing.episode_dressing`, as `hgen collect` does). `models` ("FAMILY=MODEL" or
    "FAMILY[K]=MODEL"; a task without that family is an error) and `randomize_models`: the tasks on other models
    of their objects' families (`tasks.models`); each record names its episode's models."""
    with tempfile.TemporaryDirectory(prefix="hgen-bench-") as folder:
        runs = [_task_run(spec, models, randomize_models, Path(folder)) for spec in tasks]
        if ray_address is not None:
            return _ray_bench(tasks, runs, episodes, seed, workers, progress, ray_address, room, randomize_visuals)
        return _local_bench(tasks, runs, episodes, seed, workers, progress, room, randomize_visuals)


def _task_run(spec, models: list[str] | None, randomize: bool, folder: Path) -> tuple[str, str | None]:
    """The task file and plan an episode of `spec` runs (its name and reference plan without models)."""
    if not models and not randomize:
        return spec.name, None
    from humanoidgen.tasks.models import task_with_models

    task, plan = task_with_models(spec.name, list(models or []), randomize, folder / spec.name)
    return task, str(plan) if plan is not None else None


def _local_bench(tasks: list, runs: list, episodes: int, seed: int, workers: int, progress, room,
                 randomize_visuals: bool) -> list[TaskReport]:
    # Each episode runs in its own locked-down worker process; threads here only wait on them.
    pool = ThreadPoolExecutor(workers) if workers > 1 else None
    reports = []
    try:
        for spec, run in zip(tasks, runs):
            reqs = [_request(run, seed + i, room, randomize_visuals) for i in range(episodes)]
            outs = list(pool.map(_one, reqs)) if pool is not None else [_one(r) for r in reqs]
            reports.append(_report(spec, reqs, outs))
            if progress is not None:
                progress(spec.name, reports[-1].successes, episodes)
    finally:
        if pool is not None:
            pool.shutdown(wait=True, cancel_futures=True)
    return reports


def _request(run: tuple[str, str | None], seed: int, room: str | int | None, randomize_visuals: bool) -> EpisodeRequest:
    from humanoidgen.scenes.dressing import episode_dressing

    task, plan = run
    return EpisodeRequest(task, seed, plan, dressing=episode_dressing(room, randomize_visuals, seed))


def _ray_bench(tasks: list, runs: list, episodes: int, seed: int, workers: int | None, progress, address: str,
               room: str | int | None = None, randomize_visuals: bool = False) -> list[TaskReport]:
    from humanoidgen.episodes.ray_pool import PoolRunner, pool_for
    from humanoidgen.episodes.ray_session import connect

    reqs = [_request(run, seed + i, room, randomize_visuals) for run in runs for i in range(episodes)]
    outs: list[dict] = []
    with connect(address, workers if address == "local" else None) as session:
        slots = session.cpu_slots(1.0)
        lost = lambda e: {"success": False, "error": f"lost on the cluster: {e.reason}", "wall": 0.0, "plan": 0.0,  # noqa: E731
                          "sim": 0.0}
        runner = PoolRunner(pool_for(session.ray, slots), slots, _one, lambda req: (req,), on_lost=lost)
        reports = []
        for req, out in runner.results(reqs):
            outs.append(out)
            if len(outs) % episodes == 0:  # a task's episodes are all in
                spec = tasks[len(outs) // episodes - 1]
                reports.append(_report(spec, reqs[len(outs) - episodes:len(outs)], outs[-episodes:]))
                if progress is not None:
                    progress(spec.name, reports[-1].successes, episodes)
    return reports


def _report(spec, reqs: list[EpisodeRequest], outs: list[dict]) -> TaskReport:
    ok = [o for o in outs if o["success"]]
    episodes = len(reqs)
    return TaskReport(
        spec.name, spec.arms, spec.horizon, episodes, len(ok),
        float(np.mean([o["wall"] for o in ok])) if ok else float("nan"),
        float(np.mean([o["plan"] for o in outs])), float(np.mean([o["sim"] for o in ok])) if ok else float("nan"),
        # each failure names its seed, so that `hgen run TASK --seed S --video x.mp4` shows it
        [f"seed {r.seed}: {o['error'][:400]}" for r, o in zip(reqs, outs) if not o["success"]],
        [_record(r, o) for r, o in zip(reqs, outs)],
    )


def _record(req: EpisodeRequest, out: dict) -> dict:
    record = {"seed": req.seed, "success": out["success"], "error": out["error"]}
    if req.dressing is not None:
        record["dressing"] = req.dressing  # the room and look, whole (as collection's index records it)
    models = models_record(req.task, req.seed)
    if models is not None:
        record["models"] = models  # each object's model, as collection's index records it
    return record


def plot(reports: list[TaskReport], path: Path) -> None:
    """Success rate per task, grouped into single-arm/bimanual x short/long horizon."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    groups = [("single", "short"), ("single", "long"), ("bimanual", "short"), ("bimanual", "long")]
    colors = {"single": "#4C72B0", "bimanual": "#DD8452"}
    ordered = [r for g in groups for r in reports if (r.arms, r.horizon) == g]
    fig, ax = plt.subplots(figsize=(max(6, 0.5 * len(ordered) + 2), 4))
    x = np.arange(len(ordered))
    ax.bar(x, [100 * r.success_rate for r in ordered], color=[colors[r.arms] for r in ordered],
           hatch=None, edgecolor="black", linewidth=0.5)
    for i, r in enumerate(ordered):
        if r.horizon == "long":
            ax.patches[i].set_hatch("//")
    ax.set_xticks(x, [r.task for r in ordered], rotation=60, ha="right", fontsize=8)
    ax.set_ylabel("success rate (%)")
    ax.set_ylim(0, 105)
    episodes = sorted({r.episodes for r in ordered})
    ax.set_title("HGen-Bench reference plans: success over randomized seeds "
                 f"({'/'.join(map(str, episodes))} per task)", pad=28)
    from matplotlib.patches import Patch

    ax.legend(handles=[Patch(color=colors["single"], label="single arm"),
                       Patch(color=colors["bimanual"], label="bimanual"),
                       Patch(facecolor="white", edgecolor="black", hatch="//", label="long horizon")],
              loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, frameon=False, fontsize=8)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
