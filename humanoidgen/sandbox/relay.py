"""The fork server's stdout and stderr: pipes that the process which started it copies to its own.

A process started by another inherits its stdout and stderr, and the workers' fork server (`forkserver`) did:
the very files of `hgen run`. A reader of that output (`subprocess.run(..., capture_output=True)`,
`hgen run ... | tee run.log`) is done only when every copy is closed, so it waited, after `hgen run` had
exited, until the server it took down with it (`lifeline`) had torn down its memory: 0.08 s on a quiet
machine, 0.2-0.3 s on a busy one. The server's workers are not the issue: they point theirs at /dev/null
before anything else (`runner`).

With `relayed_stdio` around its start, the server holds pipes instead, and a thread of this process copies
what comes down them to this process's stdout and stderr: what the server says (a worker's traceback before
it locked itself down, a warning) still appears where it did, and the reader is done when this process is.
What the server would say after this process has gone is lost: there was nobody left to read it.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from collections.abc import Iterator

CHUNK = 1 << 16


@contextlib.contextmanager
def relayed_stdio() -> Iterator[None]:
    """While this holds, file descriptors 1 and 2 are pipes whose contents go to what they were before: a
    process started meanwhile inherits the pipes. What other threads write meanwhile is relayed too. Where
    either is closed, nothing changes."""
    try:
        targets = [os.dup(1), os.dup(2)]
    except OSError:  # no stdout or stderr to relay to
        yield
        return
    pipes = [os.pipe(), os.pipe()]
    for (read_end, _), target in zip(pipes, targets):
        threading.Thread(target=_copy, args=(read_end, target), name="hgen-relay", daemon=True).start()
    _flush()
    saved = [os.dup(1), os.dup(2)]
    try:
        os.dup2(pipes[0][1], 1)
        os.dup2(pipes[1][1], 2)
        yield
    finally:
        _flush()
        for fd, was in ((1, saved[0]), (2, saved[1])):
            os.dup2(was, fd)
            os.close(was)
        for _, write_end in pipes:  # the started process holds its own copies
            os.close(write_end)


def _copy(source: int, target: int) -> None:
    """Copy `source` to `target` until every writer has closed it. A target that fails is dropped and the
    pipe still drained, so that no writer ever blocks on it."""
    try:
        while data := os.read(source, CHUNK):
            while data and target >= 0:
                try:
                    data = data[os.write(target, data):]
                except OSError:  # a reader that went away (a closed pipe)
                    os.close(target)
                    target = -1
    finally:
        os.close(source)
        if target >= 0:
            os.close(target)


def _flush() -> None:
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
