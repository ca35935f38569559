"""The operating system is the boundary: a worker whose namespace hands plan code the real `os`, `socket`,
`subprocess` and full builtins (as if the checker had been bypassed) still cannot write files, start
processes, open sockets, signal its parent, read secrets or reach the parent's memory."""

from __future__ import annotations

import builtins
import contextlib
import os
import socket
import threading
import time
from pathlib import Path

import pytest

from humanoidgen.sandbox import SandboxWorker, wire
from humanoidgen.sandbox.lockdown import scrubbed_environ

CANARY = "sk-canary-lockdown-5b1e0c"


def escape_setup() -> dict:
    """The worst case: plan code gets the real modules and builtins (no checker would let this through)."""
    import ctypes
    import subprocess

    def run(code: str) -> str:
        ns = {"os": os, "socket": socket, "subprocess": subprocess, "ctypes": ctypes, "__builtins__": builtins}
        try:
            exec(code, ns)  # noqa: S102 - deliberately unchecked: the kernel must stop it
        except BaseException as e:  # noqa: BLE001
            return f"blocked: {type(e).__name__}: {e}"
        return "ALLOWED " + repr(ns.get("result"))[:200]

    return {"run": run}


@pytest.fixture(scope="module")
def worker():
    os.environ["OPENAI_API_KEY"] = CANARY  # the parent holds a secret...
    try:
        with SandboxWorker(escape_setup, memory_limit=2 << 30) as w:
            w.start()
            yield w
    finally:
        os.environ.pop("OPENAI_API_KEY", None)


@pytest.fixture()
def listener():
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(4)
    srv.settimeout(0.2)
    accepted: list = []
    stop = threading.Event()

    def serve() -> None:
        while not stop.is_set():
            try:
                conn, _ = srv.accept()
            except OSError:
                continue
            accepted.append(conn)

    t = threading.Thread(target=serve, daemon=True)
    t.start()
    yield srv.getsockname()[1], accepted
    stop.set()
    t.join(2)
    srv.close()


def test_every_layer_is_applied(worker: SandboxWorker) -> None:
    assert worker.lockdown is not None
    assert worker.lockdown["seccomp"] and worker.lockdown["landlock_abi"] >= 1, worker.lockdown
    assert worker.lockdown["warnings"] == [] and worker.lockdown["threads_at_lockdown"] == 1


@pytest.mark.parametrize("name, code", [
    ("open_write", "open('{m}/open', 'w').write('x')"),
    ("os_open", "os.open('{m}/os_open', os.O_CREAT | os.O_WRONLY)"),
    ("append", "open('{m}/../canary.txt', 'a').write('x')"),
    ("mkdir", "os.mkdir('{m}/dir')"),
    ("unlink", "os.unlink('{m}/../canary.txt')"),
    ("rename", "os.rename('{m}/../canary.txt', '{m}/moved')"),
    ("symlink", "os.symlink('/etc/passwd', '{m}/link')"),
    ("chmod", "os.chmod('{m}/../canary.txt', 0o777)"),
    ("system", "rc = os.system('touch {m}/system')\nif rc:\n    raise OSError(rc, 'system() failed')"),
    ("subprocess", "subprocess.run(['touch', '{m}/subprocess'])"),
    ("execv", "os.execv('/bin/touch', ['touch', '{m}/execv'])"),
    ("fork", "pid = os.fork()\nif pid == 0:\n    open('{m}/fork', 'w')\n    os._exit(0)"),
    ("posix_spawn", "os.posix_spawn('/bin/touch', ['touch', '{m}/spawn'], {{}})"),
    ("libc_system", "rc = ctypes.CDLL(None).system(b'touch {m}/libc')\nif rc:\n    raise OSError(rc, 'failed')"),
    ("libc_fork", "ctypes.CDLL(None).fork()\nopen('{m}/libc_fork', 'w')"),
    ("socket", "s = socket.create_connection(('127.0.0.1', {port}))"),
    ("udp", "socket.socket(socket.AF_INET, socket.SOCK_DGRAM).sendto(b'x', ('127.0.0.1', {port}))"),
    ("unix_socket", "socket.socket(socket.AF_UNIX).connect('/tmp/none')"),
    ("kill_parent", "os.kill(os.getppid(), 0)"),
    ("parent_environ", "result = open(f'/proc/{{os.getppid()}}/environ').read()"),
    ("parent_mem", "result = open(f'/proc/{{os.getppid()}}/mem', 'rb').read(1)"),
    ("home", "result = os.listdir(os.path.expanduser('~'))"),
    ("markers_readable", "result = os.listdir('{m}')"),
    ("setrlimit", "import resource\nresource.setrlimit(resource.RLIMIT_AS, (-1, -1))"),
    ("clear_pdeathsig", "import ctypes\nif ctypes.CDLL(None, use_errno=True).prctl(1, 0, 0, 0, 0):\n"
                        "    raise OSError(ctypes.get_errno(), 'refused')"),
])
def test_kernel_blocks(worker: SandboxWorker, listener, tmp_path: Path, name: str, code: str) -> None:
    port, accepted = listener
    markers = tmp_path / "markers"
    markers.mkdir()
    canary = tmp_path / "canary.txt"
    canary.write_text("untouched")
    out = worker.call("run", code.format(m=markers, port=port))
    time.sleep(0.1)
    assert out.startswith("blocked"), (name, out)
    assert list(markers.iterdir()) == [] and canary.read_text() == "untouched" and oct(canary.stat().st_mode)[-3:] != "777"
    assert accepted == []


