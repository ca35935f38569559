"""Collecting demonstrations: randomized attempts (seed, seed+1, ...), each in its own locked-down plan
worker; successful ones are kept until N, written one by one by this process (workers cannot write).
`workers` attempts run at once (threads here, each waiting on its worker process). Kept episodes are the
first N successful seeds in seed order, so the dataset is the same whatever the number of workers;
`resume` continues after the last attempted seed. `ray_collect` runs the same attempts as Ray tasks and
keeps them by the same rule (`SeedTally`)."""

from __future__ import annotations

import time
from concurrent.futures import Future, ThreadPoolExecutor
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path

from humanoidgen.episodes.dataset import EpisodeStore
from humanoidgen.episodes.recorder import RecorderConfig
from humanoidgen.episodes.task_episode import EpisodeRequest, models_record, run_task_episode, start_worker
from humanoidgen.sim.action import ACTION_JOINTS
from humanoidgen.sim.cameras import CAMERA_NAMES
from humanoidgen.sim.layout import ROBOT


@dataclass
class CollectStats:
    kept: int
    tried: int
    wall_seconds: float

    @property
    def success_rate(self) -> float:
        return self.kept / self.tried if self.tried else 0.0


def attempt(req: EpisodeRequest, worker=None) -> tuple[dict, dict | None]:
    """One attempt, as a plain record plus the arrays of a kept episode (local and Ray collection both run
    this; its plan runs in a locked-down plan worker, `worker` if one was started for it ahead). The images
    of a kept episode are not rendered yet: they are when its file is written (`image_job`), while the next
    attempts run."""
    try:
        result, arrays = run_task_episode(req, render=False, worker=worker)
    except Exception as exc:  # a broken attempt is a failed attempt, not a dead collection
        return {"seed": req.seed, "success": False, "error": f"{type(exc).__name__}: {exc}"}, None
    finally:
        if worker is not None:
            worker.close()  # already closed by the episode, unless it failed before starting
    failed = result.failed_step
    record = {
        "seed": req.seed, "success": result.success, "wall_seconds": round(result.wall_seconds, 3),
        "sim_seconds": round(result.sim_seconds, 3), "plan_seconds": round(result.plan_seconds, 3),
        "error": (f"step {failed.index} ({failed.title}): {failed.error}" if failed else
                  "; ".join(c["detail"] for c in result.checks if not c["ok"])),
    }
    if req.dressing is not None:
        record["dressing"] = req.dressing  # the room and look, whole: the episode re-renders from it
    models = models_record(req.task, req.seed)
    if models is not None:
        record["models"] = models  # each object's model: the episode runs and renders again on them (--model)
    if result.success and req.recorder is not None and not arrays:
        record["success"] = False  # nothing to keep: a success is only counted with its recording
        record["error"] = "the episode succeeded but its replay recorded nothing"
    return record, (arrays if record["success"] else None)


_attempt = attempt  # what `collect` calls (looked up at call time, so tests can replace it)


@dataclass
class SeedTally:
    """The dataset's rule, the same for local and Ray collection: attempts are taken in seed order, and the
    dataset ends with the n-th success (or when `limit` attempts were made), whatever ran past it."""

    n: int
    limit: int
    kept: int
    tried: int
    next_seed: int  # the first seed not attempted yet

    @property
    def done(self) -> bool:
        return self.kept >= self.n or self.tried >= self.limit

    def take(self, record: dict) -> bool:
        """Count the next attempt in seed order; False if it lies past the end of the dataset."""
        if self.done:
            return False
        self.tried += 1
        self.kept += bool(record["success"])
        return True

    def seeds(self) -> range:
        """The seeds that may still be attempted, in order."""
        return range(self.next_seed, self.next_seed + max(self.limit - self.tried, 0))


def open_collection(task: str, n: int, out: Path, seed: int = 0, resume: bool = False,
                    recorder: RecorderConfig | None = None, plan_path: str | None = None,
                    max_attempts: int | None = None) -> tuple[EpisodeStore, SeedTally, RecorderConfig]:
    """The store (created, or repaired when resuming) and where the collection stands."""
    from humanoidgen.episodes.task_episode import load_spec

    spec = load_spec(task)  # fail early on a bad task name
    recorder = recorder or RecorderConfig()
    store = EpisodeStore(out)
    store.create({"task": spec.name, "task_source": task, "robot": ROBOT.name, "seed": seed, "control_hz": 50.0,
                  "action_names": list(ACTION_JOINTS), "state_names": list(ACTION_JOINTS),
                  "objects": [f"{o.type}[{i}]" for i, o in enumerate(spec.objects)],
                  "cameras": list(recorder.cameras), "recorder": asdict(recorder),
                  "plan": plan_path or spec.plan}, resume=resume)
    attempts = store.attempts()
    limit = max_attempts if max_attempts is not None else max(20, 10 * n)
    tally = SeedTally(n, limit, len(store.kept()), len(attempts),
                      max((a["seed"] for a in attempts), default=seed - 1) + 1)
    return store, tally, recorder


