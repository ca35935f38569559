"""Warm Ray workers: one long-lived actor per CPU slot that keeps the per-process setup of an attempt (imports,
the plan workers' fork server with MuJoCo's mesh cache) for as long as the driver is connected, and a runner
that hands it items and yields their results in submission order.

Why actors and not tasks: Ray recycles its idle task workers (measured here: a fresh worker process for about
every other `ray_collect`, each paying 5-11 s of imports and fork-server start before its first attempt),
while a local `--workers` pool pays that once per process. An actor is never recycled while the driver holds
it, so Ray runs an attempt exactly as warm as `collect` does (bench/results/ray_scaling.json).

The pool is cached per driver connection (`pool_for`) and reused by every collection, bench and policy
evaluation of that connection; it holds its CPUs until `release_pool()` or `ray.shutdown()` (which
`ray_session.connect` does at the end of a command). Guarantees kept from tasks:
- retries: an actor whose process dies (OOM killer, a lost node) is restarted (`max_restarts=-1`) and the
  calls it held are run again (`max_task_retries`), so a seed is never lost silently nor run twice into the
  dataset (the driver takes one result per item);
- cancellation: `PoolRunner.close()` cancels the queued calls and tells each busy actor to kill the plan
  workers of the calls it is running (`abort`, in a concurrency group of its own so it runs while an attempt
  does); Ray cannot interrupt a running call of a sync actor.
Plan code still runs only in the locked-down plan worker the attempt starts; the actor runs trusted code."""

from __future__ import annotations

import contextlib
import itertools
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from humanoidgen.episodes.ray_session import ON_SHUTDOWN, TASK_RETRIES, TaskLost

DEPTH = 2  # calls queued per actor: one running, one waiting, so it never idles on a round trip to the driver
ABORT_WAIT_S = 10.0  # how long close() waits for the actors to confirm their plan workers are gone


class WarmWorker:
    """The actor's body (made a Ray actor class in `pool_for`, so that Ray stays an optional import)."""

    def __init__(self) -> None:
        from humanoidgen.sandbox.forkserver import context

        # Started now, when the pool is created, rather than inside the first attempt: several actors
        # start at once and the first results are not held up by it.
        context()
        self._aborted: set[int] = set()

    def ready(self) -> str:
        from humanoidgen.episodes.ray_session import node_label

        return node_label()

    def run(self, epoch: int, fn: Callable[..., Any], args: tuple) -> Any:
        if epoch in self._aborted:
            return None  # queued before its runner was closed, dequeued after: not wanted any more
        return fn(*args)

    def abort(self, epoch: int) -> bool:
        """Runs beside `run` (concurrency group "control"): the attempt in progress loses its plan worker and
        returns at once as a failed attempt, which its closed runner ignores."""
        from humanoidgen.sandbox.runner import kill_all

        self._aborted.add(epoch)
        for _ in range(3):  # the attempt's thread may be adding its worker to the set kill_all walks
            try:
                kill_all()
                return True
            except RuntimeError:
                continue
        return False


@dataclass
class WorkerPool:
    ray: Any
    key: tuple
    gpus: float
    actors: list = field(default_factory=list)
    ready_refs: list = field(default_factory=list)  # actor i is up when ready_refs[i] is done

    def grow(self, size: int) -> None:
        options: dict[str, Any] = {"num_cpus": 1, "max_restarts": -1, "max_task_retries": TASK_RETRIES}
        if self.gpus > 0:
            options["num_gpus"] = self.gpus  # fixed for the actor's life: its fork server sees that GPU
        cls = self.ray.remote(concurrency_groups={"control": 1}, **options)(WarmWorker)
        while len(self.actors) < size:
            actor = cls.remote()
            self.actors.append(actor)
            self.ready_refs.append(actor.ready.remote())

    def release(self) -> None:
        for actor in self.actors:
            with contextlib.suppress(Exception):
                self.ray.kill(actor)
        self.actors.clear()
        self.ready_refs.clear()


_pool: WorkerPool | None = None
_epochs = itertools.count()


def _connection_key(ray) -> tuple:
    """Which driver connection a pool belongs to: its actors die with the connection."""
    ctx = ray.get_runtime_context()
    return ctx.gcs_address, ctx.get_job_id(), ctx.get_worker_id()


def pool_for(ray, size: int, gpus: float = 0.0) -> WorkerPool:
    """The cached pool of this connection with at least `size` actors of `gpus` GPUs each (a pool of another
    GPU share is released first: its actors hold the CPUs the new ones need)."""
    global _pool
    key = (*_connection_key(ray), float(gpus))
    if _pool is not None and _pool.key != key:
        if _pool.key[:3] == key[:3]:
            _pool.release()  # same connection: free its CPUs; another connection's actors are gone already
        _pool = None
    if _pool is None:
        _pool = WorkerPool(ray, key, float(gpus))
    _pool.grow(max(1, size))
    return _pool