# SysV and POSIX IPC: a segment, queue or semaphore set outlives the worker (and SysV shm lies outside
# RLIMIT_AS); another process's segment could be read. `L` is libc, errors come back through ctypes' errno.
_LIBC = "import ctypes, errno, resource\nL = ctypes.CDLL(None, use_errno=True)\n"
_FAILS = "\nif r < 0:\n    raise OSError(ctypes.get_errno(), 'refused')\nresult = r"


def _syscall(name: str, args: str) -> str:
    """A raw system call by name; only a refusal by the filter (EPERM) counts as blocked: reaching the kernel
    (EINVAL, EFAULT for the null arguments) means the filter let it through."""
    return (_LIBC + "import pyseccomp as sc\n"
            f"r = L.syscall(sc.resolve_syscall(sc.system_arch(), '{name}'), {args})\n"
            "if r < 0 and ctypes.get_errno() in (errno.EPERM, errno.EACCES):\n    raise OSError(ctypes.get_errno(), 'refused')\n"
            "result = (r, ctypes.get_errno())")


_IPC = [
    ("shmget", _LIBC + "r = L.shmget(0, 64 << 20, 0o1600)" + _FAILS),
    ("shmat_other", _LIBC + "L.shmat.restype = ctypes.c_void_p\np = L.shmat({shmid}, None, 0)\n"
                    "r = -1 if p in (None, 2**64 - 1) else 0" + _FAILS + " = ctypes.string_at(p, 32)"),
    ("shmctl_other", _LIBC + "buf = ctypes.create_string_buffer(256)\nr = L.shmctl({shmid}, 2, buf)" + _FAILS),
    ("msgget", _LIBC + "r = L.msgget(0, 0o1600)" + _FAILS),
    ("semget", _LIBC + "r = L.semget(0, 4, 0o1600)" + _FAILS),
    ("semop", _syscall("semop", "0, None, 0")),
    ("semtimedop", _syscall("semtimedop", "0, None, 0, None")),
    ("semctl", _syscall("semctl", "0, 0, 2, 0")),
    ("msgsnd", _syscall("msgsnd", "0, None, 0, 0")),
    ("msgrcv", _syscall("msgrcv", "0, None, 0, 0, 0")),
    ("msgctl", _syscall("msgctl", "0, 2, None")),
    ("mq_open", _LIBC + "r = L.mq_open(b'/{mq}', os.O_CREAT | os.O_RDWR, 0o600, None)" + _FAILS),
    ("mq_unlink", _syscall("mq_unlink", "b'{mq}'")),
    ("mq_timedsend", _syscall("mq_timedsend", "-1, None, 0, 0, None")),
    ("mq_timedreceive", _syscall("mq_timedreceive", "-1, None, 0, None, None")),
    ("mq_notify", _syscall("mq_notify", "-1, None")),
    ("mq_getsetattr", _syscall("mq_getsetattr", "-1, None, None")),
]


