"""The server that plan workers are forked from: started once per parent process, with a scrubbed
environment, after importing numpy, MuJoCo, Drake, OMPL and the planner (`sandbox.preload`), so that a worker
starts in milliseconds with warm imports and no secret in its memory or in `/proc/self/environ`.

This is the standard library's multiprocessing "forkserver" start method. Its server is a process of its
own, spawned (fork + exec) from the parent; it runs no plan code itself and forks one worker per request.
Server and workers die with the process that started them (`lifeline`). The server's stdout and stderr are
pipes that process relays (`relay`), so that a reader of its output is done when it is.

A forked worker would also re-run the parent's `__main__` script before anything else (multiprocessing's
"main fixup"): the `hgen` console script, or in a Ray worker Ray's `default_worker.py`, which imports all of
Ray, 0.3 s per worker here (bench/results/ray_scaling.json). Workers named `WORKER_NAME` skip it: their
target and setup are importable by name. A setup defined in a script's `__main__` (bench/sandbox.py) gets
`WORKER_NAME_MAIN`, which keeps the fixup.
"""

from __future__ import annotations

import contextlib
import json
import multiprocessing as mp
import multiprocessing.forkserver as mp_forkserver
import multiprocessing.spawn as mp_spawn
import os
import threading
from collections.abc import Iterator

from humanoidgen.sandbox.lifeline import ENV_PARENT
from humanoidgen.sandbox.lockdown import scrubbed_environ
from humanoidgen.sandbox.relay import relayed_stdio

# lifeline first: the server dies with its parent from the start, not after seconds of imports
PRELOAD = ["humanoidgen.sandbox.lifeline", "humanoidgen.sandbox.preload"]
ENV_WARM = "HGEN_SANDBOX_WARM"  # read (and taken out) by sandbox.preload
WORKER_NAME = "humanoidgen-plan-worker"
WORKER_NAME_MAIN = "humanoidgen-plan-worker-main"
_lock = threading.Lock()
_started_env: dict[str, str] | None = None


def worker_name(setup: object) -> str:
    """The process name for a worker holding `setup`: whether it needs the parent's `__main__`."""
    setup = getattr(setup, "func", setup)  # a functools.partial: where its function lives
    defined_in = getattr(setup, "__module__", None) or type(setup).__module__
    return WORKER_NAME_MAIN if defined_in == "__main__" else WORKER_NAME


def _preparation_data(name: str, _original=mp_spawn.get_preparation_data) -> dict:
    data = _original(name)
    if name == WORKER_NAME:
        data.pop("init_main_from_path", None)
        data.pop("init_main_from_name", None)
    return data


# popen_forkserver looks the function up on the module at each start, so this covers every worker started here.
mp_spawn.get_preparation_data = _preparation_data


def context(warm: tuple[str, dict] | None = None) -> mp.context.BaseContext:
    """The forkserver context, its server running with the scrubbed environment. `warm`: if this starts the
    server, a function it calls while it warms up, by name ("package.module:function") with JSON data, to
    build what its first worker will need (`hgen run`: `episode_worker.prebuild`, the episode's scene); passed
    in the server's environment, trusted like the rest of it."""
    global _started_env
    ctx = mp.get_context("forkserver")
    with _lock:
        if _started_env is None or not _server_alive():
            ctx.set_forkserver_preload(PRELOAD)
            env = scrubbed_environ()
            # The server dies with the thread that starts it (lifeline): only the main thread lasts as long as
            # this process.
            env[ENV_PARENT] = str(os.getpid()) if threading.current_thread() is threading.main_thread() else "-"
            if warm is not None:
                env[ENV_WARM] = json.dumps({"call": warm[0], "data": warm[1]})
            with _environ(env), relayed_stdio():  # no reader of our output waits for the server's end
                mp_forkserver.ensure_running()
            _started_env = env
    return ctx


def prestart(warm: tuple[str, dict] | None = None) -> None:
    """Start the server now and return at once: it imports and warms up (`sandbox.preload`, seconds) while
    this process goes on with its own imports and set-up, instead of when the first worker is asked for.
    `warm`: what the server builds for its first worker while it warms up (see `context`)."""
    context(warm)


def _server_alive() -> bool:
    pid = getattr(mp_forkserver._forkserver, "_forkserver_pid", None)
    if pid is None:
        return False
    try:
        done, _ = os.waitpid(pid, os.WNOHANG)
    except ChildProcessError:
        return False
    return done == 0


@contextlib.contextmanager
def _environ(env: dict[str, str]) -> Iterator[None]:
    """Swap os.environ (and so the C environment the server is spawned with) for `env`, then restore it.
    Another thread reading the environment in this instant would miss a variable: this runs once, early."""
    saved = dict(os.environ)
    os.environ.clear()
    os.environ.update(env)
    try:
        yield
    finally:
        os.environ.clear()
        os.environ.update(saved)
