"""The sandbox for LLM-written plan steps: static checker, step splitting and the worker process."""

from __future__ import annotations

import contextlib
import math
import os
import statistics
import time
import types
from collections import deque

import numpy as np
import pytest

from humanoidgen.sandbox import (
    CodeRejected,
    SandboxWorker,
    check_code,
    split_steps,
    strip_api_imports,
)
from humanoidgen.sandbox.checker import BLOCKED_ATTRIBUTES

NAMES = {"planner", "np", "math", "spin", "calls", "crash"}

PAPER_SCRIPT = '''from humanoidgen.motion_planning.h1_2.solution.generated.solver_env import *
def step(planner:HumanoidMotionPlanner):
    # Step 1: Left hand grasps the drawer
    planner.hand_pre_grasp("left")
    constraint_r = planner.generate_constraints(
            obj_name="drawer",
            obj_id=0,
            action="grasp",
            hand_name="left"
        )
    _, target_effector_pose = planner.generate_end_effector_pose(constraint_r, "left")
    planner.move_to_pose_with_screw(
        target_effector_pose,
        "left",
        attach_obj=False
    )
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
'''


# -- checker ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("source, needle", [
    ("import os", "import"),
    ("from os import path", "from ... import"),
    ("open('/etc/passwd')", "open"),
    ("x = ().__class__.__bases__", "__class__"),
    ("getattr(planner, '_x')", "getattr"),
    ("eval('1')", "eval"),
    ("__import__('os')", "__import__"),
    ("planner._private", "_private"),
    ("foo(1)", "unknown name `foo`"),
    ("np.f2py.os.system('ls')", "f2py"),
    ("g = (i for i in [1])\ng.gi_frame.f_back", "gi_frame"),
    ("class A:\n    pass", "class"),
    ("for i in iter(int, 1):\n    pass", "for"),
    ("import humanoidgen.sandbox as h", "import"),  # only the exact paper import lines are stripped
])
def test_checker_rejects(source: str, needle: str) -> None:
    with pytest.raises(CodeRejected) as e:
        check_code(strip_api_imports(source), NAMES)
    assert any(needle in v.message for v in e.value.violations), e.value.violations


def test_violations_report_line_numbers() -> None:
    with pytest.raises(CodeRejected) as e:
        check_code("x = 1\ny = 2\nimport os\nplanner._env", NAMES)
    assert [v.line for v in e.value.violations] == [3, 4]


def test_size_and_node_caps() -> None:
    with pytest.raises(CodeRejected, match="bytes"):
        check_code("x = 1\n" * 5000, NAMES)
    with pytest.raises(CodeRejected, match="nodes"):
        check_code("x = [" + "1, " * 6000 + "]", NAMES)
    with pytest.raises(CodeRejected, match="syntax"):
        check_code("x = (", NAMES)


def test_checker_accepts_paper_script_unchanged() -> None:
    checked = check_code(strip_api_imports(PAPER_SCRIPT), NAMES)
    assert checked.defines_step
    assert strip_api_imports(PAPER_SCRIPT).split("\n")[1] == PAPER_SCRIPT.split("\n")[1]  # lines kept


def test_checker_accepts_typical_steps() -> None:
    src = """
hand = "right"
pose = planner.right_hand_init_pose
target = np.array([0.1, -0.2, 0.3]) + 0.01 * math.cos(math.pi)
for i in range(3):
    target[i] += 0.001 * i
for side in ["left", "right"]:
    planner.hand_pre_grasp(side)
a, (b, c) = 1, (2, 3)
a += len([x ** 2 for x in range(4) if x % 2]) + sum(v for v in {1, 2})
d = {k: v for k, v in zip("ab", [1, 2])}
if a > 1 and not b:
    pass
else:
    print(f"target {target!r:>10} {d['a']}")
assert abs(target[0]) < 1, "out of reach"
_, pose = planner.generate_end_effector_pose(None, hand_name=hand)
planner.move_to_pose_with_screw(pose, *[hand], **{"attach_obj": False})
"""
    check_code(src, NAMES)


