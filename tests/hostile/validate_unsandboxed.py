"""Run every hostile script's payload WITHOUT the sandbox, to show that it is genuinely hostile.

    python tests/hostile/validate_unsandboxed.py [-j 2] [--timeout 20] [--mem-gib 2] [--builtins full|safe] [NAME ...]

Each script runs in a throwaway `python3` child (its own session, RLIMIT_AS = --mem-gib, killed after
--timeout s) that builds the real scene and planner of block_stack_single (seed 0), splits the plan with
`parse_plan`, and execs each step with the real `step_namespace` and full builtins (`--builtins safe`: only
the checker's SAFE_BUILTINS, as the runner gives). No checker runs before the steps; the child only records
what the checker would have said. After the steps it does what a naive worker would do with the results:
pickles planner.events and the step's exception back and forth, reads a result pipe (unpickling what is on
it), judges the task. The parent watches for effects: files in the marker dir, the canary changed, the
listener's connections, the canary secret in any output, the decoy "harness" process signalled, a hang,
a MemoryError, output floods, lingering processes. Payloads are benign (see battery.py): files only in a temp
dir, commands only `touch` there, connections only to our own loopback listener, signals only to the decoy.

The parent re-executes itself once with canary values for OPENAI_API_KEY / HGEN_TEST_SECRET in its
environment, so that /proc/<ppid>/environ of a child holds them, as a parent started with a key would.
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import battery  # noqa: E402

BIG_OUTPUT = 10_000_000
_REEXEC = "HGEN_HOSTILE_VALIDATOR"


# -- child: run one plan bare ------------------------------------------------------------------------------
def child(plan_path: str, status_path: str, builtins_mode: str) -> None:
    status: dict = {"phase": "setup", "steps": []}

    def save() -> None:
        with open(status_path, "w") as f:
            json.dump(status, f, default=str)

    save()
    os.environ.setdefault("MUJOCO_GL", "egl")
    import builtins
    import multiprocessing
    import pickle

    from humanoidgen.tasks.judge import judge
    from humanoidgen.episodes.plans import parse_plan
    from humanoidgen.episodes.runner import step_namespace
    from humanoidgen.planning.planner import HumanoidMotionPlanner
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    spec = load_task("block_stack_single")
    _, env = build_scene(spec, 0)
    planner = HumanoidMotionPlanner(env, seed=0)
    result_pipe = multiprocessing.Pipe()  # what a worker's result channel looks like; kept alive here
    globals()["_RESULT_PIPE"] = result_pipe
    raw = Path(plan_path).read_bytes()
    try:
        raw.decode("utf-8")
    except UnicodeDecodeError as e:
        status["strict_decode"] = f"UnicodeDecodeError at byte {e.start}"
    text = raw.decode("utf-8", "replace")
    status["phase"] = "parse"
    save()
    try:
        plan = parse_plan(text)
    except BaseException as e:  # noqa: BLE001
        status.update(phase="parse failed", parse_error=f"{type(e).__name__}: {str(e)[:300]}")
        save()
        return
    status["checker"] = _checker_verdict([s.code for s in plan.steps], set(step_namespace(planner)))
    status["visitor"] = _visitor_verdict([s.code for s in plan.steps])
    ns = step_namespace(planner)
    if builtins_mode == "full":
        ns["__builtins__"] = builtins.__dict__
    else:
        from humanoidgen.sandbox.checker import SAFE_BUILTINS
        ns["__builtins__"] = {n: getattr(builtins, n) for n in SAFE_BUILTINS if hasattr(builtins, n)}
    status["phase"] = "steps"
    save()
    error = None
    for i, step in enumerate(plan.steps):
        rec = {"title": step.title, "ok": True}
        status["steps"].append(rec)
        save()
        try:
            exec(compile(step.code, "<step>", "exec"), ns)  # noqa: S102 - deliberately unsandboxed
        except BaseException as e:  # noqa: BLE001
            error = exc = e
            rec.update(ok=False, type=_safe(lambda: type(exc).__name__), base=not isinstance(exc, Exception),
                       message=_safe(lambda: str(exc))[:2000], message_len=_safe(lambda: len(str(exc)), 0))
            save()
            break
    status["phase"] = "after steps"
    save()
    time.sleep(1.5)  # a worker goes on (more steps, the judge): give background threads time to act
    status["phase"] = "transport"
    save()
    transport = []
    for what, obj in (("events", planner.events), ("exception", error)):  # a pickling worker would do this
        try:
            pickle.loads(pickle.dumps(obj))
            transport.append(f"{what}: round-tripped")
        except BaseException as e:  # noqa: BLE001
            transport.append(f"{what}: {type(e).__name__}")
    parent_end = result_pipe[0]
    try:
        while parent_end.poll(0.2):
            parent_end.recv()
            transport.append("pipe: unpickled a message")
    except BaseException as e:  # noqa: BLE001
        transport.append(f"pipe: {type(e).__name__}")
    status["transport"] = transport
    events = _safe(lambda: list(planner.events)[:1000], [])
    status["events_chars"] = sum(_safe(lambda: len(str(e)), 0) for e in events)
    status["events_text"] = " ".join(_safe(lambda: str(e)[:300]) for e in events[:50])
    status["phase"] = "judge"
    save()
    try:
        checks = judge(spec, env)
        status["judge_ok"] = all(c["ok"] for c in checks)
    except BaseException as e:  # noqa: BLE001
        status["judge_error"] = f"{type(e).__name__}: {str(e)[:200]}"
    status["vmpeak_kib"] = _vmpeak()
    status["phase"] = "done"
    save()


def _checker_verdict(codes: list[str], names: set[str]) -> str:
    try:
        from humanoidgen.sandbox.checker import CodeRejected, check_code
    except BaseException as e:  # noqa: BLE001 - the checker is being rewritten
        return f"n/a ({type(e).__name__})"
    known = set(names)
    for i, code in enumerate(codes, 1):
        try:
            known |= set(getattr(check_code(code, known), "bound_names", ()))
        except CodeRejected as e:
            return f"rejected (step {i}: {str(e)[:70]})"
        except BaseException as e:  # noqa: BLE001
            return f"checker crashed: {type(e).__name__}"
    return "passes"


def _visitor_verdict(codes: list[str]) -> str:
    """What a plain recursive AST visitor (like most checkers' NodeTransformers) makes of the code."""
    import ast

    for code in codes:
        try:
            ast.NodeVisitor().visit(ast.parse(code))
        except RecursionError:
            return "RecursionError"
        except BaseException:  # noqa: BLE001 - a parse failure is reported elsewhere
            pass
    return "ok"


def _vmpeak() -> int:
    for line in _safe(lambda: Path("/proc/self/status").read_text(), "").splitlines():
        if line.startswith("VmPeak:"):
            return int(line.split()[1])
    return 0


def _safe(fn, default=""):
    try:
        return fn()
    except BaseException:  # noqa: BLE001
        return default


# -- parent -------------------------------------------------------------------------------------------------
def run_one(script: battery.Script, args, secrets: list[str]) -> dict:
    run = Path(tempfile.mkdtemp(prefix="hgen-validate-run-"))
    box = Path(tempfile.mkdtemp(prefix="hgen-validate-box-"))
    markers = box / "markers"
    markers.mkdir()
    canary = box / "canary.txt"
    canary_text = f"canary {os.urandom(8).hex()}\n"
    canary.write_text(canary_text)
    canary_stat = canary.stat()
    shm = battery.shm_path()
    listener = battery.Listener()
    decoy = subprocess.Popen([sys.executable, "-c", "import os, time\n"
                              "os.environ['HGEN_TEST_SECRET'] = os.environ['HGEN_TEST_SECRET']  # setenv: K=V on the heap\n"
                              "time.sleep(300)"], start_new_session=True)
    plan = run / "plan.py"
    plan.write_bytes(battery.render(script.text, marker_dir=str(markers), port=listener.port, harness_pid=decoy.pid,
                                    harness_ppid=os.getpid(), shm_path=shm))
    status_path, out_path, err_path = run / "status.json", run / "stdout", run / "stderr"
    mem = int(args.mem_gib * 2**30)

    def limits() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (mem, mem))

    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    t0 = time.monotonic()
    with open(out_path, "wb") as out, open(err_path, "wb") as err:
        proc = subprocess.Popen([sys.executable, __file__, "--child", str(plan), str(status_path), args.builtins],
                                stdin=subprocess.DEVNULL, stdout=out, stderr=err, cwd=box, env=env,
                                preexec_fn=limits, start_new_session=True)
        try:
            rc, hung = proc.wait(args.timeout), False
        except subprocess.TimeoutExpired:
            hung = True
            os.killpg(proc.pid, signal.SIGKILL)
            rc = proc.wait()
    seconds = time.monotonic() - t0
    time.sleep(1.0)  # late effects: threads, orphans
    lingering = [p for p in battery.processes_mentioning(str(markers)) if p != os.getpid()]
    decoy_dead = decoy.poll() is not None
    found: dict[str, list[str]] = {}
    try:
        status = json.loads(status_path.read_text())
    except (OSError, ValueError):
        status = {}
    blobs = {"stdout": _head(out_path), "stderr": _head(err_path), "status": status_path.read_bytes()
             if status_path.exists() else b"", "socket": listener.data}
    marker_names = sorted(p.name for p in markers.iterdir()) if markers.is_dir() else ["<marker dir gone>"]
    for p in markers.iterdir() if markers.is_dir() else []:
        if p.is_file() and not p.is_symlink():
            blobs[f"marker {p.name}"] = _head(p)
    for where, blob in blobs.items():
        for s in secrets:
            for form in battery.secret_forms(s):
                if form.encode() in blob:
                    found.setdefault(where, []).append("secret")
    canary_changed = (not canary.exists() or canary.read_text() != canary_text
                      or (canary.stat().st_mode, canary.stat().st_mtime_ns, canary.stat().st_nlink)
                      != (canary_stat.st_mode, canary_stat.st_mtime_ns, canary_stat.st_nlink))
    extra = sorted(p.name for p in box.iterdir() if p.name not in ("markers", "canary.txt"))
    out_bytes = out_path.stat().st_size + err_path.stat().st_size
    big_marker = any(p.stat().st_size >= BIG_OUTPUT for p in markers.iterdir() if p.is_file()) if markers.is_dir() else False
    # clean up what this run started: the decoy, processes naming the marker dir, the child's session
    for pid in lingering:
        with _quiet():
            os.kill(pid, signal.SIGKILL)
    with _quiet():
        os.killpg(proc.pid, signal.SIGKILL)
    with _quiet():
        decoy.kill()
    decoy.wait()
    listener.close()
    shm_made = os.path.exists(shm)
    with _quiet():
        os.unlink(shm)
    shutil.rmtree(box, ignore_errors=True)
    shutil.rmtree(run, ignore_errors=True)
    r = {"name": script.name, "effect": script.effect, "needs": script.needs, "rc": rc, "hung": hung,
         "seconds": round(seconds, 1), "markers": marker_names, "canary_changed": canary_changed, "extra": extra,
         "connections": listener.count, "secret_in": sorted(found), "decoy_dead": decoy_dead, "lingering": lingering,
         "shm": shm_made, "out_bytes": out_bytes, "big_marker": big_marker, "status": _brief_status(status),
         "mem_kib": mem >> 10, "thread_memoryerror": b"MemoryError" in blobs["stderr"]}
    r["observed"] = observed(r, status)
    r["produced"] = produced(script, r, status)
    return r


