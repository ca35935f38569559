"""Plan workers and their fork server die with the process that started them.

A worker is the child of the fork server, not of `hgen`; the fork server is `hgen`'s child. When `hgen`
dies (SIGTERM, SIGKILL, a crash), a worker busy in a step never reads its closed pipe and lived on, holding
gigabytes; the fork server exits on its own only once nobody else holds a copy of its "alive" pipe (a fork
of `hgen` would). So each sets a parent-death signal (prctl PR_SET_PDEATHSIG, SIGKILL) for itself:

- the fork server, on import of this module as the first of its preload modules (`forkserver.PRELOAD`),
  when `ENV_PARENT` (set by `forkserver.context` in the server's environment only) names its parent;
- each worker in `runner._worker_main`, before lockdown, with the fork server's pid recorded here.

The signal fires when the parent *thread* ends: `forkserver` asks for it only when the server is started
from the main thread, which lasts as long as its process (from another thread, e.g. a pool's, the server ends
as before, when its alive pipe closes, and its workers with it). A parent that died before the signal was set is seen in `os.getppid()` (the orphan
was handed to another reaper), and then this process exits at once. The worker's seccomp filter refuses
clearing the signal again (`lockdown`).
"""

from __future__ import annotations

import ctypes
import os
import signal

ENV_PARENT = "HGEN_SANDBOX_SERVER_PARENT"  # the parent's pid, or "-": no signal for the server
PR_SET_PDEATHSIG = 1
_server_pid: int | None = None  # set in the fork server; a forked worker inherits it


def die_with_parent(expected_parent: int | None) -> None:
    """SIGKILL this process when its parent ends; exit now if the parent (`expected_parent`) is gone already.
    Raises OSError if the kernel refuses the signal."""
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) != 0:
        err = ctypes.get_errno()
        raise OSError(err, f"prctl(PR_SET_PDEATHSIG): {os.strerror(err)}")
    if expected_parent is not None and os.getppid() != expected_parent:
        os._exit(1)  # the parent died before the signal was set: nobody is left to ask for anything


def server_pid() -> int | None:
    """The fork server's pid, in the server and in the workers forked from it; None elsewhere."""
    return _server_pid


def _in_fork_server() -> None:
    """Runs on import: only the fork server's environment holds ENV_PARENT (taken out, so workers lack it)."""
    global _server_pid
    parent = os.environ.pop(ENV_PARENT, None)
    if parent is None:
        return
    _server_pid = os.getpid()  # the workers check for it even where the server itself has no signal
    if not parent.isdigit():  # started from a thread that may end before its process
        return
    try:
        die_with_parent(int(parent))
    except OSError:  # the server must come up (multiprocessing skips only ImportError): as before, then
        pass


_in_fork_server()
