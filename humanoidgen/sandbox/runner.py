"""Run checked plan steps in a separate worker process that owns the simulation.

The worker is started with the "spawn" context: a fresh interpreter inherits no state from the parent (no
copied MuJoCo/EGL contexts, locks or threads, which fork would duplicate in an undefined state) and no
objects the untrusted code could reach. The cost (importing numpy/mujoco again, ~1 s) is paid once per
worker. `setup` must therefore be picklable (a module-level function); it runs in the child and returns the
namespace the steps see, e.g. {"planner": planner, "np": numpy, "math": math}.

Per step the child re-checks the source against its *current* namespace (names bound by earlier steps are
allowed; parsing untrusted text also happens in the child, so a parser crash cannot hit the parent), executes
it with only `SAFE_BUILTINS`, and sends back a `StepOutcome`. A step over its wall-time budget gets the worker
killed (state lost); the next call starts a fresh worker and says so (`worker_restarted=True`). The child's
address space is capped with RLIMIT_AS, so a memory bomb raises MemoryError there or kills the child, never
the parent.
"""

from __future__ import annotations

import builtins
import contextlib
import io
import multiprocessing as mp
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Self

from humanoidgen.sandbox.checker import (
    SAFE_BUILTINS,
    STEP_FUNCTION,
    CodeRejected,
    check_code,
)

# Measured (spawn child, 2 CPUs): numpy+mujoco+drake imports ~0.33 GiB of address space, HumanoidEnv +
# planner ~1.35 GiB peak. More cores add BLAS thread stacks/arenas, so 4 GiB leaves ~2.5 GiB for steps.
DEFAULT_MEMORY_LIMIT = 4 << 30
DEFAULT_TIMEOUT_S = 120.0
STDOUT_LIMIT = 64_000
STEP_FILENAME = "<step>"


@dataclass
class StepOutcome:
    ok: bool
    error_type: str | None  # exception class name, "CodeRejected", "Timeout" or "WorkerDied"
    message: str
    line: int | None  # line within the step where it failed
    seconds: float  # wall time seen by the parent (check + execution + round trip)
    stdout: str = ""
    worker_restarted: bool = False  # a fresh worker ran this step: state from earlier steps is gone
    value: Any = None  # the result of `SandboxWorker.call`


class SandboxError(RuntimeError):
    """`SandboxWorker.call` failed; `outcome` says how."""

    def __init__(self, outcome: StepOutcome) -> None:
        self.outcome = outcome
        super().__init__(f"{outcome.error_type}: {outcome.message}")


class SandboxWorker:
    """A worker process holding one namespace; `run_step` executes untrusted steps in it."""

    def __init__(self, setup: Callable[[], dict[str, Any]], *, memory_limit: int | None = DEFAULT_MEMORY_LIMIT,
                 start_timeout_s: float = 300.0, start_method: str = "spawn") -> None:
        self.setup = setup
        self.memory_limit = memory_limit
        self.start_timeout_s = start_timeout_s
        self._ctx = mp.get_context(start_method)
        self._proc: Any = None
        self._conn: Any = None
        self._started_before = False

    # -- public -----------------------------------------------------------------------------------------
    def run_step(self, code: str, timeout_s: float = DEFAULT_TIMEOUT_S) -> StepOutcome:
        """Check and execute one step; every failure comes back as data."""
        return self._request(("run", code), timeout_s)

    def call(self, fn_name: str, *args: Any, timeout_s: float = DEFAULT_TIMEOUT_S, **kwargs: Any) -> Any:
        """Call `fn_name` from the namespace `setup` returned (not one a step rebound); return its result."""
        out = self._request(("call", (fn_name, args, kwargs)), timeout_s)
        if not out.ok:
            raise SandboxError(out)
        return out.value

    def start(self) -> bool:
        """Start the worker if it is not running; True if it started one now."""
        if self._proc is not None and self._proc.is_alive():
            return False
        self._kill()
        parent, child = self._ctx.Pipe()
        self._proc = self._ctx.Process(target=_worker_main, args=(child, self.setup, self.memory_limit),
                                       daemon=True, name="humanoidgen-sandbox")
        self._proc.start()
        child.close()  # so a dead child shows up as EOF on our end
        self._conn = parent
        if not parent.poll(self.start_timeout_s):
            self._kill()
            raise RuntimeError("sandbox worker did not start in time")
        try:
            status, message = parent.recv()
        except EOFError:
            code = self._proc.exitcode
            self._kill()
            raise RuntimeError(f"sandbox worker died during setup (exit code {code})") from None
        if status != "ready":
            self._kill()
            raise RuntimeError(f"sandbox setup failed: {message}")
        return True

    def close(self) -> None:
        if self._conn is not None and self._proc is not None and self._proc.is_alive():
            with contextlib.suppress(OSError, BrokenPipeError):
                self._conn.send(("exit", None))
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
            self._conn.send(message)
            ready = self._conn.poll(timeout_s)
            reply = self._conn.recv() if ready else None
        except (EOFError, OSError, BrokenPipeError):
            reply, ready = None, True
        seconds = time.perf_counter() - t0
        if reply is None:
            if ready:
                self._proc.join(2.0)  # EOF can arrive before the child is reaped
            exitcode = self._proc.exitcode
            self._kill()
            if not ready:
                out = StepOutcome(False, "Timeout", f"step exceeded {timeout_s:g} s; worker killed, its state is "
                                  "lost", None, seconds)
            else:
                out = StepOutcome(False, "WorkerDied", f"worker process died (exit code {exitcode}); its state "
                                  "is lost", None, seconds)
        else:
            out = reply
            out.seconds = seconds
        out.worker_restarted = restarted
        return out

    def _kill(self) -> None:
        if self._proc is not None:
            if self._proc.is_alive():
                self._proc.kill()  # SIGKILL: a step stuck in C code ignores anything softer
            self._proc.join(5.0)
            with contextlib.suppress(ValueError):
                self._proc.close()
        if self._conn is not None:
            self._conn.close()
        self._proc = self._conn = None