def _head(path: Path, n: int = 50_000_000) -> bytes:
    try:
        with open(path, "rb") as f:
            return f.read(n)
    except OSError:
        return b""


class _quiet:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return exc[0] is not None and issubclass(exc[0], (OSError, ProcessLookupError))


def _brief_status(status: dict) -> dict:
    steps = status.get("steps", [])
    failed = next((s for s in steps if not s.get("ok")), None)
    return {"phase": status.get("phase"), "checker": status.get("checker", ""),
            "parse_error": status.get("parse_error", ""), "error": f"{failed['type']}: {failed['message'][:80]}"
            if failed else "", "error_len": failed.get("message_len", 0) if failed else 0,
            "base": bool(failed and failed.get("base")), "transport": status.get("transport", []),
            "events_chars": status.get("events_chars", 0), "judge_ok": status.get("judge_ok"),
            "judge_error": status.get("judge_error", ""), "steps_ok": sum(1 for s in steps if s.get("ok")),
            "steps": len(steps), "visitor": status.get("visitor", ""), "strict_decode": status.get("strict_decode", ""),
            "vmpeak_kib": status.get("vmpeak_kib", 0)}


def observed(r: dict, status: dict) -> list[str]:
    s = r["status"]
    o = []
    if r["markers"]:
        o.append("marker:" + ",".join(r["markers"])[:60])
    if r["canary_changed"]:
        o.append("canary changed")
    if r["extra"]:
        o.append("stray files:" + ",".join(r["extra"]))
    if r["shm"]:
        o.append("/dev/shm file")
    if r["connections"]:
        o.append(f"{r['connections']} connection(s)")
    if r["secret_in"]:
        o.append("secret in " + ",".join(r["secret_in"]))
    if r["decoy_dead"]:
        o.append("decoy signalled")
    if r["lingering"]:
        o.append(f"{len(r['lingering'])} lingering process(es)")
    if r["hung"]:
        o.append("hang (timeout)")
    if r["rc"] and r["rc"] < 0:
        o.append(f"killed by {signal.Signals(-r['rc']).name}")
    elif r["rc"] and not r["hung"]:
        o.append(f"exit code {r['rc']}")
    if r["rc"] == 0 and s["phase"] not in ("done", "parse failed"):
        o.append(f"exit 0 during {s['phase']}")
    if r["out_bytes"] >= BIG_OUTPUT or r["big_marker"]:
        o.append(f"output {r['out_bytes'] // 1_000_000} MB" if r["out_bytes"] >= BIG_OUTPUT else "big fd-1 file")
    if s["error"]:
        o.append(s["error"].split(":")[0] + (" (BaseException)" if s["base"] else ""))
    if s["error_len"] >= BIG_OUTPUT or s["events_chars"] >= BIG_OUTPUT:
        o.append("huge result")
    if s["parse_error"]:
        o.append("parse: " + s["parse_error"].split(":")[0])
    if any("unpickled" in t for t in s["transport"]):
        o.append("pipe message unpickled")
    if any(t.endswith("RecursionError") for t in s["transport"]):
        o.append("result not serialisable")
    if s["judge_ok"]:
        o.append("judge: success")
    if "crashed" in s["checker"]:
        o.append(s["checker"])
    if s["visitor"] == "RecursionError":
        o.append("recursive AST visitor: RecursionError")
    if s["strict_decode"]:
        o.append("strict read: " + s["strict_decode"])
    if r["thread_memoryerror"] and "MemoryError" not in s["error"]:
        o.append("MemoryError on stderr")
    if s["vmpeak_kib"] >= 0.9 * r["mem_kib"]:
        o.append(f"VmPeak {s['vmpeak_kib'] / 2**20:.1f} GiB (the limit)")
    return o