@pytest.mark.parametrize("name, code", _IPC, ids=[n for n, _ in _IPC])
def test_ipc_is_out_of_reach(worker: SandboxWorker, name: str, code: str) -> None:
    """No SysV shared memory, message queue or semaphore set, no POSIX message queue: nothing is made that
    outlives the worker, and another process's segment (made here, holding a canary) cannot be read."""
    import ctypes
    import secrets

    libc = ctypes.CDLL(None, use_errno=True)
    libc.shmat.restype = ctypes.c_void_p
    before = _sysv_ids()
    shmid = libc.shmget(0, 4096, 0o1600)
    assert shmid >= 0
    mq = f"hgen-lockdown-{secrets.token_hex(4)}"
    try:
        addr = libc.shmat(shmid, None, 0)
        ctypes.memmove(addr, CANARY.encode(), len(CANARY))
        libc.shmdt(ctypes.c_void_p(addr))
        out = worker.call("run", code.format(shmid=shmid, mq=mq))
        assert out.startswith("blocked"), (name, out)
    finally:
        libc.shmctl(shmid, 0, None)  # IPC_RMID
        made = _sysv_ids() - before - {("shm", shmid)}
        for kind, ident in made:  # whatever got through: removed, and reported below
            libc[{"shm": "shmctl", "msg": "msgctl", "sem": "semctl"}[kind]](ident, 0, 0)
        leaked_mq = libc.mq_unlink(f"/{mq}".encode()) == 0
    assert not made and not leaked_mq, (made, leaked_mq)


def test_the_worker_has_an_ipc_namespace_of_its_own_where_allowed(worker: SandboxWorker) -> None:
    """Where the kernel allows it (root, or a user namespace) the worker moves to an empty IPC namespace."""
    assert isinstance(worker.lockdown.get("ipc_namespace"), bool)
    cap_eff = int(next(line for line in open("/proc/self/status") if line.startswith("CapEff")).split()[1], 16)
    if cap_eff & (1 << 21):  # CAP_SYS_ADMIN: this machine allows it, so the worker must have one
        assert worker.lockdown["ipc_namespace"]
    if worker.lockdown["ipc_namespace"]:
        assert os.readlink(f"/proc/{worker._proc.pid}/ns/ipc") != os.readlink("/proc/self/ns/ipc")


def _sysv_ids() -> set[tuple[str, int]]:
    out = set()
    for kind, column in (("shm", 1), ("msg", 1), ("sem", 1)):
        with contextlib.suppress(OSError):
            for line in Path(f"/proc/sysvipc/{kind}").read_text().splitlines()[1:]:
                out.add((kind, int(line.split()[column])))
    return out


_SCHEDULING = [
    ("nice_self", "os.setpriority(os.PRIO_PROCESS, 0, -20)"),
    ("nice_group", "os.setpriority(os.PRIO_PGRP, 0, os.getpriority(os.PRIO_PGRP, 0))"),
    ("nice_parent", "os.setpriority(os.PRIO_PROCESS, os.getppid(), os.getpriority(os.PRIO_PROCESS, os.getppid()))"),
    # if it got through, put it back at once (a spinning real-time worker would starve the machine)
    ("fifo_self", "try:\n    os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(1))\n"
                  "finally:\n    os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))"),
    ("fifo_parent", "os.sched_setscheduler(os.getppid(), os.SCHED_OTHER, os.sched_param(0))"),
    ("setparam_self", "os.sched_setparam(0, os.sched_param(0))"),
    ("affinity_parent", "os.sched_setaffinity(os.getppid(), os.sched_getaffinity(os.getppid()))"),
    ("affinity_group_leader", "os.sched_setaffinity(os.getpgrp(), os.sched_getaffinity(os.getpgrp()))"),
    ("sched_setattr", _syscall("sched_setattr", "0, None, 0")),
    ("ioprio_set", _syscall("ioprio_set", "1, 0, 2 << 13")),
    ("prlimit_parent", "import resource\nresource.prlimit(os.getppid(), resource.RLIMIT_NOFILE)"),
]


