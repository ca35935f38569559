"""Planning time per reference episode, two checkouts of the planner taking turns on one machine.

Each round runs the same reference episodes (task, seed) through the real entry point (`run_task_episode`, camera-
less) once with each checkout's code (`PYTHONPATH`), in alternating order, one episode at a time, and keeps each
episode's motion-planning time (`plan_seconds`: goal solves and motion plans) and wall time. Reports the mean per
checkout and the ratio after / before.

    python bench/planning_ab.py --before /tmp/wt-base --after . --tasks close_drawer,open_laptop_hard --seeds 100-101
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from foreign_plans import parse_seeds  # noqa: E402
from provenance import commit, machine  # noqa: E402

RUN = r"""
import json, sys
from humanoidgen.episodes.recorder import RecorderConfig
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode
out = []
for job in json.loads(sys.argv[1]):
    result, _ = run_task_episode(EpisodeRequest(job[0], job[1], recorder=RecorderConfig()), render=False)
    out.append({"task": job[0], "seed": job[1], "success": result.success, "plan_s": result.plan_seconds,
                "wall_s": result.wall_seconds})
print("RESULT " + json.dumps(out))
"""


def run(code: Path, jobs: list[tuple[str, int]]) -> list[dict]:
    env = dict(os.environ, PYTHONPATH=str(code), OMP_NUM_THREADS="1")
    proc = subprocess.run([sys.executable, "-c", RUN, json.dumps(jobs)], capture_output=True, text=True, env=env,
                          cwd=code, check=False)
    line = next((x for x in proc.stdout.splitlines() if x.startswith("RESULT ")), None)
    if line is None:
        raise SystemExit(f"{code}: {proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else 'no result'}")
    return json.loads(line[len("RESULT "):])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--before", type=Path, required=True, help="checkout of the planner before the change")
    ap.add_argument("--after", type=Path, default=HERE.parent, help="checkout after (default: this one)")
    ap.add_argument("--tasks", required=True, help="comma-separated task names (their reference plans)")
    ap.add_argument("--seeds", default="100-101")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--json", type=Path)
    args = ap.parse_args(argv)
    jobs = [(t, s) for t in args.tasks.split(",") for s in parse_seeds(args.seeds)]
    rows = []
    for r in range(args.rounds):
        order = [("before", args.before), ("after", args.after)]
        for name, code in order if r % 2 == 0 else order[::-1]:
            t0 = time.monotonic()
            for ep in run(code.resolve(), jobs):
                rows.append({"round": r, "code": name, **ep})
            print(f"round {r} {name}: {time.monotonic() - t0:.1f} s", flush=True)
    summary = {}
    for name in ("before", "after"):
        mine = [x for x in rows if x["code"] == name]
        summary[name] = {"episodes": len(mine), "successes": sum(x["success"] for x in mine),
                         "mean_plan_s": round(statistics.mean(x["plan_s"] for x in mine), 3),
                         "mean_wall_s": round(statistics.mean(x["wall_s"] for x in mine), 3)}
    summary["plan_ratio"] = round(summary["after"]["mean_plan_s"] / summary["before"]["mean_plan_s"], 3)
    summary["wall_ratio"] = round(summary["after"]["mean_wall_s"] / summary["before"]["mean_wall_s"], 3)
    print(json.dumps(summary, indent=1))
    if args.json:
        args.json.write_text(json.dumps({
            "what": "reference episodes' motion-planning and wall time, two checkouts taking turns",
            "before": commit(args.before), "after": commit(args.after),
            "machine": machine(), "tasks": args.tasks, "seeds": args.seeds,
            "summary": summary, "episodes": rows}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
