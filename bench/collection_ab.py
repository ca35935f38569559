"""Collection time, one revision against another, taking turns in one run (this 2-core machine's timings move
with the load of other jobs; alternating rows see the same load). Each row is `hgen collect TASK -n EPISODES`
from a checkout of the revision (a temporary git worktree), camera-less (`--cameras none --no-point-cloud`)
or with the default recording (`--recording default`: six 320x240 RGB-D cameras and the point cloud at
10 Hz), timed from start to exit: what a user waits for, fork server start and imports included. One warm-up
collect per revision first (numba kernels compiled to their caches, files in the OS cache).

    python bench/collection_ab.py --before fd0c4fb^ --after HEAD --task handover_and_storage --rounds 3
    python bench/collection_ab.py --before 1ebaf6a --after HEAD --task block_stack_single --recording default
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _checkout(rev: str, where: Path) -> tuple[Path, str]:
    sha = subprocess.run(["git", "rev-parse", rev], cwd=ROOT, check=True, capture_output=True, text=True).stdout.strip()
    subprocess.run(["git", "worktree", "add", "-f", "--detach", str(where), sha], cwd=ROOT, check=True,
                   capture_output=True)
    return where, sha


def _collect(code: Path, task: str, n: int, out: Path, recording: str = "none") -> dict:
    shutil.rmtree(out, ignore_errors=True)
    env = dict(os.environ, PYTHONPATH=str(code), OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    load = os.getloadavg()[0]
    t0 = time.perf_counter()
    cameras = ["--cameras", "none", "--no-point-cloud"] if recording == "none" else []
    r = subprocess.run([sys.executable, "-m", "humanoidgen.cli.main", "collect", task, "-n", str(n), "--out", str(out),
                        *cameras], cwd=code, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise SystemExit(f"collect failed in {code}: {r.stderr.strip().splitlines()[-1:]}")
    rows = [json.loads(line) for line in (out / "index.jsonl").read_text().splitlines()]
    kept = sum(x["success"] for x in rows)
    return {"seconds_per_kept": round(wall / max(kept, 1), 2), "wall": round(wall, 2), "kept": kept,
            "tried": len(rows), "episode_wall_seconds": [x["wall_seconds"] for x in rows],
            "load_average": [round(load, 2), round(os.getloadavg()[0], 2)]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", required=True)
    ap.add_argument("--after", default="HEAD")
    ap.add_argument("--task", default="handover_and_storage")
    ap.add_argument("--episodes", type=int, default=3)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--recording", choices=("none", "default"), default="none")
    ap.add_argument("--json", type=Path, default=ROOT / "bench/results/collection_handover_no_cameras.json")
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="hgen_ab_"))
    try:
        codes = {name: _checkout(rev, tmp / name) for name, rev in (("before", args.before), ("after", args.after))}
        for name, (code, _) in codes.items():  # warm-up
            _collect(code, args.task, 1, tmp / f"warm_{name}", args.recording)
        runs = []
        for k in range(args.rounds):
            for name, (code, _) in codes.items():
                row = {"code": name, **_collect(code, args.task, args.episodes, tmp / f"{name}_{k}", args.recording)}
                runs.append(row)
                print(f"{name}: {row['seconds_per_kept']} s per kept episode ({row['kept']}/{row['tried']}), "
                      f"load {row['load_average']}", flush=True)
        mean = {n: round(sum(r["seconds_per_kept"] for r in runs if r["code"] == n) / args.rounds, 2) for n in codes}
        what = "without cameras" if args.recording == "none" else "with the default recording"
        result = {"what": f"{args.task} {what} through hgen collect ({args.episodes} episodes per run, seeds "
                          f"from 0), the two revisions taking turns after one warm-up collect each; seconds per kept "
                          f"episode from start to exit",
                  "machine": f"{os.uname().machine}, {os.cpu_count()} CPUs",
                  "revisions": {n: sha for n, (_, sha) in codes.items()}, "runs": runs,
                  "mean_seconds_per_kept": mean, "speedup": round(mean["before"] / mean["after"], 2)}
        args.json.write_text(json.dumps(result, indent=2) + "\n")
        print(f"speedup {result['speedup']}x ({mean['before']} -> {mean['after']} s per kept episode); wrote {args.json}")
    finally:
        for name in ("before", "after"):
            subprocess.run(["git", "worktree", "remove", "--force", str(tmp / name)], cwd=ROOT, capture_output=True)
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