@pytest.mark.parametrize("name, code", _SCHEDULING, ids=[n for n, _ in _SCHEDULING])
def test_scheduling_is_out_of_reach(worker: SandboxWorker, name: str, code: str) -> None:
    """A plan cannot renice, re-schedule or re-pin itself, its fork server or their process group."""
    out = worker.call("run", code)
    assert out.startswith("blocked"), (name, out)


def test_priority_limits_are_zero() -> None:
    """Nor can it raise its priority within its limits: RLIMIT_NICE and RLIMIT_RTPRIO are 0 after lockdown even
    when the process started with room (a parent's limits are inherited)."""
    import json
    import resource

    from humanoidgen.sandbox import lockdown

    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        try:
            os.close(r)
            for which in (resource.RLIMIT_NICE, resource.RLIMIT_RTPRIO):
                with contextlib.suppress(ValueError, OSError):  # raising them needs CAP_SYS_RESOURCE
                    resource.setrlimit(which, (10, 10))
            lockdown.lock_down(lockdown.Limits(memory_bytes=None))
            with open(f"/proc/{os.getpid()}/limits") as f:
                out = [line.split()[-2:] for line in f if line.startswith(("Max nice", "Max realtime priority"))]
        except BaseException as e:  # noqa: BLE001 - never back into pytest in the child
            out = f"{type(e).__name__}: {e}"
        os.write(w, json.dumps(out).encode())
        os._exit(0)
    os.close(w)
    os.waitpid(pid, 0)
    with os.fdopen(r) as f:
        assert json.loads(f.read()) == [["0", "0"], ["0", "0"]]


def render_setup() -> dict:
    """A scene and a camera in a locked-down worker: what recording video does."""
    from humanoidgen.sim.cameras import CameraRig
    from humanoidgen.sim.scene import SceneBuilder

    import mujoco

    scene = SceneBuilder().build()
    data = mujoco.MjData(scene.model)
    mujoco.mj_forward(scene.model, data)

    def render() -> dict:
        rig = CameraRig(scene.model, 64, 48)
        try:
            rgb = rig.render(data, mujoco.mj_id2name(scene.model, mujoco.mjtObj.mjOBJ_CAMERA, 0),
                             depth=False, segmentation=False).rgb
        finally:
            rig.close()
        return {"shape": list(rgb.shape), "spread": int(rgb.max()) - int(rgb.min())}

    return {"render": render}


def test_rendering_works_in_a_locked_down_worker() -> None:
    """EGL/Mesa rendering (video frames) needs none of what the filter refuses."""
    with SandboxWorker(render_setup, memory_limit=4 << 30) as w:
        w.start()
        assert w.lockdown["seccomp"] and not w.lockdown["warnings"], w.lockdown
        out = w.call("render", timeout_s=120.0)
    assert out["shape"] == [48, 64, 3] and out["spread"] > 0, out


def test_the_worker_dies_with_its_parent(worker: SandboxWorker) -> None:
    """Its parent-death signal is SIGKILL (the fork server's too: tests/test_sandbox.py kills their parent)."""
    code = "import ctypes\nv = ctypes.c_int()\nctypes.CDLL(None).prctl(2, ctypes.byref(v))\nresult = v.value"
    assert worker.call("run", code) == "ALLOWED 9"


@pytest.mark.parametrize("parent_gone", [False, True])
def test_a_parent_gone_before_the_signal_is_set_ends_the_child(parent_gone: bool) -> None:
    """The race: the parent died between fork and prctl (the child was handed to another reaper)."""
    from humanoidgen.sandbox import lifeline

    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        try:
            lifeline.die_with_parent(os.getppid() + (1 if parent_gone else 0))
            os._exit(0)
        finally:
            os._exit(3)
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == (1 if parent_gone else 0)


def test_no_secret_in_the_worker(worker: SandboxWorker) -> None:
    code = ("text = str(dict(os.environ)) + open('/proc/self/environ').read()\n"
            "result = ('{c}' in text, 'OPENAI_API_KEY' in text, 'MESA_SHADER_CACHE_DISABLE' in os.environ)")
    # no secret anywhere; caches that write are off rather than given a hole
    assert worker.call("run", code.format(c=CANARY)) == "ALLOWED (False, False, True)"


