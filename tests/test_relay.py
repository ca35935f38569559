"""The fork server's stdout and stderr are pipes its parent relays (`sandbox.relay`): what the server says
still appears on the parent's stdout and stderr, and a reader of the parent's output is done when the parent
is, not when the last process holding a copy of its files is."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

RELAYED = textwrap.dedent('''
    import subprocess, sys
    from humanoidgen.sandbox.relay import relayed_stdio

    with relayed_stdio():
        print("mine, meanwhile", flush=True)
        subprocess.run(["sh", "-c", "echo child-out; echo child-err >&2; (sleep 300 & echo $! > {pid})"])
    print("mine, after", flush=True)
''')


def _kill(pid_file: Path) -> None:
    if pid_file.exists():
        try:
            os.kill(int(pid_file.read_text()), signal.SIGKILL)
        except (ProcessLookupError, ValueError):
            pass


def test_a_process_started_meanwhile_is_heard_and_not_waited_for(tmp_path):
    pid = tmp_path / "sleeper.pid"
    t0 = time.monotonic()
    try:
        r = subprocess.run([sys.executable, "-c", RELAYED.format(pid=pid)], capture_output=True, text=True,
                           timeout=240, cwd=ROOT)
    finally:
        _kill(pid)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split() == ["mine,", "meanwhile", "child-out", "mine,", "after"]
    assert r.stderr.split() == ["child-err"]
    assert time.monotonic() - t0 < 200  # the sleeper holding the child's stdout and stderr was not waited for


SERVER = textwrap.dedent('''
    from humanoidgen.sandbox import SandboxWorker
    from humanoidgen.sandbox.forkserver import prestart

    # The server runs this while it warms up: it prints, and leaves a process holding its stdout and stderr.
    prestart(warm=("os:system", "echo server-out; echo server-err >&2; (sleep 300 & echo $! > {pid})"))
    with SandboxWorker(dict) as w:
        w.start()  # the server is up
    print("parent done", flush=True)
''')


def test_the_fork_servers_output_is_relayed_and_its_end_not_waited_for(tmp_path):
    pid = tmp_path / "sleeper.pid"
    t0 = time.monotonic()
    try:
        r = subprocess.run([sys.executable, "-c", SERVER.format(pid=pid)], capture_output=True, text=True,
                           timeout=500, cwd=ROOT)
    finally:
        _kill(pid)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split()[-3:] == ["server-out", "parent", "done"]
    assert "server-err" in r.stderr.split()
    assert time.monotonic() - t0 < 250  # not the sleeper's 300 s
