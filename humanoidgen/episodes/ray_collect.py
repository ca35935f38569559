"""Collection on a Ray cluster (`hgen collect --ray ADDRESS`): each attempt (seed) is a call to a warm Ray actor
(`ray_pool`, one per CPU slot) that runs `collect.attempt`, so its plan runs in a locked-down plan worker on
the actor's node exactly as it does locally, dressed (`--room`, `--randomize-visuals`) as it is locally. The driver (this process) takes the results in seed order by the same rule as local collection
(`collect.SeedTally`): the kept episodes are those of `--workers 1`, written as they arrive; `--resume`
continues after the last attempt written.

A kept episode's arrays reach the dataset one of two ways (`transport`):
- `object-store`: the task returns them; Ray moves them to the driver, which compresses and writes the file;
- `shared-folder`: the task (trusted code, never the plan worker) writes the compressed file into the
  dataset's `incoming/` folder (temporary name, fsync, rename) and returns its name; the driver renames it
  into place and appends the index line. Compression then runs on the workers, not on the driver.
`auto` takes the shared folder when the recording has images or point clouds, else the object store. A task
that cannot see the driver's folder (`--out` not on a shared file system) returns the arrays instead; a
marker file written by the driver tells it. See the README and bench/results/ray_transport.json.

A worker killed mid-attempt (OOM killer, a lost node) is restarted by Ray and the attempt rerun
(`max_task_retries`); only the result of the run that finished is written, so no seed is duplicated or missing. A seed lost beyond its retries stops
the collection with what came before it written (continue with --resume). Ctrl-C cancels the tasks in flight."""

from __future__ import annotations

import contextlib
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from humanoidgen.episodes import collect as collect_mod
from humanoidgen.episodes.collect import CollectStats, open_collection
from humanoidgen.episodes.dataset import DatasetError, write_episode_file
from humanoidgen.episodes.ray_pool import PoolRunner, pool_for
from humanoidgen.episodes.ray_session import TASK_RETRIES, NodeRates, TaskLost, connect, node_label
from humanoidgen.episodes.recorder import RecorderConfig
from humanoidgen.episodes.task_episode import EpisodeRequest

TRANSPORTS = ("auto", "object-store", "shared-folder")


@dataclass(frozen=True)
class Staging:
    """The dataset's `incoming/` folder as a task sees it; `token` names this run's files and its marker."""

    folder: str
    token: str

    @property
    def marker(self) -> Path:
        return Path(self.folder) / f".driver-{self.token}"

    def visible(self) -> bool:
        """Whether this node sees the driver's folder (a shared file system), not a same-named local one."""
        return self.marker.exists()

    def path_for(self, seed: int) -> Path:
        # A retried task writes a file of its own; only the one whose result arrives is adopted.
        return Path(self.folder) / f"seed_{seed}.{self.token}.{uuid.uuid4().hex[:8]}.npz"

    def clean(self) -> None:
        """Remove this run's files that were not adopted (cancelled or superseded tries) and the marker."""
        folder = Path(self.folder)
        for path in folder.glob(f"*.{self.token}.*"):
            path.unlink(missing_ok=True)
        self.marker.unlink(missing_ok=True)
        with contextlib.suppress(OSError):
            folder.rmdir()  # only when empty: another run may share it


def remote_attempt(req: EpisodeRequest, staging: Staging | None,
                   attempt_fn: Callable[[EpisodeRequest], tuple[dict, dict | None]]) -> dict:
    """The body of one attempt on a Ray actor: the attempt, then its kept arrays staged on the shared folder or returned."""
    record, arrays = attempt_fn(req)
    out: dict = {"record": record, "node": node_label()}
    if arrays is None:
        return out
    if staging is not None and staging.visible():
        path = staging.path_for(req.seed)
        write_episode_file(path, arrays)
        out.update(staged=str(path), length=int(len(arrays["action"])))
    else:
        out["arrays"] = arrays
    return out