def test_threads_are_allowed_and_bound_too(worker: SandboxWorker) -> None:
    code = ("import threading\nbox = []\n"
            "def go():\n    try:\n        open('/tmp/hgen-thread-escape', 'w')\n        box.append('ALLOWED')\n"
            "    except OSError as e:\n        box.append('blocked')\n"
            "t = threading.Thread(target=go)\nt.start()\nt.join()\nresult = box")
    assert worker.call("run", code) == "ALLOWED ['blocked']"
    assert not Path("/tmp/hgen-thread-escape").exists()


def test_forged_messages_cannot_run_code_in_the_parent(worker: SandboxWorker, tmp_path: Path) -> None:
    """The parent never unpickles: a pickle written straight onto the worker's pipe is a protocol error."""
    marker = tmp_path / "unpickled"
    code = ("import pickle, gc\n"
            "class P:\n    def __reduce__(self):\n        return (open, ('" + str(marker) + "', 'w'))\n"
            "import struct\nfrom humanoidgen.sandbox import runner\n"
            "b = pickle.dumps(P())\nos.write(runner._channel, struct.pack('<Q', len(b)) + b)\n")
    reply = worker._request(("call", ("run", (code,), {})), 30.0)
    assert not reply.ok and reply.error_type == "ProtocolError" and not marker.exists()
    assert worker.call("run", "result = 1") == "ALLOWED 1"  # a fresh worker took over


@pytest.mark.parametrize("code, error", [
    # announces 1 GB, sends 3 bytes, stalls: the parent's deadline still holds
    ("import struct, time\nfrom humanoidgen.sandbox import runner\n"
     "os.write(runner._channel, struct.pack('<Q', 10**9) + b'abc')\ntime.sleep(60)", "Timeout"),
    # announces more than the cap: refused before anything is read
    ("import struct\nfrom humanoidgen.sandbox import runner\n"
     "os.write(runner._channel, struct.pack('<Q', 2**62))", "ProtocolError"),
])
def test_a_stalling_or_flooding_worker_cannot_hang_the_parent(worker: SandboxWorker, code: str, error: str) -> None:
    t0 = time.perf_counter()
    reply = worker._request(("call", ("run", (code,), {})), 3.0)
    assert not reply.ok and reply.error_type == error and time.perf_counter() - t0 < 10
    assert worker.call("run", "result = 2") == "ALLOWED 2"


def test_a_stream_flood_is_a_protocol_error(worker: SandboxWorker) -> None:
    """Stream messages (video frames) are capped per request in count and bytes: a worker streaming without
    end is killed long before the request's deadline, and `on_stream` sees no more than the cap."""
    from humanoidgen.sandbox import runner

    seen = [0]
    worker.on_stream = lambda _payload: seen.__setitem__(0, seen[0] + 1)
    flood = "from humanoidgen.sandbox import runner\nwhile True:\n    runner.stream({p})"
    try:
        t0 = time.perf_counter()
        reply = worker._request(("call", ("run", (flood.format(p=1),), {})), 40.0)
        assert not reply.ok and reply.error_type == "ProtocolError", reply
        assert time.perf_counter() - t0 < 30 and seen[0] <= runner.MAX_STREAM_MESSAGES
        worker.max_stream_bytes, seen[0] = 10 << 20, 0  # a few big frames over a byte cap
        reply = worker._request(("call", ("run", (flood.format(p="'x' * (1 << 20)"),), {})), 120.0)
        assert not reply.ok and reply.error_type == "ProtocolError" and seen[0] <= 10, (reply, seen)
    finally:
        worker.on_stream, worker.max_stream_bytes = None, runner.MAX_STREAM_BYTES
    assert worker.call("run", "result = 3") == "ALLOWED 3"


def test_wire_rejects_what_it_cannot_trust() -> None:
    import numpy as np

    data = wire.encode({"a": np.arange(6, dtype=np.float32).reshape(2, 3), "b": [1, "x", None, float("nan")]})
    back = wire.decode(data)
    assert back["a"].shape == (2, 3) and back["b"][:3] == [1, "x", None]
    for bad in (b"", b"\xff" * 8, data[:-4], data + b"x",
                wire.encode({"x": 1}).replace(b'"arrays": []', b'"arrays": [{"dtype": "object", "shape": [1], '
                                                              b'"nbytes": 8}]')):
        with pytest.raises(wire.WireError):
            wire.decode(bad)
    with pytest.raises(TypeError):
        wire.encode({"f": open})


