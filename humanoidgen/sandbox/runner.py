"""The locked-down plan worker: a separate process that owns the simulation and runs untrusted plan steps.

Every path that runs plan code (`hgen run`, built-in plans too, `collect`, `bench`, `generate`, the tree
search) goes through `SandboxWorker`. A worker is forked from a pre-imported server process
(`sandbox.forkserver`, started with a scrubbed environment), so it costs milliseconds, not seconds. In the
new process, before anything else:

- a parent-death signal: it dies with the fork server, which dies with its parent (`lifeline`);
- file descriptors: everything but its two pipes is closed; stdin, stdout and stderr point at /dev/null
  (what a step prints is captured in Python and capped; C-level writes go nowhere);
- `lockdown.lock_down`: rlimits, Landlock, seccomp (see there). This happens before `setup` runs and
  before any thread exists, so every thread the simulator or renderer starts later is bound too;
- then `setup()` (trusted, picklable, module level) returns the namespace that steps see.

Requests go down a pipe as pickles (the parent is trusted); everything coming back is `wire`-encoded
(JSON + raw arrays), never unpickled, with a size cap and a deadline (`frames`). A step over its wall-time budget, a worker that
dies, or one that sends a malformed message is killed; the next request starts a fresh worker and says so
(`worker_restarted=True`). `on_stream` receives what the worker streams while it works (video frames), up to
a cap per request in messages and bytes (a worker past it is killed, as for a malformed message).
"""

from __future__ import annotations

import contextlib
import io
import os
import pickle
import threading
import time
import traceback
import weakref
from collections.abc import Callable
from dataclasses import asdict
from typing import Any, Self

from humanoidgen.sandbox import frames, lifeline, wire
from humanoidgen.sandbox.checker import STEP_FUNCTION, CodeRejected, check_code, safe_builtins
from humanoidgen.sandbox.lockdown import Limits, lock_down
from humanoidgen.sandbox.outcome import (MESSAGE_LIMIT, STDOUT_LIMIT, STEP_FILENAME, SandboxError, StepOutcome,
                                         exit_text, message_of, outcome_of_reply, step_line, type_name)
from humanoidgen.sandbox.twin import TWIN, TwinChannel, fork_twin

# Measured (2 CPUs): numpy+mujoco+drake ~0.33 GiB of address space, HumanoidEnv + planner ~1.35 GiB peak.
# Recording cameras needs more: the renderer maps large buffers and frames pile up (see task_episode).
DEFAULT_MEMORY_LIMIT = 4 << 30
DEFAULT_CPU_LIMIT_S = 3600
DEFAULT_TIMEOUT_S = 120.0
DEFAULT_MAX_MESSAGE_BYTES = 8 << 30
# Stream messages one request may send: a worker streaming without end would keep the parent decoding and
# calling `on_stream` until the request's deadline (minutes in an episode). 10 min of video at 25 fps is 15,000
# frames; at 1280x720 RGB, 41 GB.
MAX_STREAM_MESSAGES = 100_000
MAX_STREAM_BYTES = 64 << 30


