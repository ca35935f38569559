"""Collecting demonstrations: randomized attempts (seed, seed+1, ...), each in its own locked-down plan
worker; successful ones are kept until N, written one by one by this process (workers cannot write).
`workers` attempts run at once (threads here, each waiting on its worker process). Kept episodes are the
first N successful seeds in seed order, so the dataset is the same whatever the number of workers;
`resume` continues after the last attempted seed."""

from __future__ import annotations

import time
from concurrent.futures import Future, ThreadPoolExecutor
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path

from humanoidgen.episodes.dataset import EpisodeStore
from humanoidgen.episodes.recorder import RecorderConfig
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode
from humanoidgen.sim.action import ACTION_JOINTS
from humanoidgen.sim.cameras import CAMERA_NAMES


@dataclass
class CollectStats:
    kept: int
    tried: int
    wall_seconds: float

    @property
    def success_rate(self) -> float:
        return self.kept / self.tried if self.tried else 0.0


def _attempt(req: EpisodeRequest) -> tuple[dict, dict | None]:
    """One attempt, as a plain record plus the arrays of a kept episode."""
    try:
        result, arrays = run_task_episode(req)
    except Exception as exc:  # a broken attempt is a failed attempt, not a dead collection
        return {"seed": req.seed, "success": False, "error": f"{type(exc).__name__}: {exc}"}, None
    failed = result.failed_step
    record = {
        "seed": req.seed, "success": result.success, "wall_seconds": round(result.wall_seconds, 3),
        "sim_seconds": round(result.sim_seconds, 3), "plan_seconds": round(result.plan_seconds, 3),
        "error": (f"step {failed.index} ({failed.title}): {failed.error}" if failed else
                  "; ".join(c["detail"] for c in result.checks if not c["ok"])),
    }
    return record, (arrays if result.success else None)


def collect(task: str, n: int, out: Path, workers: int = 1, seed: int = 0, resume: bool = False,
            recorder: RecorderConfig | None = None, plan_path: str | None = None, max_attempts: int | None = None,
            progress: Callable[[int, int], None] | None = None) -> CollectStats:
    """Collect `n` successful episodes of `task` into `out` (see the module docstring)."""
    from humanoidgen.episodes.task_episode import load_spec

    spec = load_spec(task)  # fail early on a bad task name
    recorder = recorder or RecorderConfig()
    store = EpisodeStore(out)
    store.create({"task": spec.name, "task_source": task, "seed": seed, "control_hz": 50.0,
                  "action_names": list(ACTION_JOINTS), "state_names": list(ACTION_JOINTS),
                  "objects": [f"{o.type}[{i}]" for i, o in enumerate(spec.objects)],
                  "cameras": list(recorder.cameras), "recorder": asdict(recorder),
                  "plan": plan_path or spec.plan}, resume=resume)
    attempts = store.attempts()
    kept = len(store.kept())
    tried = len(attempts)
    next_seed = max((a["seed"] for a in attempts), default=seed - 1) + 1
    limit = max_attempts if max_attempts is not None else max(20, 10 * n)
    t0 = time.perf_counter()
    pool = ThreadPoolExecutor(workers) if workers > 1 else None
    # Episode files are compressed and written by one thread while the next attempts run, in seed order;
    # one batch at most waits, so a slow disk holds back collection instead of filling memory.
    writer = ThreadPoolExecutor(1, thread_name_prefix="hgen-write")
    writing: list[Future] = []
    try:
        while kept < n and tried < limit:
            batch = [EpisodeRequest(task, s, plan_path, recorder) for s in range(next_seed, next_seed + max(workers, 1))]
            next_seed += len(batch)
            results = list(pool.map(_attempt, batch)) if pool is not None else [_attempt(r) for r in batch]
            for done in writing:
                done.result()  # the previous batch is on disk (or its error is raised here)
            writing = []
            for record, arrays in results:  # in seed order
                if kept >= n:
                    break  # attempts past the n-th success are not part of the dataset
                tried += 1
                kept += bool(record["success"])
                writing.append(writer.submit(_write, store, record, arrays, progress, kept, tried))
        for done in writing:
            done.result()
    except BaseException:
        from humanoidgen.sandbox.runner import kill_all

        kill_all()  # Ctrl-C: the attempts in flight end now; what was written stays
        raise
    finally:
        if pool is not None:
            pool.shutdown(wait=True, cancel_futures=True)  # each attempt's worker ends with its attempt
        writer.shutdown(wait=True)  # an episode being written is finished, never left half-written
    return CollectStats(kept, tried, time.perf_counter() - t0)


def _write(store: EpisodeStore, record: dict, arrays: dict | None, progress: Callable[[int, int], None] | None,
           kept: int, tried: int) -> None:
    store.add(record, arrays if record["success"] else None)
    if progress is not None:
        progress(kept, tried)


__all__ = ["collect", "CollectStats", "CAMERA_NAMES"]
