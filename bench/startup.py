"""What `hgen run` costs beyond the episode itself: the wall time a user waits for, minus the episode's own
wall time (its plan, from the first step to the verdict), and where it goes.

Each round runs, in fresh processes:
- `hgen run TASK --seed S --json F`, timed from start to exit (`total_s`); `episode_s` is the worker's own
  wall time from the JSON; `beyond_episode_s` = total - episode;
- a probe that times the phases one after the other: the CLI's imports in the parent, the fork server
  coming up (its imports and warm-up: `sandbox.preload`; meanwhile the parent imports what runs an episode,
  loads the task and reads the plan, `parent_set_up_s`, as `hgen run` does), one worker's start (fork, the
  task's scene unless the server built it, the twin's fork, lockdown), the episode, and the verdict after the
  last step.

    python bench/startup.py --rounds 3                     # block_stack_single seed 3
    python bench/startup.py --task open_drawer --seed 0 --json /tmp/startup.json
    python bench/startup.py --rounds 3 --against /work/old   # taking turns with another checkout, round by
                                                            # round: its results go to --before-json

Python's compiled bytecode: each checkout's package is compiled (`compileall`, into its `__pycache__`) before
any timing, as an installed `hgen` has it (pip compiles what it installs; Python writes the rest on first
import). Where the environment sets PYTHONDONTWRITEBYTECODE (this machine's does), nothing would be written and
every run would compile the package's modules from source again, about 0.25 s of `hgen run`'s start;
`--no-bytecode` times that (it removes nothing: a checkout compiled before keeps its bytecode).

The probe starts the server as `hgen run` does: told which episode to build while it warms up
(`forkserver.prestart(warm=...)`), where the checkout's `prestart` takes that. Where `perf` can count,
`cpu_s` is the CPU time of `hgen run`'s whole process tree (server, worker and twin included; the episode's
own CPU too): on a machine other jobs share, it moves less than the wall times do.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
from provenance import commit  # noqa: E402

PROBE = r"""
import json, os, sys, time
t0 = time.perf_counter()
os.environ.setdefault("MUJOCO_GL", "egl")
import humanoidgen.cli.main  # noqa: F401  (what `hgen` imports before any command)
t_cli = time.perf_counter()
import inspect
from humanoidgen.sandbox.forkserver import prestart
if "warm" in inspect.signature(prestart).parameters:  # as `hgen run` starts it
    prestart(warm=("humanoidgen.episodes.episode_worker:prebuild",
                   {"task": sys.argv[1], "seed": int(sys.argv[2]), "dressing": None}))
else:
    prestart()
# What `hgen run` does while the server comes up: its own imports, the task, the plan's text.
from humanoidgen.sandbox import SandboxWorker
from humanoidgen.episodes.task_episode import EpisodeRequest, load_spec, plan_file, read_plan_text, run_task_episode, worker_for
req = EpisodeRequest(sys.argv[1], int(sys.argv[2]))
spec = load_spec(req.task)
text = read_plan_text(plan_file(req.task, spec, None))
t_parent = time.perf_counter()
with SandboxWorker(dict) as w:  # an empty worker: it can only fork once the server is up
    w.start()
t_server = time.perf_counter()
worker = worker_for(req, spec, text)
worker.start()
t_worker = time.perf_counter()
result, _ = run_task_episode(req, worker=worker)
t_end = time.perf_counter()
print(json.dumps({"cli_imports_s": t_cli - t0, "parent_set_up_s": t_parent - t_cli,
                  "fork_server_s": t_server - t_cli, "worker_start_s": t_worker - t_server,
                  "episode_s": result.wall_seconds, "after_episode_s": t_end - t_worker - result.wall_seconds,
                  "success": result.success}))
"""


def _env(code: Path) -> dict:
    return dict(os.environ, PYTHONPATH=str(code))


def run_cli(task: str, seed: int, code: Path = ROOT) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out, counted = Path(tmp) / "run.json", Path(tmp) / "perf.csv"
        cmd = [sys.executable, "-m", "humanoidgen.cli.main", "run", task, "--seed", str(seed), "--json", str(out)]
        perf = shutil.which("perf")
        if perf:  # task-clock of the whole tree: children are counted wherever they are reaped
            cmd = [perf, "stat", "-x", ",", "-e", "task-clock", "-o", str(counted), "--", *cmd]
        t0 = time.perf_counter()
        r = subprocess.run(cmd, cwd=code, env=_env(code), capture_output=True, text=True)
        total = time.perf_counter() - t0
        if not out.exists():
            raise SystemExit(f"hgen run failed: {(r.stderr or r.stdout).strip().splitlines()[-1:]}")
        d = json.loads(out.read_text())
        cpu = _task_clock(counted)
    return {"total_s": round(total, 3), "episode_s": round(d["wall_seconds"], 3),
            "beyond_episode_s": round(total - d["wall_seconds"], 3), "cpu_s": cpu, "success": d["success"]}


def compile_bytecode(code: Path) -> None:
    """Compile the checkout's package to bytecode, as an installed `hgen` has it (see the module docstring)."""
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(code / "humanoidgen")], check=True,
                   capture_output=True)