class SandboxWorker:
    """A locked-down worker process holding one namespace; `run_step` executes untrusted steps in it."""

    def __init__(self, setup: Callable[[], dict[str, Any]], *, memory_limit: int | None = DEFAULT_MEMORY_LIMIT,
                 cpu_limit_s: int | None = DEFAULT_CPU_LIMIT_S, start_timeout_s: float = 300.0,
                 on_stream: Callable[[Any], None] | None = None,
                 max_message_bytes: int = DEFAULT_MAX_MESSAGE_BYTES, max_stream_messages: int = MAX_STREAM_MESSAGES,
                 max_stream_bytes: int = MAX_STREAM_BYTES, twin: bool = False) -> None:
        self.setup = setup
        self.wants_twin = twin  # fork a trusted twin after setup, before the lockdown (`sandbox.twin`)
        self.twin: TwinChannel | None = None
        self.limits = Limits(memory_bytes=memory_limit, cpu_seconds=cpu_limit_s)
        self.start_timeout_s = start_timeout_s
        self.on_stream = on_stream
        self.max_message_bytes = max_message_bytes
        self.max_stream_messages = max_stream_messages  # per request; past either cap: ProtocolError
        self.max_stream_bytes = max_stream_bytes
        self.lockdown: dict | None = None  # what the kernel applied in the current worker
        self._proc: Any = None
        self._send: Any = None  # parent -> worker (pickles)
        self._recv: Any = None  # worker -> parent (wire bytes)
        self._started_before = False

    # -- public -----------------------------------------------------------------------------------------
    def run_step(self, code: str, timeout_s: float = DEFAULT_TIMEOUT_S) -> StepOutcome:
        """Check and execute one step; every failure comes back as data."""
        return self._request(("run", code), timeout_s)

    def call(self, fn_name: str, *args: Any, timeout_s: float = DEFAULT_TIMEOUT_S, **kwargs: Any) -> Any:
        """Call `fn_name` from the namespace `setup` returned (not one a step rebound); return its result
        (JSON-like data and numpy arrays: tuples come back as lists)."""
        out = self._request(("call", (fn_name, args, kwargs)), timeout_s)
        if not out.ok:
            raise SandboxError(out)
        return out.value

    @property
    def alive(self) -> bool:
        return self._proc is not None and self._proc.is_alive()

    def start(self) -> bool:
        """Start the worker if it is not running; True if it started one now."""
        if self.alive:
            return False
        self._kill()
        from humanoidgen.sandbox.forkserver import context, worker_name

        ctx = context()
        down_r, down_w = ctx.Pipe(duplex=False)
        up_r, up_w = ctx.Pipe(duplex=False)
        twin_pipes = (ctx.Pipe(duplex=False), ctx.Pipe(duplex=False)) if self.wants_twin else None
        twin_ends = (twin_pipes[0][0], twin_pipes[1][1]) if twin_pipes else None
        self._proc = ctx.Process(target=_worker_main, args=(down_r, up_w, self.setup, self.limits, twin_ends),
                                 daemon=True, name=worker_name(self.setup))
        self._proc.start()
        _live.add(self)
        down_r.close()
        up_w.close()  # so a dead worker shows up as EOF on our end
        if twin_pipes:
            for end in twin_ends:
                end.close()
            self.twin = TwinChannel(twin_pipes[0][1], twin_pipes[1][0])
        self._send, self._recv = down_w, up_r
        os.set_blocking(down_w.fileno(), False)  # both ends are read/written against deadlines
        os.set_blocking(up_r.fileno(), False)
        try:
            reply = self._receive(self.start_timeout_s)
        except _NoReply as e:
            self._kill()
            raise RuntimeError(f"plan worker did not start: {e}") from None
        if not isinstance(reply, dict) or reply.get("kind") != "ready":
            message = reply.get("message", "") if isinstance(reply, dict) else ""
            self._kill()
            raise RuntimeError(f"plan worker setup failed: {str(message)[:MESSAGE_LIMIT]}")
        self.lockdown = reply.get("lockdown") if isinstance(reply.get("lockdown"), dict) else None
        _warn_once(self.lockdown)
        return True

    def close(self) -> None:
        if self.alive and self._send is not None:
            # _post reports a dead or stuck pipe as _NoReply (a worker killed by kill_all may still look alive)
            with contextlib.suppress(_NoReply):
                self._post(("exit", None), 1.0)
            self._proc.join(2.0)
        self._kill()

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- internals --------------------------------------------------------------------------------------
    def _request(self, message: tuple[str, Any], timeout_s: float) -> StepOutcome:
        restarted = self.start() and self._started_before
        self._started_before = True
        t0 = time.perf_counter()
        try:
            self._post(message, timeout_s)
            reply = self._receive(timeout_s)
            out = outcome_of_reply(reply)
            if out is None:
                raise _NoReply("protocol: not a reply")
        except _NoReply as e:
            out = self._lost(e, timeout_s)
        except BaseException:  # Ctrl-C in the parent: the worker must not outlive the request
            self._kill()
            raise
        out.seconds = time.perf_counter() - t0
        out.worker_restarted = restarted
        return out

    def _post(self, message: Any, timeout_s: float) -> None:
        try:
            frames.write_frame(self._send.fileno(), pickle.dumps(message), time.monotonic() + timeout_s)
        except frames.FrameTimeout:
            raise _NoReply("timeout") from None
        except (frames.FrameClosed, OSError):
            raise _NoReply("died") from None

    def _receive(self, timeout_s: float) -> Any:
        """The next reply, handing stream messages to `on_stream` on the way (at most the stream caps)."""
        deadline = time.monotonic() + timeout_s
        messages = nbytes = 0
        while True:
            try:
                data = frames.read_frame(self._recv.fileno(), self.max_message_bytes, deadline)
            except frames.FrameTimeout:
                raise _NoReply("timeout") from None
            except (frames.FrameClosed, OSError):
                raise _NoReply("died") from None
            except frames.FrameTooLarge as e:  # the pipe is no longer in step
                raise _NoReply(f"protocol: {e}") from None
            try:
                msg = wire.decode(data)
            except wire.WireError as e:
                raise _NoReply(f"protocol: {e}") from None
            if isinstance(msg, dict) and msg.get("kind") == "stream":
                messages, nbytes = messages + 1, nbytes + len(data)
                if messages > self.max_stream_messages or nbytes > self.max_stream_bytes:
                    raise _NoReply(f"protocol: streamed more than {self.max_stream_messages} messages or "
                                   f"{self.max_stream_bytes} bytes in one request")
                if self.on_stream is not None:
                    self.on_stream(msg.get("payload"))
                continue
            return msg

    def _lost(self, e: _NoReply, timeout_s: float) -> StepOutcome:
        reason = str(e)
        if reason == "died":
            self._proc.join(2.0)  # EOF can arrive before the worker is reaped
        exitcode = self._proc.exitcode
        self._kill()
        if reason == "timeout":
            return StepOutcome(False, "Timeout", f"step exceeded {timeout_s:g} s; worker killed, its state is lost",
                               None, 0.0)
        if reason == "died":
            return StepOutcome(False, "WorkerDied", f"worker process died ({exit_text(exitcode)}); its state is "
                               "lost", None, 0.0)
        return StepOutcome(False, "ProtocolError", f"worker sent a malformed message ({reason.split(': ', 1)[-1]});"
                           " worker killed, its state is lost", None, 0.0)

    def _kill(self) -> None:
        if self._proc is not None:
            if self._proc.is_alive():
                self._proc.kill()  # SIGKILL: a step stuck in C code ignores anything softer
            self._proc.join(5.0)
            with contextlib.suppress(ValueError):
                self._proc.close()
        for conn in (self._send, self._recv):
            if conn is not None:
                with contextlib.suppress(OSError):
                    conn.close()
        if self.twin is not None:
            self.twin.close()
        self._proc = self._send = self._recv = self.twin = None


