"""Ending a command's process without the interpreter's teardown, once its work is done and written.

A normal exit of a process that imported numpy, MuJoCo, pydantic and the task library first frees every
module's objects one by one: about 0.1 s after `hgen run` has printed its result (0.4-0.8 s on a machine
other jobs share), and a user waits for it. A command that has finished everything it writes says so
(`allow`), and `app` in `cli.main` then ends the process with `exit_now`: it does what a normal exit does
that a command's results can depend on (the exit handlers: multiprocessing's finalizers, logging's flush,
temporary folders; then flushing stdout and stderr) and leaves the rest to the operating system. The exit code
is the command's. Where a thread other than the main one still runs, which a normal exit would wait for, it
exits normally instead.

Only the real program does this: a command invoked in-process (typer's test runner) never reaches it.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import sys
import threading
from typing import NoReturn

_allowed = False


def allow() -> None:
    """The running command has written all its output and closed its files: its process may end now."""
    global _allowed
    _allowed = True


def allowed() -> bool:
    return _allowed


def exit_code(code: object) -> int:
    """The exit status `sys.exit(code)` gives: None is 0, an int is itself, anything else is printed and 1."""
    if code is None:
        return 0
    if isinstance(code, int):
        return code & 0xFF
    with contextlib.suppress(Exception):
        print(code, file=sys.stderr)
    return 1


def exit_now(code: object) -> NoReturn:
    """End the process with `code` (as `sys.exit` would) after the exit handlers and a flush of stdout and
    stderr, skipping the interpreter's teardown; a normal `SystemExit` while another non-daemon thread runs."""
    if any(t.is_alive() and not t.daemon for t in threading.enumerate() if t is not threading.current_thread()):
        raise SystemExit(code)
    status = exit_code(code)
    atexit._run_exitfuncs()  # what a normal exit runs first (they print their own errors)
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):  # a closed pipe: nothing left to lose
            stream.flush()
    os._exit(status)