def test_split_steps_fenced_blocks() -> None:
    response = (
        "Step 1: pre-grasp\n```python\n    planner.hand_pre_grasp(\"right\")\n```\n"
        "Step 2:\n```python\n    from humanoidgen.x.solver_env import *\n    c = planner.generate_constraints(\n"
        "        obj_name=\"can\", obj_id=0)\n```\nDone."
    )
    steps = split_steps(response)
    assert steps == ['planner.hand_pre_grasp("right")',
                     'c = planner.generate_constraints(\n    obj_name="can", obj_id=0)']
    for s in steps:
        check_code(s, NAMES)


def test_split_steps_whole_file_with_step_function() -> None:
    (body,) = split_steps(PAPER_SCRIPT)
    assert body.startswith("# Step 1") and body.endswith('obj_id=0)')
    check_code(body, NAMES)


def test_numpy_attribute_walk_reaches_no_dangerous_module() -> None:
    """Every object reachable from `np`/`math` through attributes the checker allows is harmless: no module
    of the OS or the interpreter, and no helper that reads or writes attributes named by strings (through
    which `update_wrapper(f, g, updated=('__globals__',))` merges a module's globals into the plan's). A
    package's submodules count too: numpy hands some out on first access (`np.core`), others are there
    once anything imported them."""
    import functools
    import inspect
    import operator
    import pkgutil
    import typing
    import warnings

    dangerous = {"os", "sys", "subprocess", "builtins", "importlib", "ctypes", "pickle", "io", "shutil",
                 "pathlib", "inspect", "types", "marshal", "runpy", "posix", "gc", "contextlib", "functools",
                 "operator", "typing", "string", "dataclasses", "copyreg"}
    bad_functions = [open, exec, eval, compile, getattr, setattr, delattr, vars, globals, locals, __import__,
                     functools.update_wrapper, functools.wraps, operator.attrgetter, operator.methodcaller,
                     inspect.getattr_static, typing.get_type_hints]
    seen, found = set(), []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # np.core and friends warn on first access
        queue = deque([("np", np), ("math", math)])
        while queue:
            path, obj = queue.popleft()
            if id(obj) in seen or path.count(".") > 4:
                continue
            seen.add(id(obj))
            if isinstance(obj, types.ModuleType) and obj.__name__.split(".")[0] in dangerous or any(obj is f for f in bad_functions):
                found.append(path)
            elif isinstance(obj, (types.ModuleType, type)):
                names = set(dir(obj))
                if isinstance(obj, types.ModuleType) and isinstance(getattr(obj, "__path__", None), list):
                    names |= {m.name for m in pkgutil.iter_modules(obj.__path__)}
                for name in sorted(names):
                    if name.startswith("_") or name in BLOCKED_ATTRIBUTES:
                        continue
                    with contextlib.suppress(Exception):  # lazy attributes that fail to import
                        queue.append((f"{path}.{name}", getattr(obj, name)))
    assert not found


# -- runner ----------------------------------------------------------------------------------------------
class FakePlanner:
    def __init__(self) -> None:
        self.calls: list[tuple] = []
        self._private = "secret"

    def hand_pre_grasp(self, hand_name: str) -> None:
        self.calls.append(("pre_grasp", hand_name))

    def generate_constraints(self, **kwargs):
        return kwargs

    def generate_end_effector_pose(self, constraint, hand_name):
        return None, ("pose", constraint["obj_name"], hand_name)

    def move_to_pose_with_screw(self, pose, hand_name, attach_obj=False) -> None:
        self.calls.append(("move", pose, hand_name))

    def hand_grasp(self, hand_name, grasp_object, obj_id) -> None:
        if grasp_object == "ghost":
            raise ValueError("no ghost in the scene")
        self.calls.append(("grasp", grasp_object, obj_id))


def fake_setup() -> dict:
    """Runs in the worker process (module-level so the spawn context can pickle it)."""
    planner = FakePlanner()

    def spin() -> None:
        while True:
            pass

    def calls() -> list:
        return list(planner.calls)

    def crash() -> None:
        os._exit(3)  # stands in for a segfault in the simulator

    return {"planner": planner, "np": np, "math": math, "spin": spin, "calls": calls, "crash": crash}


@pytest.fixture(scope="module")
def worker():
    with SandboxWorker(fake_setup, memory_limit=2 << 30) as w:
        yield w


