"""A plan worker's trusted twin: a copy of the worker process forked after the worker's trusted `setup` has
built its world (the task's scene) and before the worker locks itself down and runs any plan code.

The twin holds the world exactly as the plan's process got it, in memory the plan can never reach (another
address space; the plan's process may not ptrace, signal other processes, read their /proc entries or
create processes). It serves the parent over pipes of its own: the episode's replay runs there
(`episodes.replay_twin`), so the verdict comes from a simulation the plan never ran in, built once for both.

`setup()` asks for a twin by returning a callable under `TWIN`: `main(receive, send)`, where `receive()`
gives the parent's next message (None once the parent is gone) and `send(obj)` sends wire data back. The
twin locks itself down too, and dies with the plan worker (a parent-death signal): a twin outlives no
episode.
"""

from __future__ import annotations

import os
import pickle
import time
from collections.abc import Callable
from typing import Any

from humanoidgen.sandbox import frames, lifeline, wire
from humanoidgen.sandbox.lockdown import Limits, lock_down

TWIN = "__hgen_twin__"


def fork_twin(main: Callable, down_fd: int, up_fd: int, limits: Limits,
              isolate: Callable[[tuple[int, ...]], None]) -> int:
    """In the worker, before its lockdown: fork the twin, which keeps only `down_fd`/`up_fd` and runs `main`;
    returns the twin's pid (in the worker)."""
    parent = os.getpid()
    pid = os.fork()
    if pid:
        return pid
    code = 0
    try:
        isolate((down_fd, up_fd))
        lifeline.die_with_parent(parent)
        lock_down(limits)

        def receive() -> Any:
            try:
                return pickle.loads(frames.read_frame(down_fd, 1 << 40))  # from the trusted parent
            except (frames.FrameClosed, OSError):
                return None

        def send(obj: Any) -> None:
            frames.write_frame(up_fd, wire.encode(obj))

        main(receive, send)
    except BaseException:  # noqa: BLE001 - the parent sees EOF and says the twin was lost
        code = 1
    finally:
        os._exit(code)


class TwinChannel:
    """The parent's end of a twin's pipes, read and written against deadlines."""

    def __init__(self, send_conn: Any, recv_conn: Any) -> None:
        self._send, self._recv = send_conn, recv_conn
        os.set_blocking(send_conn.fileno(), False)
        os.set_blocking(recv_conn.fileno(), False)

    def post(self, message: Any, timeout_s: float) -> None:
        """Send one message; raises TwinLost if the twin is gone or not reading."""
        try:
            frames.write_frame(self._send.fileno(), pickle.dumps(message), time.monotonic() + timeout_s)
        except (frames.FrameTimeout, frames.FrameClosed, OSError, ValueError) as e:
            raise TwinLost(f"the replay process stopped reading ({type(e).__name__})") from None

    def receive(self, timeout_s: float, max_bytes: int) -> Any:
        try:
            return wire.decode(frames.read_frame(self._recv.fileno(), max_bytes, time.monotonic() + timeout_s))
        except frames.FrameTimeout:
            raise TwinLost(f"the replay process did not answer within {timeout_s:g} s") from None
        except (frames.FrameClosed, frames.FrameTooLarge, wire.WireError, OSError, ValueError) as e:
            raise TwinLost(f"the replay process was lost ({type(e).__name__})") from None

    def close(self) -> None:
        for conn in (self._send, self._recv):
            try:
                conn.close()
            except OSError:
                pass


class TwinLost(RuntimeError):
    """The twin died, stopped reading or did not answer in time."""
