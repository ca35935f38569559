"""The server that plan workers are forked from: started once per parent process, with a scrubbed
environment, after importing numpy, MuJoCo, Drake, OMPL and the planner (`sandbox.preload`), so that a worker
starts in milliseconds with warm imports and no secret in its memory or in `/proc/self/environ`.

This is the standard library's multiprocessing "forkserver" start method. Its server is a process of its
own, spawned (fork + exec) from the parent; it runs no plan code itself and forks one worker per request.
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import multiprocessing.forkserver as mp_forkserver
import os
import threading
from collections.abc import Iterator

from humanoidgen.sandbox.lockdown import scrubbed_environ

PRELOAD = ["humanoidgen.sandbox.preload"]
_lock = threading.Lock()
_started_env: dict[str, str] | None = None


def context() -> mp.context.BaseContext:
    """The forkserver context, its server running with the scrubbed environment."""
    global _started_env
    ctx = mp.get_context("forkserver")
    with _lock:
        if _started_env is None or not _server_alive():
            ctx.set_forkserver_preload(PRELOAD)
            env = scrubbed_environ()
            with _environ(env):
                mp_forkserver.ensure_running()
            _started_env = env
    return ctx


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