def collect(task: str, n: int, out: Path, workers: int = 1, seed: int = 0, resume: bool = False,
            recorder: RecorderConfig | None = None, plan_path: str | None = None, max_attempts: int | None = None,
            progress: Callable[[int, int], None] | None = None, room: str | int | None = None,
            randomize_visuals: bool = False) -> CollectStats:
    """Collect `n` successful episodes of `task` into `out` (see the module docstring). `room` (a seed or
    "random") and `randomize_visuals` dress each attempt (`scenes.dressing.episode_dressing`)."""
    from humanoidgen.sandbox.forkserver import prestart
    from humanoidgen.scenes.dressing import episode_dressing

    prestart()  # the plan workers' server warms up while the dataset is opened
    store, tally, recorder = open_collection(task, n, out, seed, resume, recorder, plan_path, max_attempts)
    t0 = time.perf_counter()
    pool = ThreadPoolExecutor(workers) if workers > 1 else None
    # Episode files are rendered, compressed and written by one thread while the next attempts run, in seed
    # order; one batch at most waits, so slow rendering or a slow disk holds back collection instead of
    # filling memory.
    writer = ThreadPoolExecutor(1, thread_name_prefix="hgen-write")
    writing: list[Future] = []
    if recorder.renders:
        from humanoidgen.episodes.image_job import warm_up

        writer.submit(warm_up, task, recorder, tally.next_seed)  # while the first attempts plan

    def request(s: int) -> EpisodeRequest:
        return EpisodeRequest(task, s, plan_path, recorder, dressing=episode_dressing(room, randomize_visuals, s))

    # One attempt at a time and no images: the next attempt's worker starts (fork, lock-down, scene) while one
    # runs, on the core that attempt leaves idle (a camera-less hand-over: 15% less time per kept episode).
    # With images that core renders the kept attempts, and a worker started ahead only took time from it.
    ahead = (_WorkerAhead(request) if pool is None and not recorder.renders and _attempt is attempt else None)
    try:
        while not tally.done:
            seeds = tally.seeds()[: max(workers, 1)]
            batch = [request(s) for s in seeds]
            tally.next_seed += len(batch)
            if pool is not None:
                results = list(pool.map(_attempt, batch))
            elif ahead is not None:
                later = tally.seeds()  # the seeds after this batch: the first may be attempted next
                results = [ahead.run(r, next_seed=later[0] if later else None) for r in batch]
            else:
                results = [_attempt(r) for r in batch]
            for done in writing:
                done.result()  # the previous batch is on disk (or its error is raised here)
            writing = []
            for record, arrays in results:  # in seed order
                if not tally.take(record):
                    break  # attempts past the n-th success are not part of the dataset
                writing.append(writer.submit(_write, store, record, arrays, progress, tally.kept, tally.tried))
        for done in writing:
            done.result()
    except BaseException:
        from humanoidgen.sandbox.runner import kill_all

        kill_all()  # Ctrl-C: the attempts in flight end now; what was written stays
        raise
    finally:
        if ahead is not None:
            ahead.close()
        if pool is not None:
            pool.shutdown(wait=True, cancel_futures=True)  # each attempt's worker ends with its attempt
        writer.shutdown(wait=True)  # an episode being written is finished, never left half-written
    return CollectStats(tally.kept, tally.tried, time.perf_counter() - t0)


class _WorkerAhead:
    """Runs attempts one by one, each in a worker started while the attempt before it ran."""

    def __init__(self, request: Callable[[int], EpisodeRequest]) -> None:
        self.request = request
        self.starter = ThreadPoolExecutor(1, thread_name_prefix="hgen-start")
        self.next: tuple[int, Future] | None = None

    def run(self, req: EpisodeRequest, next_seed: int | None) -> tuple[dict, dict | None]:
        worker = self._take(req.seed)
        if next_seed is not None:
            self.next = (next_seed, self.starter.submit(start_worker, self.request(next_seed)))
        return attempt(req, worker)

    def _take(self, seed: int | None):
        """The worker started for `seed`, if it started; any other is closed."""
        pending, self.next = self.next, None
        if pending is None:
            return None
        try:
            worker = pending[1].result()
        except Exception:  # noqa: BLE001 - the attempt starts its own worker and reports what goes wrong
            return None
        if pending[0] == seed:
            return worker
        worker.close()
        return None

    def close(self) -> None:
        self._take(None)
        self.starter.shutdown(wait=True)


def _write(store: EpisodeStore, record: dict, arrays: dict | None, progress: Callable[[int, int], None] | None,
           kept: int, tried: int) -> None:
    store.add(record, arrays if record["success"] else None)
    if progress is not None:
        progress(kept, tried)



__all__ = ["attempt", "collect", "open_collection", "SeedTally", "CollectStats", "CAMERA_NAMES"]