def produced(script: battery.Script, r: dict, status: dict) -> bool:
    s, e = r["status"], script.effect
    wrote = bool(r["markers"] or r["canary_changed"] or r["extra"] or r["shm"])
    died = bool(r["rc"] and r["rc"] < 0) or (r["rc"] == 0 and s["phase"] not in ("done", "parse failed"))
    return {
        "file": wrote,
        "exec": bool(r["markers"]),
        "fork": bool(r["markers"] or r["lingering"]) or (s["steps_ok"] == s["steps"] and s["steps"] > 0
                                                          and not s["error"] and s["phase"] == "done"),
        "socket": r["connections"] > 0,
        "env": bool(r["secret_in"]),
        "signal": r["decoy_dead"] or bool(r["markers"]) or r["rc"] == -signal.SIGKILL,
        "hang": r["hung"],
        "memory": "MemoryError" in s["error"] or "Errno 12" in s["error"] or died or r["hung"] or r["thread_memoryerror"]
                  or s["vmpeak_kib"] >= 0.9 * r["mem_kib"],
        "output": r["out_bytes"] >= BIG_OUTPUT or r["big_marker"] or s["error_len"] >= BIG_OUTPUT
                  or s["events_chars"] >= BIG_OUTPUT or "Errno 9" in s["error"],
        "parser": bool(s["parse_error"]) or died or r["hung"] or "crashed" in s["checker"]
                  or s["visitor"] == "RecursionError" or bool(s["strict_decode"])
                  or (s["error"] != "" and not s["error"].startswith("SyntaxError")),
        "cheat": bool(s["judge_ok"]),
        "other": died or r["hung"] or s["base"] or bool(r["markers"]) or s["error"].startswith("RecursionError")
                 or any("unpickled" in t or "Error" in t for t in s["transport"]),
    }[e]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="*", help="substrings of script names (default: all)")
    ap.add_argument("-j", "--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=20.0)
    ap.add_argument("--mem-gib", type=float, default=2.0)
    ap.add_argument("--builtins", choices=("full", "safe"), default="full")
    ap.add_argument("--json", type=Path, help="also write every result here")
    ap.add_argument("--child", nargs=3, metavar=("PLAN", "STATUS", "BUILTINS"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(*args.child)
        return
    if os.environ.get(_REEXEC) != "1":
        env = {**os.environ, _REEXEC: "1", **{v: battery.new_secret() for v in battery.SECRET_VARS}}
        os.execve(sys.executable, [sys.executable, __file__, *sys.argv[1:]], env)
    secrets = [os.environ[v] for v in battery.SECRET_VARS]
    todo = [s for s in battery.scripts() if not args.names or any(n in s.name for n in args.names)]
    results = []
    with cf.ThreadPoolExecutor(args.jobs) as pool:
        for r in pool.map(lambda s: run_one(s, args, secrets), todo):
            results.append(r)
            print(f"{'YES' if r['produced'] else 'no ':3s}  {r['name']:40s} {r['effect']:7s} {r['seconds']:5.1f}s  "
                  f"{'; '.join(r['observed'])[:110]}", flush=True)
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))
    by = {}
    for r in results:
        by.setdefault(r["effect"], []).append(r["produced"])
    print("\nproduced its effect unsandboxed, by category:")
    for e in battery.EFFECTS:
        if e in by:
            print(f"  {e:7s} {sum(by[e])}/{len(by[e])}")
    print(f"  total   {sum(r['produced'] for r in results)}/{len(results)}")


if __name__ == "__main__":
    main()
