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

import array
import contextlib
import fcntl
import os
import sys
import termios
import threading
import time
from collections.abc import Iterator

CHUNK = 1 << 16
DRAIN_S = 2.0  # at the block's end, how long to wait for the copies to catch up with what was already written


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
    copies = [_Copy(read_end, target) for (read_end, _), target in zip(pipes, targets)]
    for copy in copies:
        threading.Thread(target=copy.run, name="hgen-relay", daemon=True).start()
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
        # What was written before the block ended reaches the targets before this process goes on (and maybe
        # exits): the copy threads are daemons, and on a busy machine they lag (a child's last line was lost).
        deadline = time.monotonic() + DRAIN_S
        for copy in copies:
            copy.wait_caught_up(deadline)


class _Copy:
    """Copies `source` to `target` until every writer has closed it. A target that fails is dropped and the
    pipe still drained, so that no writer ever blocks on it."""

    def __init__(self, source: int, target: int) -> None:
        self.source, self.target = source, target
        self.busy = False  # between reading a chunk and having written it
        self.done = False

    def run(self) -> None:
        try:
            while True:
                data = os.read(self.source, CHUNK)
                if not data:
                    break
                self.busy = True
                while data and self.target >= 0:
                    try:
                        data = data[os.write(self.target, data):]
                    except OSError:  # a reader that went away (a closed pipe)
                        os.close(self.target)
                        self.target = -1
                self.busy = False
        finally:
            self.done = True
            os.close(self.source)
            if self.target >= 0:
                os.close(self.target)

    def wait_caught_up(self, deadline: float) -> None:
        """Until nothing is left in the pipe nor in hand (or the deadline)."""
        while not self.done and time.monotonic() < deadline:
            pending = array.array("i", [0])
            try:
                fcntl.ioctl(self.source, termios.FIONREAD, pending)
            except OSError:  # closed meanwhile: all copied
                return
            if pending[0] == 0 and not self.busy:
                return
            time.sleep(0.002)


def _flush() -> None:
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