def test_plans_can_print_numpy_arrays_and_scalars(worker: SandboxWorker) -> None:
    """numpy imports its printing functions on first use through the caller's `__import__`, which plan code
    restricts: unless that `__import__` lets numpy's own loaded modules through (`vocabulary`), a plan's
    `print(np.zeros(3))` failed ("Unable to configure default ndarray.__str__"; found by tests/cheats_unseen/093,
    an honest plan)."""
    out = worker.run_step("print(np.zeros(3), np.float64(1.5), np.int64(2))\nprint(f'{np.ones(2)}', str(np.ones(1)))")
    assert out.ok, out
    assert out.stdout == "[0. 0. 0.] 1.5 2\n[1. 1.] [1.]\n", out.stdout


def test_namespace_persists_across_steps(worker: SandboxWorker) -> None:
    steps = split_steps(PAPER_SCRIPT.replace('"drawer"', '"can"'))
    out = worker.run_step(steps[0])
    assert out.ok, out
    out = worker.run_step("n = len(planner.calls)\nprint('calls', n, constraint_r['obj_name'])")
    assert out.ok and out.stdout == "calls 3 can\n", out
    assert worker.call("calls")[-1] == ["grasp", "can", 0]  # wire data: tuples become lists
    # The paper's whole-file form: the runner calls `step(planner)` after defining it.
    out = worker.run_step(strip_api_imports(PAPER_SCRIPT))
    assert out.ok, out
    assert worker.call("calls")[-1] == ["grasp", "drawer", 0]


def test_step_errors_come_back_as_data(worker: SandboxWorker) -> None:
    out = worker.run_step('x = 1\n\nplanner.hand_grasp("right", grasp_object="ghost", obj_id=0)\n')
    assert not out.ok and out.error_type == "ValueError" and out.line == 3 and "ghost" in out.message
    out = worker.run_step("y = 1\nplanner._private")
    assert out.error_type == "CodeRejected" and out.line == 2
    out = worker.run_step("y = [1][5]")
    assert out.error_type == "IndexError" and out.line == 1
    assert worker.run_step("z = x + 1").ok  # the worker survived and kept `x`


def test_timeout_kills_and_restarts_worker(worker: SandboxWorker) -> None:
    assert worker.run_step("kept = 1").ok
    t0 = time.perf_counter()
    out = worker.run_step("a = 1\nspin()", timeout_s=1.0)
    assert out.error_type == "Timeout" and not out.ok
    assert time.perf_counter() - t0 < 5.0
    out = worker.run_step("b = 2")
    assert out.ok and out.worker_restarted
    out = worker.run_step("c = kept")  # state was lost with the killed worker
    assert out.error_type == "CodeRejected" and "kept" in out.message and not out.worker_restarted


@pytest.mark.parametrize("bomb", [
    "x = [0] * (4 * 10**8)",  # one 3.2 GB allocation
    "x = np.ones(10**11)",  # 800 GB
    "x = [[0] * 10**6 for i in range(500)]",  # grows 8 MB at a time up to 4 GB: only the rlimit stops it
])
def test_memory_bomb_is_contained(worker: SandboxWorker, bomb: str) -> None:
    out = worker.run_step(bomb, timeout_s=30.0)
    assert not out.ok and out.error_type in {"MemoryError", "_ArrayMemoryError", "WorkerDied"}, out
    assert worker.run_step("y = 1").ok


def test_worker_death_is_reported(worker: SandboxWorker) -> None:
    out = worker.run_step("crash()")
    assert out.error_type == "WorkerDied" and "exit code 3" in out.message
    assert worker.run_step("y = 1").worker_restarted


def test_call_errors(worker: SandboxWorker) -> None:
    from humanoidgen.sandbox import SandboxError

    with pytest.raises(SandboxError, match="KeyError"):
        worker.call("nonexistent")
    worker.run_step("calls = 5")  # a step cannot replace what setup registered for `call`
    assert isinstance(worker.call("calls"), list)


def test_step_overhead(worker: SandboxWorker) -> None:
    worker.run_step("x = 0")
    times = []
    for _ in range(50):
        t0 = time.perf_counter()
        out = worker.run_step("x = x + 1")
        times.append(time.perf_counter() - t0)
        assert out.ok
    median = statistics.median(times)
    print(f"sandbox per-step overhead: median {median * 1e3:.2f} ms, max {max(times) * 1e3:.2f} ms")
    assert median < 0.020