# -- child process --------------------------------------------------------------------------------------
def _worker_main(conn: Any, setup: Callable[[], dict[str, Any]], memory_limit: int | None) -> None:
    if memory_limit is not None:
        import resource

        # Soft and hard: the limit cannot be raised again from inside the worker.
        resource.setrlimit(resource.RLIMIT_AS, (memory_limit, memory_limit))
    try:
        provided = dict(setup())
    except BaseException as e:  # noqa: BLE001 - report any setup failure to the parent
        conn.send(("error", f"{type(e).__name__}: {e}\n{traceback.format_exc(limit=5)}"))
        return
    safe = {name: getattr(builtins, name) for name in SAFE_BUILTINS if hasattr(builtins, name)}
    namespace: dict[str, Any] = {**provided, "__builtins__": safe, "__name__": "__sandbox__"}
    conn.send(("ready", sorted(provided)))
    while True:
        try:
            kind, payload = conn.recv()
        except (EOFError, KeyboardInterrupt):
            return
        if kind == "exit":
            return
        if kind == "run":
            out = _run(payload, namespace)
        else:
            out = _call(payload, provided)
        try:
            conn.send(out)
        except Exception as e:  # noqa: BLE001 - e.g. a call result that cannot be pickled
            conn.send(StepOutcome(False, type(e).__name__, f"could not send result: {e}", None, 0.0))


class _CappedIO(io.StringIO):
    """Captured stdout that keeps only the first STDOUT_LIMIT characters (a print loop cannot eat memory)."""

    def write(self, s: str) -> int:
        room = STDOUT_LIMIT - self.tell()
        if room > 0:
            super().write(s[:room])
        return len(s)


def _run(source: str, namespace: dict[str, Any]) -> StepOutcome:
    buf = _CappedIO()
    try:
        names = {k for k in namespace if not k.startswith("__")}
        checked = check_code(source, names)
        code = checked.compile(STEP_FILENAME)
    except CodeRejected as e:
        first = e.violations[0]
        return StepOutcome(False, "CodeRejected", str(e), first.line, 0.0)
    try:
        with contextlib.redirect_stdout(buf), contextlib.redirect_stderr(buf):
            exec(code, namespace)  # noqa: S102 - checked code, restricted builtins, separate process
            if checked.defines_step:
                namespace[STEP_FUNCTION](namespace.get("planner"))
    except BaseException as e:  # noqa: BLE001 - every failure of the step is reported as data
        return StepOutcome(False, type(e).__name__, str(e) or repr(e), _step_line(e), 0.0, buf.getvalue())
    return StepOutcome(True, None, "", None, 0.0, buf.getvalue())


def _call(payload: tuple[str, tuple, dict], provided: dict[str, Any]) -> StepOutcome:
    name, args, kwargs = payload
    fn = provided.get(name)
    if not callable(fn):
        return StepOutcome(False, "KeyError", f"setup registered no function {name!r}", None, 0.0)
    try:
        value = fn(*args, **kwargs)
    except BaseException as e:  # noqa: BLE001
        return StepOutcome(False, type(e).__name__, str(e) or repr(e), None, 0.0)
    return StepOutcome(True, None, "", None, 0.0, value=value)


def _step_line(e: BaseException) -> int | None:
    """Line of the innermost traceback frame inside the step's code."""
    line = None
    for frame in traceback.extract_tb(e.__traceback__):
        if frame.filename == STEP_FILENAME:
            line = frame.lineno
    return line
