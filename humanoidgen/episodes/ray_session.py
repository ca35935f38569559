"""Connecting to a Ray cluster (`--ray ADDRESS`); the attempts run on warm actors (`ray_pool`).

ADDRESS is `local` (start a Ray instance on this machine, stopped at the end), `auto` (the cluster this
machine belongs to, started with `ray start`), `ray://host:port` (Ray Client) or `host:port` (a head's GCS).
Ray is an optional extra (`pip install "humanoidgen[ray]"`); it is imported only here and only when asked for.

Each Ray worker process runs with one BLAS/OpenMP thread: the plan worker it starts is single-threaded, and
several BLAS threads per worker on a shared node only fight for the cores."""

from __future__ import annotations

import contextlib
import os
import re
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

# Called before a session started here shuts Ray down (ray_pool registers its release of the warm actors:
# the pool builds on the session, so the session cannot import it).
ON_SHUTDOWN: list = []
LOCAL_OBJECT_STORE_BYTES = 500 << 20  # a modest store: episodes are small or travel through the shared folder
WORKER_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "MUJOCO_GL": "egl"}
# Ray starts its workers at niceness +15 (so that its own daemons come first); on a machine shared with other
# work that starves the attempts (measured here: 3x slower than `--workers`), so a local Ray keeps ours.
LOCAL_SYSTEM_CONFIG = {"worker_niceness": 0}
TASK_RETRIES = 3  # an attempt whose worker was killed (OOM killer, a lost node) is rerun this many times
_ADDRESS = re.compile(r"^(ray://)?[A-Za-z0-9._\-\[\]:]+:\d{1,5}$")


class RaySetupError(RuntimeError):
    """Ray is missing or the cluster cannot be reached (one line, for the command line)."""


class TaskLost(RuntimeError):
    """A task failed on the cluster after its retries (not an attempt that failed: the worker was lost)."""

    def __init__(self, item: Any, reason: str) -> None:
        super().__init__(f"{item}: {reason}")
        self.item, self.reason = item, reason


def check_address(address: str) -> str:
    if address in ("local", "auto") or _ADDRESS.match(address):
        return address
    raise RaySetupError(f"--ray must be 'local', 'auto', 'ray://host:port' or 'host:port', got {address!r}")


def import_ray():
    try:
        import ray
    except ImportError:
        raise RaySetupError("Ray is not installed; install it with: pip install 'humanoidgen[ray]'") from None
    return ray


@dataclass
class RaySession:
    ray: Any
    address: str
    started_here: bool

    def cpu_slots(self, cpus_per_task: float = 1.0) -> int:
        """How many tasks of `cpus_per_task` CPUs the cluster runs at once."""
        cpus = float(self.ray.cluster_resources().get("CPU", 1.0))
        return max(1, int(cpus // max(cpus_per_task, 1e-6)))


@contextlib.contextmanager
def connect(address: str, workers: int | None = None) -> Iterator[RaySession]:
    """A Ray session for `address` (see the module docstring). `workers`: CPUs of a `local` instance (default:
    this machine's). A Ray already initialized in this process (a test, a notebook) is used as it is."""
    check_address(address)
    ray = import_ray()
    if ray.is_initialized():
        yield RaySession(ray, address, started_here=False)
        return
    if address not in ("local", "auto"):
        _probe(address)
    runtime_env = {"env_vars": dict(WORKER_ENV)}
    try:
        if address == "local":
            # address="local": a new instance even where a cluster file from `ray start` is lying around
            ray.init(address="local", num_cpus=workers or os.cpu_count(),
                     object_store_memory=LOCAL_OBJECT_STORE_BYTES, include_dashboard=False, runtime_env=runtime_env,
                     log_to_driver=False, _system_config=LOCAL_SYSTEM_CONFIG)
        else:
            ray.init(address=address, runtime_env=runtime_env, log_to_driver=False)
    except Exception as exc:  # noqa: BLE001 - Ray raises ConnectionError, RuntimeError, grpc errors ...
        with contextlib.suppress(Exception):
            ray.shutdown()
        first = (str(exc).strip().splitlines() or [type(exc).__name__])[0][:300]
        raise RaySetupError(f"cannot reach a Ray cluster at {address!r}: {first}") from None
    try:
        yield RaySession(ray, address, started_here=True)
    finally:
        for release in ON_SHUTDOWN:  # the warm actors end with the connection (they would die with it anyway)
            release()
        ray.shutdown()


def _probe(address: str, timeout_s: float = 5.0) -> None:
    """Fail in seconds when nothing listens at host:port (Ray itself retries for minutes)."""
    import socket

    host, _, port = address.removeprefix("ray://").rpartition(":")
    try:
        socket.create_connection((host.strip("[]"), int(port)), timeout=timeout_s).close()
    except OSError as exc:
        raise RaySetupError(f"cannot reach a Ray cluster at {address!r}: nothing answers at {host}:{port} "
                            f"({exc.strerror or type(exc).__name__})") from None


def node_label() -> str:
    """The node a task runs on, for the progress bar and the index (its IP address)."""
    import ray

    try:
        return ray.util.get_node_ip_address()
    except Exception:  # noqa: BLE001 - a label, never a reason to lose the attempt
        return "?"


@dataclass
class NodeRates:
    """Finished tasks per node, as a rate since the first result."""

    t0: float = field(default_factory=time.perf_counter)
    counts: dict[str, int] = field(default_factory=dict)

    def add(self, node: str) -> None:
        self.counts[node] = self.counts.get(node, 0) + 1

    def per_minute(self) -> dict[str, float]:
        minutes = max(time.perf_counter() - self.t0, 1e-6) / 60
        return {node: count / minutes for node, count in sorted(self.counts.items())}

    def text(self) -> str:
        return ", ".join(f"{node} {rate:.1f}/min" for node, rate in self.per_minute().items())