def test_close_survives_a_worker_whose_pipe_is_gone() -> None:
    """kill_all (an interrupted collection) can leave a worker that still looks alive while its pipe is dead;
    closing it must not raise (a module fixture's teardown did, with _NoReply: died)."""
    from humanoidgen.sandbox import runner

    w = SandboxWorker(fake_setup, memory_limit=2 << 30)
    w.start()
    try:
        def dead(*_a, **_k):
            raise runner._NoReply("died")

        w._post = dead  # what _post reports once the worker's end of the pipe is closed
        w.close()
        assert not w.alive
    finally:
        w._kill()


# -- a worker dies with the process that asked for it ------------------------------------------------------
# Starts a worker and keeps it busy in a long call (an idle worker already ends when its pipe closes). A
# forked child holds a copy of the fork server's "alive" pipe, as any fork of `hgen` would: the server then
# sees no end of file when `hgen` dies.
_PARENT = """
import multiprocessing.forkserver as fs, os, sys, time
from humanoidgen.sandbox import SandboxWorker
from humanoidgen.sandbox.probe import probe_setup

w = SandboxWorker(probe_setup, memory_limit=2 << 30)
w.start()
child = os.fork()
if child == 0:
    time.sleep(60)
    os._exit(0)
print(w._proc.pid, fs._forkserver._forkserver_pid, child, flush=True)
w.call("attempt", "import time\\ntime.sleep(120)", timeout_s=300)
"""


def _running(pid: int) -> bool:
    """Alive and not a zombie (an orphan's reaper may be slow)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] not in ("Z", "X")
    except OSError:
        return False


@pytest.mark.parametrize("sig", ["SIGTERM", "SIGKILL"])
def test_worker_and_fork_server_die_with_their_parent(sig: str) -> None:
    """An `hgen` killed while a worker holds an episode takes the worker (child of the fork server, not of
    `hgen`) and the fork server with it, within seconds: neither lives on holding gigabytes."""
    import signal
    import subprocess
    import sys

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (os.getcwd(), os.environ.get("PYTHONPATH")) if p)}
    parent = subprocess.Popen([sys.executable, "-c", _PARENT], stdout=subprocess.PIPE, text=True, env=env)
    pids: list[int] = []
    child = 0
    try:
        line = parent.stdout.readline()  # the parent starts a fork server and a worker: seconds
        *pids, child = [int(p) for p in line.split()]
        assert len(pids) == 2 and all(_running(p) for p in pids), line
        time.sleep(1.0)  # the worker is in its call
        parent.send_signal(getattr(signal, sig))
        parent.wait(10)
        deadline = time.monotonic() + 5.0
        while any(_running(p) for p in pids) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not [p for p in pids if _running(p)], f"still running after the parent's {sig}: {pids}"
    finally:
        parent.kill()
        parent.wait(10)
        if child:  # it exists only to hold the pipe
            with contextlib.suppress(OSError):
                os.kill(child, 9)
        for pid in pids:  # only what this test started (checked by name before the kill)
            with contextlib.suppress(OSError):
                if _running(pid) and b"python" in open(f"/proc/{pid}/cmdline", "rb").read():
                    os.kill(pid, 9)


_THREAD_PARENT = """
import multiprocessing.forkserver as fs, threading, time
from humanoidgen.sandbox import SandboxWorker
from humanoidgen.sandbox.probe import probe_setup

w = SandboxWorker(probe_setup, memory_limit=2 << 30)
t = threading.Thread(target=w.start)
t.start()
t.join()
server, worker = fs._forkserver._forkserver_pid, w._proc.pid
time.sleep(0.5)
out = w._request(("call", ("attempt", ("x = 1",), {})), 60.0)
print(out.value, out.worker_restarted, server == fs._forkserver._forkserver_pid, worker == w._proc.pid, flush=True)
w.close()
"""


def test_a_fork_server_started_from_a_thread_outlives_the_thread() -> None:
    """The parent-death signal fires when the *thread* that started a process ends: a server started from a
    pool's thread must not die with that thread (it gets no signal; it still ends when its alive pipe closes)."""
    import subprocess
    import sys

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (os.getcwd(), os.environ.get("PYTHONPATH")) if p)}
    out = subprocess.run([sys.executable, "-c", _THREAD_PARENT], capture_output=True, text=True, env=env, timeout=300)
    assert out.stdout.split() == ["ALLOWED", "False", "True", "True"], (out.stdout, out.stderr[-2000:])