class _NoReply(Exception):
    pass


_warned: set[str] = set()


def _warn_once(report: dict | None) -> None:
    """A layer the kernel lacks is said loudly in the parent (the worker's stderr goes nowhere), once."""
    import logging

    warnings = report.get("warnings") if isinstance(report, dict) else ["the worker sent no lockdown report"]
    for w in warnings if isinstance(warnings, list) else []:
        if isinstance(w, str) and w not in _warned:
            _warned.add(w)
            logging.getLogger("humanoidgen.sandbox").warning("PLAN WORKER NOT FULLY LOCKED DOWN: %s", w[:500])


_live: weakref.WeakSet[SandboxWorker] = weakref.WeakSet()


def kill_all() -> None:
    """Kill every worker of this process now (an interrupted collection); their requests fail as data."""
    for w in list(_live):
        proc = w._proc
        if proc is not None:
            with contextlib.suppress(Exception):
                proc.kill()


# -- worker process ---------------------------------------------------------------------------------------
_channel: Any = None
_channel_lock = threading.Lock()


def stream(payload: Any) -> None:
    """From inside a worker: send `payload` (wire data) to the parent's `on_stream` now."""
    if _channel is None:
        raise RuntimeError("not in a plan worker")
    _send({"kind": "stream", "payload": payload})


def _send(msg: Any) -> None:
    data = wire.encode(msg)
    with _channel_lock:
        frames.write_frame(_channel, data)


def _isolate_fds(keep: tuple[int, ...]) -> None:
    """Close every inherited descriptor but `keep`; stdin/stdout/stderr become /dev/null."""
    null = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):
        os.dup2(null, fd)
    os.close(null)
    try:
        fds = sorted(int(x) for x in os.listdir("/proc/self/fd"))
    except OSError:
        fds = list(range(3, 1024))
    for fd in fds:
        if fd > 2 and fd not in keep:
            with contextlib.suppress(OSError):
                os.close(fd)


