"""The hostile plan battery (tests/hostile/NNN_*.py) through the real entry points: no plan leaves a trace.

Each script tries one way out (files, commands, forks, sockets, the API key, signals, hangs, memory, output,
parser bombs, tampering with the verdict; see tests/hostile/battery.py for the format). It runs as the plan
of `block_stack_single` (seed 0) through `run_task_episode`, and afterwards: the marker dir is empty, the
canary file is untouched, nobody connected to our listener, the canary secrets appear in no output or
result, no process naming the marker dir (or any other new descendant) is left, no signal reached us, our
fds 1/2, cwd, threads and memory are as before, the episode came back as data (a failed episode, or a
success only where the script says `# expect: contained`), and a benign plan run next still fails honestly.

`test_generated_hostile_answer` sends a few of the scripts as an LLM's answer to `hgen generate script`
(scripted loopback endpoint), followed by a benign answer, and checks the same plus every file written.

HGEN_HOSTILE_TIMEOUT_S (default 120) is the safety net per episode; run with e.g.
`HGEN_TEST_SECRET=$(python -c 'import secrets; print("sk-hgencanary-" + secrets.token_hex(16))') pytest ...`
to also check that the secret in this process's *startup* environment (/proc/<pid>/environ) stays in.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import dataclasses  # noqa: E402
import importlib.util  # noqa: E402
import json  # noqa: E402
import resource  # noqa: E402
import signal  # noqa: E402
import sys  # noqa: E402
import threading  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402

_spec = importlib.util.spec_from_file_location("hostile_battery", Path(__file__).parent / "hostile" / "battery.py")
battery = sys.modules.setdefault("hostile_battery", importlib.util.module_from_spec(_spec))
_spec.loader.exec_module(battery)

SCRIPTS = battery.scripts()
TIMEOUT_S = float(os.environ.get("HGEN_HOSTILE_TIMEOUT_S", "120"))
STEP_TIMEOUT_S = 5.0  # per step: long enough for the payloads, short enough that 12 hangs cost a minute
OUTPUT_LIMIT = 2_000_000  # bytes of stdout+stderr a plan may cause in this process
RESULT_LIMIT = 5_000_000  # characters of the episode's JSON
MEMORY_GROWTH_LIMIT_KIB = 3 << 20  # ru_maxrss growth of this process (KiB)
WATCHED_SIGNALS = (signal.SIGUSR1, signal.SIGUSR2, signal.SIGHUP)
CONTROL_PLAN = "# step: do nothing\nx = 1\n"
# A few representative scripts, by name without the number, for the generation test.
GENERATION_CASES = ("builtins_open_write", "os_system_builtins_import", "socket_create_connection",
                    "os_environ_print_encoded", "format_path_environ", "os_fork_five", "huge_range",
                    "bytearray_30gib", "forge_pipe_pickle", "patch_predicates")


# -- fixtures ---------------------------------------------------------------------------------------------
@pytest.fixture
def secrets(monkeypatch) -> list[str]:
    """Canary values for the key variables; plus any they had when this process started."""
    values = []
    for var in battery.SECRET_VARS:
        values.append(battery.new_secret())
        monkeypatch.setenv(var, values[-1])
    values += [v for v in _startup_env(battery.SECRET_VARS) if len(v) >= 8]
    return values


@pytest.fixture
def listener():
    lst = battery.Listener()
    yield lst
    lst.close()


@pytest.fixture
def box(tmp_path: Path):
    """tmp_path/box: canary.txt (known content) and an empty markers/ dir; plus a /dev/shm path."""
    root = tmp_path / "box"
    (root / "markers").mkdir(parents=True)
    canary = root / "canary.txt"
    canary.write_text(f"canary {os.urandom(8).hex()}\n")
    b = Box(root, root / "markers", canary, canary.read_text(), _identity(canary), battery.shm_path())
    yield b
    for pid in battery.processes_mentioning(str(b.markers)):  # started by the plan under test
        _kill(pid)
    if os.path.lexists(b.shm):
        os.unlink(b.shm)


@pytest.fixture
def signals():
    """Counts the signals a plan might send us (SIGKILL/SIGSTOP cannot be watched: we would not be here)."""
    got: list[int] = []
    old = {s: signal.signal(s, lambda n, _f: got.append(n)) for s in WATCHED_SIGNALS}
    yield got
    for s, h in old.items():
        signal.signal(s, h)


@dataclasses.dataclass
class Box:
    root: Path
    markers: Path
    canary: Path
    canary_text: str
    canary_id: tuple
    shm: str


# -- the battery ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("script", SCRIPTS, ids=lambda s: s.name)
def test_hostile_plan_leaves_no_trace(script, tmp_path, box, listener, secrets, signals, capfd, record_property):
    from humanoidgen.episodes.plans import PlanFormatError

    plan = tmp_path / "plan.py"
    plan.write_bytes(_render(script, box, listener.port))
    before = _process_state()
    outcome = _bounded(lambda: _episode(plan), TIMEOUT_S)
    problems = _leftovers(box, listener, signals, before, outcome)
    out, err = capfd.readouterr()
    texts = {"stdout": out, "stderr": err}
    if outcome.error is not None:
        texts["exception"] = f"{type(outcome.error).__name__}: {outcome.error}"
        if not isinstance(outcome.error, PlanFormatError):  # a plan refused before running is fine
            problems.append(f"run_task_episode did not return: {_short(texts['exception'])}")
    elif outcome.value is not None:
        result = outcome.value[0]
        texts["result"] = json.dumps(result.to_dict(), default=str)
        failed = result.failed_step
        record_property("episode", {"success": result.success, "failed_step": failed.error[:200] if failed else ""})
        if result.success and script.expect != "contained":
            problems.append("the episode reports success")
        if len(texts["result"]) > RESULT_LIMIT:
            problems.append(f"the result is {len(texts['result']) // 1_000_000} MB of JSON")
    problems += _secret_leaks(texts, secrets)
    if len(out) + len(err) > OUTPUT_LIMIT:
        problems.append(f"{(len(out) + len(err)) // 1_000_000} MB of output reached the test process")
    # The next episode must not inherit anything (patched judge, dead fork server, ...). Every episode has a
    # fresh worker, so this is checked after the scripts that tamper with the process, and a sample of the rest.
    if not outcome.hung and (script.effect in ("cheat", "other", "signal") or SCRIPTS.index(script) % 8 == 0):
        problems += _control_run(tmp_path)
    assert not problems, _hide(f"{script.name} ({script.attempts}):\n- " + "\n- ".join(problems), secrets)


@pytest.mark.parametrize("name", GENERATION_CASES)
def test_generated_hostile_answer(name, tmp_path, box, listener, secrets, signals, capfd):
    """The script as an LLM's answer to `hgen generate script` (then a benign answer): no effect, no secret in
    any file written (log, cache, recording), and no success (a poisoned judge would pass the benign one)."""
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app
    from humanoidgen.episodes.plans import parse_plan
    from humanoidgen.llm.fake_server import ScriptedServer

    script = next(s for s in SCRIPTS if s.name.split("_", 1)[1] == name)
    text = _render(script, box, listener.port).decode("utf-8", "surrogateescape")
    answer = "Here is the plan.\n" + "".join(f"```python\n# step: {s.title}\n{s.code}\n```\n"
                                              for s in parse_plan(text).steps)
    benign = f"```python\n{CONTROL_PLAN}```\n"
    out_dir = tmp_path / "gen"
    log, rec, cache, plan_out = out_dir / "log.json", out_dir / "rec.jsonl", out_dir / "cache", out_dir / "plan.py"
    out_dir.mkdir()
    before = _process_state()
    with ScriptedServer([answer, benign], default=benign) as srv:
        args = ["generate", "script", "block_stack_single", "--out", str(plan_out), "--attempts", "2",
                "--log", str(log), "--cache-dir", str(cache), "--record", str(rec), "--base-url", srv.base_url,
                "--step-timeout", "10", "--retries", "0"]
        outcome = _bounded(lambda: CliRunner().invoke(app, args), TIMEOUT_S)
    problems = _leftovers(box, listener, signals, before, outcome, check_threads=False)
    out, err = capfd.readouterr()
    texts = {"stdout": out, "stderr": err}
    if outcome.error is not None:
        problems.append(f"the CLI raised {type(outcome.error).__name__}: {_short(str(outcome.error))}")
    elif outcome.value is not None:
        res = outcome.value
        texts["cli output"] = res.output
        if res.exception is not None and not isinstance(res.exception, SystemExit):
            problems.append(f"the CLI crashed: {type(res.exception).__name__}: {_short(str(res.exception))}")
        if res.exit_code == 0 or plan_out.exists():
            problems.append("generation reports a successful plan")
        if not log.exists():
            problems.append("no attempt log was written")
    for path in sorted(p for p in out_dir.rglob("*") if p.is_file()):
        texts[str(path.relative_to(tmp_path))] = path.read_bytes().decode("utf-8", "replace")
    problems += _secret_leaks(texts, secrets)
    assert not problems, _hide(f"{script.name} as an LLM answer:\n- " + "\n- ".join(problems), secrets)


# -- helpers ----------------------------------------------------------------------------------------------
@dataclasses.dataclass
class Outcome:
    value: object = None
    error: BaseException | None = None
    hung: bool = False


def _bounded(fn, timeout_s: float) -> Outcome:
    """fn() in a daemon thread; whatever it raises (SystemExit and KeyboardInterrupt too) comes back as data."""
    out = Outcome()

    def run() -> None:
        try:
            out.value = fn()
        except BaseException as e:  # noqa: BLE001 - a plan's KeyboardInterrupt must not end the session
            out.error = e

    t = threading.Thread(target=run, name="hostile-episode", daemon=True)
    t.start()
    t.join(timeout_s)
    out.hung = t.is_alive()
    return out


def _episode(plan: Path):
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    fields = {f.name for f in dataclasses.fields(EpisodeRequest)}
    extra = {"step_timeout_s": STEP_TIMEOUT_S} if "step_timeout_s" in fields else {}
    return run_task_episode(EpisodeRequest("block_stack_single", 0, plan_path=str(plan), **extra))


def _control_run(tmp_path: Path) -> list[str]:
    plan = tmp_path / "control.py"
    plan.write_text(CONTROL_PLAN)
    out = _bounded(lambda: _episode(plan), TIMEOUT_S)
    if out.hung or out.error is not None:
        return [f"a benign plan run next did not come back ({'hung' if out.hung else type(out.error).__name__})"]
    result = out.value[0]
    if result.success or not result.checks or all(c["ok"] for c in result.checks):
        return ["a benign plan run next was judged a success: the plan left the judge tampered with"]
    return []


def _render(script, box: Box, port: int) -> bytes:
    return battery.render(script.text, marker_dir=str(box.markers), port=port, harness_pid=os.getpid(),
                          harness_ppid=os.getppid(), shm_path=box.shm)


def _process_state() -> dict:
    return {"descendants": _descendants(os.getpid()), "threads": set(threading.enumerate()), "cwd": os.getcwd(),
            "fds": {fd: _fd_identity(fd) for fd in (1, 2)}, "maxrss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss}


def _leftovers(box: Box, listener, signals: list[int], before: dict, outcome: Outcome,
               check_threads: bool = True) -> list[str]:
    """Everything a plan may have left behind, as a list of problems."""
    problems = []
    if outcome.hung:
        problems.append(f"did not finish within {TIMEOUT_S:g} s (safety net; the worker should have stopped it)")
    lingering = _settle(before["descendants"])
    if lingering:
        problems.append(f"processes left running: {lingering}")
        for pid in lingering:
            _kill(pid)
    if naming := battery.processes_mentioning(str(box.markers)):
        problems.append(f"processes naming the marker dir are running: {naming}")
    if made := sorted(p.name for p in box.markers.iterdir()) if box.markers.is_dir() else ["<marker dir gone>"]:
        problems.append(f"files created in the marker dir: {made[:10]}")
    if extra := sorted(p.name for p in box.root.iterdir() if p.name not in ("markers", "canary.txt")):
        problems.append(f"files created next to the canary: {extra[:10]}")
    if not box.canary.exists():
        problems.append("the canary file is gone")
    elif box.canary.read_text(errors="replace") != box.canary_text or _identity(box.canary) != box.canary_id:
        problems.append("the canary file was changed (content, mode, times or links)")
    if os.path.lexists(box.shm):
        problems.append(f"{box.shm} was created")
    if listener.count:
        problems.append(f"{listener.count} connection(s) reached the loopback listener")
    if signals:
        problems.append(f"signals reached the test process: {sorted(set(signals))}")
    for fd, ident in before["fds"].items():
        if _fd_identity(fd) != ident:
            problems.append(f"fd {fd} of the test process was replaced or closed")
    if os.getcwd() != before["cwd"]:
        problems.append("the test process's working directory changed")
        os.chdir(before["cwd"])
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before["maxrss"]
    if grown > MEMORY_GROWTH_LIMIT_KIB:
        problems.append(f"the test process grew by {grown >> 20} GiB")
    if check_threads:
        # (the fork server's output relay lives as long as the server, which the first episode starts)
        threads = [t.name for t in threading.enumerate() if t not in before["threads"] and t.is_alive()
                   and t.name not in ("hostile-episode", "hostile-listener", "hgen-relay")]
        if threads:
            problems.append(f"threads left running in the test process: {threads[:10]}")
    return problems


def _settle(before: set[int], grace_s: float = 5.0) -> list[int]:
    """New descendants still alive after a grace period, except the multiprocessing fork server/resource
    tracker (long-lived helpers started once, direct children of this process)."""
    deadline = time.monotonic() + grace_s
    while True:
        new = [p for p in _descendants(os.getpid()) - before if not _helper(p)]
        if not new or time.monotonic() > deadline:
            return sorted(new)
        time.sleep(0.2)


def _helper(pid: int) -> bool:
    try:
        cmd = Path(f"/proc/{pid}/cmdline").read_bytes()
        ppid = int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])
    except (OSError, ValueError, IndexError):
        return True  # gone
    return ppid == os.getpid() and (b"multiprocessing.forkserver" in cmd or b"resource_tracker" in cmd)


def _descendants(root: int) -> set[int]:
    children: dict[int, list[int]] = {}
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                rest = (d / "stat").read_text().rsplit(")", 1)[1].split()
            except (OSError, IndexError):
                continue
            if rest[0] not in ("Z", "X"):  # zombies are dead already
                children.setdefault(int(rest[1]), []).append(int(d.name))
    out, todo = set(), [root]
    while todo:
        for c in children.get(todo.pop(), []):
            if c not in out:
                out.add(c)
                todo.append(c)
    return out


def _kill(pid: int) -> None:
    try:
        os.kill(pid, signal.SIGKILL)
    except OSError:
        pass


def _identity(path: Path) -> tuple:
    st = os.stat(path)
    return st.st_mode, st.st_nlink, st.st_size, st.st_mtime_ns


def _fd_identity(fd: int):
    try:
        st = os.fstat(fd)
        os.write(fd, b"")
    except OSError:
        return None
    return st.st_dev, st.st_ino


def _startup_env(names) -> list[str]:
    try:
        entries = Path("/proc/self/environ").read_bytes().split(b"\0")
    except OSError:
        return []
    want = tuple(n.encode() + b"=" for n in names)
    return [e.split(b"=", 1)[1].decode("utf-8", "replace") for e in entries if e.startswith(want)]


def _secret_leaks(texts: dict[str, str], secrets: list[str]) -> list[str]:
    where = sorted({name for name, text in texts.items() for s in secrets for form in battery.secret_forms(s)
                    if form in text})
    return [f"a canary secret (plain, reversed or hex) appears in: {', '.join(where)}"] if where else []


def _hide(text: str, secrets: list[str]) -> str:
    for s in secrets:
        for form in battery.secret_forms(s):
            text = text.replace(form, "<SECRET>")
    return text


def _short(text: str, n: int = 300) -> str:
    return text if len(text) <= n else text[:n] + f"... ({len(text)} characters)"


# -- the same payloads with the checker out of the way: the kernel alone must hold -------------------------
KERNEL_EFFECTS = ("file", "exec", "fork", "socket", "env", "signal")


def unchecked_setup() -> dict:
    """A worker whose plan code gets full builtins and no static check at all, as if every refusal of the
    checker had a hole: what is left is seccomp, Landlock, the scrubbed environment and the rlimits."""
    import builtins
    import math

    import numpy as np

    def run(code: str) -> str:
        ns = {"np": np, "math": math, "planner": None, "__builtins__": builtins}
        try:
            exec(compile(code, "<unchecked>", "exec"), ns)  # noqa: S102 - deliberately unchecked
            if callable(ns.get("step")):
                ns["step"](None)
        except BaseException as e:  # noqa: BLE001
            return f"{type(e).__name__}: {str(e)[:300]}"
        return "finished"

    return {"run": run}


@pytest.fixture(scope="module")
def unchecked_worker():
    from humanoidgen.sandbox import SandboxWorker

    with SandboxWorker(unchecked_setup, memory_limit=2 << 30) as w:
        yield w


@pytest.mark.parametrize("script", [s for s in SCRIPTS if s.effect in KERNEL_EFFECTS], ids=lambda s: s.name)
def test_kernel_alone_stops_the_payload(script, unchecked_worker, box, listener, secrets, signals, capfd):
    from humanoidgen.episodes.plans import PlanFormatError, parse_plan

    text = _render(script, box, listener.port).decode("utf-8", "surrogateescape")
    try:
        code = "\n".join(s.code for s in parse_plan(text).steps)
    except PlanFormatError:
        pytest.skip("not a plan the parser reads (covered by the checked battery)")
    unchecked_worker.start()  # (re)started before the snapshot: the worker itself is no leftover
    before = _process_state()
    outcome = _bounded(lambda: unchecked_worker._request(("call", ("run", (code,), {})), 15.0), TIMEOUT_S)
    problems = _leftovers(box, listener, signals, before, outcome, check_threads=False)
    out, err = capfd.readouterr()
    reply = outcome.value
    texts = {"stdout": out, "stderr": err, "reply": repr(reply.value if reply is not None else outcome.error)}
    problems += _secret_leaks(texts, secrets)
    assert not problems, _hide(f"{script.name} with no checker ({script.attempts}):\n- " + "\n- ".join(problems),
                               secrets)
