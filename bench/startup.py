"""What `hgen run` costs beyond the episode itself: the wall time a user waits for, minus the episode's own
wall time (its plan, from the first step to the verdict), and where it goes.

Each round runs, in fresh processes:
- `hgen run TASK --seed S --json F`, timed from start to exit (`total_s`); `episode_s` is the worker's own
  wall time from the JSON; `beyond_episode_s` = total - episode;
- a probe that times the phases one after the other: the CLI's imports in the parent, the fork server
  coming up (its imports and warm-up: `sandbox.preload`), one worker's start (fork, the task's scene, the
  twin's fork, lockdown), the episode, and the verdict after the last step.

    python bench/startup.py --rounds 3                     # block_stack_single seed 3
    python bench/startup.py --task open_drawer --seed 0 --json /tmp/startup.json
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PROBE = r"""
import json, os, sys, time
t0 = time.perf_counter()
os.environ.setdefault("MUJOCO_GL", "egl")
import humanoidgen.cli.main  # noqa: F401  (what `hgen` imports before any command)
t_cli = time.perf_counter()
from humanoidgen.sandbox import SandboxWorker
from humanoidgen.sandbox.forkserver import prestart
prestart()
with SandboxWorker(dict) as w:  # an empty worker: it can only fork once the server is up
    w.start()
t_server = time.perf_counter()
from humanoidgen.episodes.task_episode import EpisodeRequest, load_spec, plan_file, read_plan_text, run_task_episode, worker_for
req = EpisodeRequest(sys.argv[1], int(sys.argv[2]))
spec = load_spec(req.task)
worker = worker_for(req, spec, read_plan_text(plan_file(req.task, spec, None)))
worker.start()
t_worker = time.perf_counter()
result, _ = run_task_episode(req, worker=worker)
t_end = time.perf_counter()
print(json.dumps({"cli_imports_s": t_cli - t0, "fork_server_s": t_server - t_cli, "worker_start_s": t_worker - t_server,
                  "episode_s": result.wall_seconds, "after_episode_s": t_end - t_worker - result.wall_seconds,
                  "success": result.success}))
"""


def _env(code: Path) -> dict:
    return dict(os.environ, PYTHONPATH=str(code))


def run_cli(task: str, seed: int, code: Path = ROOT) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "run.json"
        t0 = time.perf_counter()
        r = subprocess.run([sys.executable, "-m", "humanoidgen.cli.main", "run", task, "--seed", str(seed),
                            "--json", str(out)], cwd=code, env=_env(code), capture_output=True, text=True)
        total = time.perf_counter() - t0
        if not out.exists():
            raise SystemExit(f"hgen run failed: {(r.stderr or r.stdout).strip().splitlines()[-1:]}")
        d = json.loads(out.read_text())
    return {"total_s": round(total, 3), "episode_s": round(d["wall_seconds"], 3),
            "beyond_episode_s": round(total - d["wall_seconds"], 3), "success": d["success"]}


def run_probe(task: str, seed: int, code: Path = ROOT) -> dict:
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, "-c", PROBE, task, str(seed)], cwd=code, env=_env(code),
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"probe failed: {r.stderr.strip().splitlines()[-3:]}")
    d = json.loads(r.stdout.strip().splitlines()[-1])
    d["process_s"] = time.perf_counter() - t0
    return {k: round(v, 3) if isinstance(v, float) else v for k, v in d.items()}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--task", default="block_stack_single")
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--code", type=Path, default=ROOT, help="a checkout to time (default: this one)")
    ap.add_argument("--json", type=Path, default=ROOT / "bench/results/startup.json")
    args = ap.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=args.code, capture_output=True,
                            text=True).stdout.strip()
    run_cli(args.task, args.seed, args.code)  # warm the OS file cache and numba's kernels
    rows = []
    for k in range(args.rounds):
        row = {"round": k, "load_average": round(os.getloadavg()[0], 2),
               "cli": run_cli(args.task, args.seed, args.code), "phases": run_probe(args.task, args.seed, args.code)}
        rows.append(row)
        print(json.dumps(row), flush=True)
    beyond = [r["cli"]["beyond_episode_s"] for r in rows]
    result = {"what": f"hgen run {args.task} --seed {args.seed}: wall time from start to exit minus the episode's "
                      "own wall time, and the phases of the same path timed one by one",
              "commit": commit, "machine": f"{os.uname().machine}, {os.cpu_count()} CPUs", "rounds": rows,
              "median_beyond_episode_s": round(statistics.median(beyond), 3),
              "median_phases": {key: round(statistics.median(r["phases"][key] for r in rows), 3)
                                for key in rows[0]["phases"] if key != "success"}}
    args.json.write_text(json.dumps(result, indent=2) + "\n")
    print(f"beyond the episode: median {result['median_beyond_episode_s']} s; phases {result['median_phases']}; "
          f"wrote {args.json}")


if __name__ == "__main__":
    main()