def _task_clock(path: Path) -> float | None:
    """CPU seconds from `perf stat -x,` output, None where perf could not count."""
    try:
        for line in path.read_text().splitlines():
            fields = line.split(",")
            if len(fields) > 2 and fields[2] == "task-clock" and fields[1] == "msec":
                return round(float(fields[0]) / 1000, 3)
    except (OSError, ValueError):
        pass
    return None


def run_probe(task: str, seed: int, code: Path = ROOT) -> dict:
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-c", PROBE, task, str(seed)], cwd=code, env=_env(code),
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"probe failed: {r.stderr.strip().splitlines()[-3:]}")
    d = json.loads(r.stdout.strip().splitlines()[-1])
    d["process_s"] = time.perf_counter() - t0
    return {k: round(v, 3) if isinstance(v, float) else v for k, v in d.items()}


def _rounds(task: str, seed: int, code: Path, k: int) -> dict:
    row = {"round": k, "load_average": round(os.getloadavg()[0], 2),
           "cli": run_cli(task, seed, code), "phases": run_probe(task, seed, code)}
    print(json.dumps({"code": str(code), **row}), flush=True)
    return row


def _median(xs: list) -> float | None:
    xs = [x for x in xs if x is not None]
    return round(statistics.median(xs), 3) if xs else None


def _machine() -> str:
    model = ""
    try:
        model = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                      if line.startswith("model name")), "")
    except OSError:
        pass
    return f"{os.uname().machine}, {os.cpu_count()} CPUs" + (f" ({model})" if model else "")


def _summary(task: str, seed: int, code: Path, rows: list[dict], turns: str | None, no_bytecode: bool) -> dict:
    head = commit(code)
    beyond = [r["cli"]["beyond_episode_s"] for r in rows]
    result = {"what": f"hgen run {task} --seed {seed}: wall time from start to exit minus the episode's "
                      "own wall time, and the phases of the same path timed one by one",
              "commit": head, "machine": _machine()}
    if turns:
        result["taking_turns_with"] = turns
    result["bytecode"] = "as the environment has it" if no_bytecode else "compiled first (compileall)"
    result.update({"rounds": rows, "median_beyond_episode_s": round(statistics.median(beyond), 3),
                   "median_cpu_s": _median([r["cli"]["cpu_s"] for r in rows]),
                   "median_phases": {key: round(statistics.median(r["phases"][key] for r in rows), 3)
                                     for key in rows[0]["phases"] if key != "success"}})
    return result


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--task", default="block_stack_single")
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--code", type=Path, default=ROOT, help="a checkout to time (default: this one)")
    ap.add_argument("--json", type=Path, default=ROOT / "bench/results/startup.json")
    ap.add_argument("--against", type=Path, default=None,
                    help="another checkout, timed in turns with --code (it goes first in each round)")
    ap.add_argument("--before-json", type=Path, default=ROOT / "bench/results/startup_before.json",
                    help="where --against's results go")
    ap.add_argument("--no-bytecode", action="store_true",
                    help="do not compile the checkouts' bytecode first (see above)")
    args = ap.parse_args()
    codes = [args.code] if args.against is None else [args.against, args.code]
    for code in codes:
        if not args.no_bytecode:
            compile_bytecode(code)
        run_cli(args.task, args.seed, code)  # warm the OS file cache and numba's kernels
    rows: dict[Path, list[dict]] = {code: [] for code in codes}
    for k in range(args.rounds):
        for code in codes:
            rows[code].append(_rounds(args.task, args.seed, code, k))
    outs = [(args.code, args.json)] + ([(args.against, args.before_json)] if args.against is not None else [])
    for code, path in outs:
        other = next((f"{commit(c)} (round by round, it first)" if c == args.against else f"{commit(c)}"
                      for c in codes if c != code), None)
        result = _summary(args.task, args.seed, code, rows[code], other, args.no_bytecode)
        path.write_text(json.dumps(result, indent=2) + "\n")
        print(f"{code} ({result['commit']}): beyond the episode median {result['median_beyond_episode_s']} s, "
              f"CPU {result['median_cpu_s']} s; phases {result['median_phases']}; wrote {path}")


if __name__ == "__main__":
    main()