@dataclass
class RayCollectStats(CollectStats):
    nodes: dict[str, int] = field(default_factory=dict)  # attempts finished per node
    staged: int = 0  # kept episodes written by their task into the shared folder
    through_store: int = 0  # kept episodes whose arrays came through the object store


def uses_shared_folder(transport: str, recorder: RecorderConfig) -> bool:
    if transport not in TRANSPORTS:
        raise ValueError(f"unknown transport {transport!r}; choose from {', '.join(TRANSPORTS)}")
    return transport == "shared-folder" or (transport == "auto" and recorder.renders)


def ray_collect(task: str, n: int, out: Path, address: str = "local", workers: int | None = None, seed: int = 0,
                resume: bool = False, recorder: RecorderConfig | None = None, plan_path: str | None = None,
                max_attempts: int | None = None, progress: Callable[[int, int, NodeRates], None] | None = None,
                transport: str = "auto", gpus_per_task: float = 0.0,
                attempt_fn: Callable[[EpisodeRequest], tuple[dict, dict | None]] | None = None,
                room: str | int | None = None, randomize_visuals: bool = False) -> RayCollectStats:
    """Collect `n` successful episodes of `task` into `out` on Ray (see the module docstring). `workers`: the
    CPUs of a `local` Ray, or at most this many attempts at once on a cluster (default: its CPUs). `room` and
    `randomize_visuals` dress each attempt as `collect.collect` does (`scenes.dressing.episode_dressing`).
    `attempt_fn` replaces `collect.attempt` (tests); it must be importable or picklable by value."""
    import time

    from humanoidgen.scenes.dressing import episode_dressing

    recorder = recorder or RecorderConfig()
    shared = uses_shared_folder(transport, recorder)
    # Tasks may run on other machines, in other working directories: paths are made absolute.
    task_ref = str(Path(task).resolve()) if Path(task).suffix in (".yaml", ".yml") else task
    plan_ref = str(Path(plan_path).resolve()) if plan_path else None
    attempt_fn = attempt_fn or collect_mod.attempt
    t0 = time.perf_counter()
    with connect(address, workers) as session:  # before the store: a bad address leaves no empty dataset behind
        store, tally, recorder = open_collection(task, n, out, seed, resume, recorder, plan_path, max_attempts)
        stats = RayCollectStats(tally.kept, tally.tried, 0.0)
        slots = session.cpu_slots(1.0)
        if workers and address != "local":
            slots = min(slots, workers)
        pool = pool_for(session.ray, slots, gpus_per_task)
        staging = None
        if shared:
            store.staging_dir.mkdir(parents=True, exist_ok=True)
            staging = Staging(str(store.staging_dir.resolve()), uuid.uuid4().hex[:12])
            staging.marker.touch()
        rates = NodeRates()

        def args_of(s: int) -> tuple:
            dressing = episode_dressing(room, randomize_visuals, s)
            return EpisodeRequest(task_ref, s, plan_ref, recorder, dressing=dressing), staging, attempt_fn

        runner = PoolRunner(pool, slots, remote_attempt, args_of)
        try:
            for _, res in runner.results(tally.seeds()):
                rates.add(res["node"])
                if not tally.take(res["record"]):
                    break
                record = {**res["record"], "node": res["node"]}
                if "staged" in res:
                    store.adopt(record, Path(res["staged"]), res["length"])
                    stats.staged += 1
                else:
                    store.add(record, res.get("arrays"))
                    stats.through_store += "arrays" in res
                if progress is not None:
                    progress(tally.kept, tally.tried, rates)
                if tally.done:
                    break
        except TaskLost as exc:
            raise DatasetError(f"seed {exc.item} was lost on the cluster after {TASK_RETRIES} retries ({exc.reason}); "
                               f"the attempts before it are in {out}; continue with --resume") from None
        finally:
            runner.close()  # Ctrl-C or the end: nothing keeps running
            if staging is not None:
                staging.clean()
    stats.kept, stats.tried, stats.wall_seconds = tally.kept, tally.tried, time.perf_counter() - t0
    stats.nodes = dict(rates.counts)
    return stats
