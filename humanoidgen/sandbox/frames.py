"""Length-prefixed messages over a raw pipe, with deadlines on the reading and the writing side.

multiprocessing's Connection blocks without a deadline once a message has begun: a worker that announces a
large message and then stalls would hang the parent forever, and one that stops reading would block the
parent's next send. Here the parent reads and writes with select() against a deadline and a size cap;
the worker (which has no deadline to keep) writes and reads blocking.
"""

from __future__ import annotations

import os
import select
import struct
import time

_LEN = struct.Struct("<Q")


class FrameTimeout(Exception):
    """The deadline passed before the whole message arrived (or could be written)."""


class FrameClosed(Exception):
    """The other end is gone."""


class FrameTooLarge(Exception):
    """The other end announced a message over the cap."""


def write_frame(fd: int, data: bytes, deadline: float | None = None) -> None:
    """Write one message; with a deadline (time.monotonic) the fd must be non-blocking."""
    buf = memoryview(_LEN.pack(len(data)) + data) if len(data) < 1 << 16 else None
    parts = [buf] if buf is not None else [memoryview(_LEN.pack(len(data))), memoryview(data)]
    for part in parts:
        while part:
            if deadline is not None:
                _wait(fd, deadline, write=True)
            try:
                n = os.write(fd, part)
            except BlockingIOError:
                continue
            except (BrokenPipeError, ConnectionError):
                raise FrameClosed() from None
            part = part[n:]


def read_frame(fd: int, max_bytes: int, deadline: float | None = None) -> bytes:
    """Read one message; with a deadline the fd must be non-blocking."""
    (n,) = _LEN.unpack(_read_exact(fd, _LEN.size, deadline))
    if n > max_bytes:
        raise FrameTooLarge(f"a message of {n} bytes (limit {max_bytes})")
    return _read_exact(fd, n, deadline)


def _read_exact(fd: int, n: int, deadline: float | None) -> bytes:
    chunks, got = [], 0
    while got < n:
        if deadline is not None:
            _wait(fd, deadline, write=False)
        try:
            chunk = os.read(fd, min(n - got, 1 << 22))
        except BlockingIOError:
            continue
        if not chunk:
            raise FrameClosed()
        chunks.append(chunk)
        got += len(chunk)
    return b"".join(chunks)


def _wait(fd: int, deadline: float, write: bool) -> None:
    left = deadline - time.monotonic()
    if left <= 0:
        raise FrameTimeout()
    r, w, _ = select.select([] if write else [fd], [fd] if write else [], [], left)
    if not r and not w:
        raise FrameTimeout()