def _worker_main(down: Any, up: Any, setup: Callable[[], dict[str, Any]], limits: Limits,
                 twin: tuple[Any, Any] | None = None) -> None:
    global _channel
    twin_fds = tuple(end.fileno() for end in twin) if twin else ()
    _isolate_fds((down.fileno(), up.fileno(), *twin_fds))
    _channel = up.fileno()
    down_fd = down.fileno()
    try:
        lifeline.die_with_parent(lifeline.server_pid())  # a step in progress must not outlive hgen
        if not twin_fds:
            report = lock_down(limits)
            provided = dict(setup())
            provided.pop(TWIN, None)
        else:  # setup is trusted code: it builds the world, the twin is forked with it, then the lockdown
            provided = dict(setup())
            main = provided.pop(TWIN, None)
            if not callable(main):
                raise RuntimeError("a twin was asked for, but setup() returned none")
            fork_twin(main, *twin_fds, limits, _isolate_fds)
            for fd in twin_fds:
                os.close(fd)
            report = lock_down(limits)
    except BaseException as e:  # noqa: BLE001 - report any setup failure to the parent
        _send({"kind": "error", "message": f"{type(e).__name__}: {e}\n{traceback.format_exc(limit=5)}"})
        return
    import math

    import numpy

    builtins_ = safe_builtins({"numpy": numpy, "math": math})
    namespace: dict[str, Any] = {**provided, "__builtins__": builtins_, "__name__": "__sandbox__"}
    _send({"kind": "ready", "names": sorted(provided), "lockdown": report.to_dict()})
    while True:
        try:
            kind, payload = pickle.loads(frames.read_frame(down_fd, 1 << 40))  # from the trusted parent
        except (frames.FrameClosed, OSError, KeyboardInterrupt):
            return
        if kind == "exit":
            return
        out = _run(payload, namespace, builtins_) if kind == "run" else _call(payload, provided)
        try:
            _send({"kind": "reply", "outcome": asdict(out)})
        except (TypeError, ValueError) as e:  # a call result that is not wire data
            _send({"kind": "reply", "outcome": asdict(StepOutcome(False, type(e).__name__,
                                                                  f"could not send result: {e}", None, 0.0))})


class _CappedIO(io.StringIO):
    """Captured stdout that keeps only the first STDOUT_LIMIT characters (a print loop cannot eat memory)."""

    def write(self, s: str) -> int:
        room = STDOUT_LIMIT - self.tell()
        if room > 0:
            super().write(str(s)[:room])
        return len(s)


def _run(source: str, namespace: dict[str, Any], builtins_: dict[str, Any]) -> StepOutcome:
    """Check and execute one step in `namespace`. Its `__builtins__` are put back to the restricted ones first:
    real builtins a step got in by a route the checker does not know yet do not carry over to the next step
    (functions it defined keep the builtins they were made with)."""
    namespace["__builtins__"] = builtins_
    buf = _CappedIO()
    try:
        names = {k for k in namespace if not k.startswith("__")}
        checked = check_code(source, names)
        code = checked.compile(STEP_FILENAME)
    except CodeRejected as e:
        first = e.violations[0]
        return StepOutcome(False, "CodeRejected", str(e)[:MESSAGE_LIMIT], first.line, 0.0)
    try:
        with contextlib.redirect_stdout(buf), contextlib.redirect_stderr(buf):
            exec(code, namespace)  # noqa: S102 - checked code, restricted builtins, locked-down process
            if checked.defines_step:
                namespace[STEP_FUNCTION](namespace.get("planner"))
    except BaseException as e:  # noqa: BLE001 - every failure of the step is reported as data
        return StepOutcome(False, type_name(e), message_of(e), step_line(e), 0.0, buf.getvalue())
    return StepOutcome(True, None, "", None, 0.0, buf.getvalue())


def _call(payload: tuple[str, tuple, dict], provided: dict[str, Any]) -> StepOutcome:
    name, args, kwargs = payload
    fn = provided.get(name)
    if not callable(fn):
        return StepOutcome(False, "KeyError", f"setup registered no function {name!r}", None, 0.0)
    try:
        value = fn(*args, **kwargs)
    except BaseException as e:  # noqa: BLE001
        return StepOutcome(False, type_name(e), message_of(e), None, 0.0)
    return StepOutcome(True, None, "", None, 0.0, value=value)
