"""`hgen sandbox check`: does the kernel lock a plan worker down on this machine? A worker whose namespace
is given the real `os`, `socket` and full builtins (as if the checker had been bypassed) tries each thing a
plan must not do; every attempt must fail. Each probe's effect is also checked from the outside."""

from __future__ import annotations

import builtins
import os
import socket
import tempfile
from dataclasses import dataclass
from pathlib import Path

# (name, what it tries, code; {m} is a folder the probe may not write into, {port} a loopback listener)
PROBES: tuple[tuple[str, str, str], ...] = (
    ("write a file", "open(..., 'w')", "open('{m}/w', 'w').write('x')"),
    ("create a folder", "os.mkdir", "os.mkdir('{m}/d')"),
    ("run a program", "os.execv", "os.execv('/bin/true', ['true'])"),
    ("start a process", "os.fork", "pid = os.fork()\nif pid == 0:\n    os._exit(0)"),
    ("open a socket", "socket.create_connection", "socket.create_connection(('127.0.0.1', {port}), 1)"),
    ("signal the parent", "os.kill(ppid, 0)", "os.kill(os.getppid(), 0)"),
    ("read the parent's environment", "/proc/<ppid>/environ", "open(f'/proc/{{os.getppid()}}/environ').read()"),
    ("read the user's home", "os.listdir('~')", "os.listdir(os.path.expanduser('~'))"),
    ("raise its limits", "setrlimit(RLIMIT_AS)", "import resource\nresource.setrlimit(resource.RLIMIT_AS, (-1, -1))"),
    # a segment that got through is removed at once: the probe leaves nothing behind
    ("share memory with others", "shmget (SysV IPC)", "import ctypes\nL = ctypes.CDLL(None, use_errno=True)\n"
     "r = L.shmget(0, 1 << 20, 0o1600)\nif r < 0:\n    raise OSError(ctypes.get_errno(), 'shmget refused')\n"
     "L.shmctl(r, 0, None)"),
    ("renice its process group", "setpriority(PRIO_PGRP, 0)",
     "os.setpriority(os.PRIO_PGRP, 0, os.getpriority(os.PRIO_PGRP, 0))"),
)


@dataclass
class ProbeResult:
    name: str
    route: str
    blocked: bool
    detail: str


def probe_setup() -> dict:
    def attempt(code: str) -> str:
        try:
            exec(code, {"os": os, "socket": socket, "__builtins__": builtins})  # noqa: S102 - the kernel must stop it
        except BaseException as e:  # noqa: BLE001
            return f"blocked: {type(e).__name__}: {e}"
        return "ALLOWED"

    return {"attempt": attempt}


def run_probes() -> tuple[dict | None, list[ProbeResult]]:
    """The worker's lockdown report and each probe's outcome (judged inside and outside the worker)."""
    from humanoidgen.sandbox.runner import SandboxWorker

    results = []
    with tempfile.TemporaryDirectory() as tmp, socket.socket() as srv:
        srv.bind(("127.0.0.1", 0))
        srv.listen(1)
        srv.setblocking(False)
        with SandboxWorker(probe_setup, memory_limit=2 << 30) as w:
            w.start()
            for name, route, code in PROBES:
                out = w.call("attempt", code.format(m=tmp, port=srv.getsockname()[1]))
                leaked = bool(list(Path(tmp).iterdir()))
                try:
                    srv.accept()[0].close()
                    leaked = True
                except BlockingIOError:
                    pass
                results.append(ProbeResult(name, route, out.startswith("blocked") and not leaked, out[:160]))
            return w.lockdown, results