def release_pool() -> None:
    """Kill the cached actors (their CPUs go back to the cluster); the next collection starts new ones."""
    global _pool
    if _pool is not None:
        with contextlib.suppress(Exception):
            if _pool.ray.is_initialized():
                _pool.release()
        _pool = None


ON_SHUTDOWN.append(release_pool)


class PoolRunner:
    """Runs `fn(*args_of(item))` on the first `size` actors of `pool` and yields `(item, result)` in the order
    of `items`. Each actor holds at most DEPTH calls; an item is submitted to the least loaded actor that is up,
    and only while fewer than `window` items are in flight or waiting to be yielded, so a caller that stops
    iterating submits nothing more. A call lost beyond its retries raises TaskLost (or gives `on_lost(exc)`)."""

    def __init__(self, pool: WorkerPool, size: int, fn: Callable[..., Any], args_of: Callable[[Any], tuple],
                 on_lost: Callable[[TaskLost], Any] | None = None) -> None:
        self.ray, self.fn, self.args_of, self.on_lost = pool.ray, fn, args_of, on_lost
        self.pool = pool
        self.actors = pool.actors[:max(1, size)]
        self.ready = [False] * len(self.actors)
        self.window = (DEPTH + 1) * len(self.actors)
        self.epoch = next(_epochs)
        self._load = [0] * len(self.actors)  # calls of this runner an actor holds
        self._refs: dict[int, tuple[Any, Any, int]] = {}  # position -> (item, ref, actor index)
        self._done: set[int] = set()  # positions whose call finished (result not fetched yet)
        self._busy: set[int] = set()  # actors that were given calls (to abort on close)

    def results(self, items: Iterable[Any]) -> Iterator[tuple[Any, Any]]:
        source, submitted, head, exhausted = iter(items), 0, 0, False
        try:
            while True:
                self._poll_ready()
                while not exhausted and submitted - head < self.window:
                    actor = self._free_actor()
                    if actor is None:
                        break
                    item = next(source, _END)
                    if item is _END:
                        exhausted = True
                        break
                    ref = self.actors[actor].run.remote(self.epoch, self.fn, self.args_of(item))
                    self._refs[submitted] = (item, ref, actor)
                    self._load[actor] += 1
                    self._busy.add(actor)
                    submitted += 1
                if head == submitted and exhausted:
                    return
                if head in self._done:
                    item, ref, _ = self._refs.pop(head)
                    self._done.discard(head)
                    result = self._get(ref, item)
                    head += 1
                    yield item, result
                    continue
                self._wait()
        finally:
            self.close()

    def _poll_ready(self) -> None:
        waiting = [self.pool.ready_refs[i] for i, up in enumerate(self.ready) if not up]
        if not waiting:
            return
        # The first actor is waited for (nothing can run before it); later ones are picked up as they come.
        timeout = 0.5 if not any(self.ready) else 0
        done, _ = self.ray.wait(waiting, num_returns=len(waiting), timeout=timeout)
        done_ids = {r.hex() for r in done}
        for i, ref in enumerate(self.pool.ready_refs[:len(self.actors)]):
            if ref.hex() in done_ids:
                self.ready[i] = True

    def _free_actor(self) -> int | None:
        free = [i for i, up in enumerate(self.ready) if up and self._load[i] < DEPTH]
        return min(free, key=lambda i: self._load[i]) if free else None

    def _wait(self) -> None:
        """Wait (at most 0.5 s, so Ctrl-C stays responsive) until a call finishes; free its actor's slot."""
        open_ = {ref.hex(): pos for pos, (_, ref, _) in self._refs.items() if pos not in self._done}
        if not open_:
            return
        refs = [self._refs[pos][1] for pos in open_.values()]
        done, _ = self.ray.wait(refs, num_returns=1, timeout=0.5)
        for ref in done:
            pos = open_[ref.hex()]
            self._done.add(pos)
            self._load[self._refs[pos][2]] -= 1

    def _get(self, ref, item: Any) -> Any:
        try:
            return self.ray.get(ref)
        except self.ray.exceptions.RayError as exc:
            first = (str(exc).strip().splitlines() or [type(exc).__name__])[0][:300]
            lost = TaskLost(item, f"{type(exc).__name__}: {first}")
            if self.on_lost is None:
                raise lost from None
            return self.on_lost(lost)

    def close(self) -> None:
        """Cancel what is queued, stop what is running (Ctrl-C, an error, or the end of the dataset)."""
        pending = [ref for pos, (_, ref, _) in self._refs.items() if pos not in self._done]
        for ref in pending:
            with contextlib.suppress(Exception):
                self.ray.cancel(ref)  # a queued call is dropped; a running one is left to `abort`
        if pending:
            aborts = []
            for i in sorted(self._busy):
                with contextlib.suppress(Exception):
                    aborts.append(self.actors[i].abort.options(concurrency_group="control").remote(self.epoch))
            with contextlib.suppress(Exception):
                self.ray.wait(aborts, num_returns=len(aborts), timeout=ABORT_WAIT_S)
        self._refs.clear()
        self._done.clear()
        self._busy.clear()


_END = object()