def test_scrubbed_environment_keeps_only_what_the_simulator_reads() -> None:
    env = scrubbed_environ({"OPENAI_API_KEY": "k", "AWS_SECRET_ACCESS_KEY": "s", "GITHUB_TOKEN": "t",
                            "MUJOCO_GL": "egl", "PATH": "/usr/bin", "OPENBLAS_CORETYPE": "Haswell"})
    assert set(env) >= {"MUJOCO_GL", "PATH", "OPENBLAS_CORETYPE", "MESA_SHADER_CACHE_DISABLE"}
    assert not {"OPENAI_API_KEY", "AWS_SECRET_ACCESS_KEY", "GITHUB_TOKEN"} & set(env)
    assert env["OMP_NUM_THREADS"] == "1"


def test_hgen_sandbox_check_reports_every_probe_blocked() -> None:
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app
    from humanoidgen.sandbox.probe import PROBES

    res = CliRunner().invoke(app, ["sandbox", "check"])
    assert res.exit_code == 0, res.output
    assert "seccomp: on" in res.output and "Landlock: ABI" in res.output
    assert res.output.count("blocked") >= len(PROBES) and "GOT THROUGH" not in res.output


def _lock_down_in_child(strict: bool, broken: str) -> dict:
    """lock_down() in a forked child with one layer made to fail; its report (or error) comes back."""
    import json

    from humanoidgen.sandbox import lockdown

    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        os.close(r)
        try:
            if strict:
                os.environ[lockdown.ENV_STRICT] = "1"

            def fail(*_a, **_k):
                raise OSError("not in this kernel")

            setattr(lockdown, broken, fail)
            out = {"report": lockdown.lock_down(lockdown.Limits(memory_bytes=None)).to_dict()}
        except lockdown.LockdownError as e:
            out = {"error": str(e)}
        os.write(w, json.dumps(out).encode())
        os._exit(0)
    os.close(w)
    os.waitpid(pid, 0)
    with os.fdopen(r) as f:
        return json.loads(f.read())


def test_a_missing_layer_is_reported_never_silent() -> None:
    out = _lock_down_in_child(strict=False, broken="_apply_landlock")
    assert out["report"]["landlock_abi"] == 0 and out["report"]["seccomp"]
    assert any("Landlock not applied" in w for w in out["report"]["warnings"])
    out = _lock_down_in_child(strict=False, broken="_apply_seccomp")
    assert not out["report"]["seccomp"] and any("NOT blocked" in w for w in out["report"]["warnings"])


def test_strict_mode_refuses_an_incomplete_lockdown() -> None:
    out = _lock_down_in_child(strict=True, broken="_apply_seccomp")
    assert "seccomp not applied" in out["error"]


def test_the_parent_warns_loudly_once(caplog) -> None:
    from humanoidgen.sandbox import runner

    runner._warned.discard("Landlock not applied (test)")
    with caplog.at_level("WARNING", logger="humanoidgen.sandbox"):
        runner._warn_once({"warnings": ["Landlock not applied (test)"]})
        runner._warn_once({"warnings": ["Landlock not applied (test)"]})
    hits = [r for r in caplog.records if "NOT FULLY LOCKED DOWN" in r.getMessage()]
    assert len(hits) == 1 and "Landlock not applied (test)" in hits[0].getMessage()


def test_kill_all_ends_the_requests_in_flight() -> None:
    """What an interrupted collection does: every worker of the process dies, its request fails as data."""
    from concurrent.futures import ThreadPoolExecutor

    from humanoidgen.sandbox.runner import kill_all

    with SandboxWorker(escape_setup, memory_limit=2 << 30) as w:
        w.start()
        with ThreadPoolExecutor(1) as pool:
            pending = pool.submit(w._request, ("call", ("run", ("import time\ntime.sleep(60)",), {})), 120.0)
            time.sleep(1.0)
            t0 = time.perf_counter()
            kill_all()
            out = pending.result(timeout=30)
        assert out.error_type == "WorkerDied" and time.perf_counter() - t0 < 10
