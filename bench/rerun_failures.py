"""Rerun only the episodes a corpus bench lost for one reason, and say how many of them pass now.

Reads one or more reports of `bench/foreign_plans.py` (our corpus, or the paper authors' plans laid out by
`bench/upstream_corpus.py`), takes the failures whose message contains `--match`, and runs each (plan, seed)
again through the real entry point (`run_task_episode`, the locked-down worker, the replay's verdict), one at a
time by default. Each episode's simulated time is kept beside its task's time limit, so a change of the time
rule can be read off directly.

    python bench/rerun_failures.py bench/results/foreign_plans_s0-9.json --json-out /tmp/rerun.json
    python bench/rerun_failures.py bench/results/upstream_plans_s0-2.json --remap /tmp/upcorpus=/tmp/mycorpus

Plans a report names by an absolute path (the authors' plans stay outside the repository) are looked up there,
or where `--remap OLD=NEW` moves them.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from foreign_plans import failure_message  # noqa: E402
from provenance import commit, machine  # noqa: E402


def lost(report: Path, match: str, remap: dict[str, str]) -> list[dict]:
    """(task, plan, path, seed, message) of every failure in `report` whose message contains `match`."""
    out = []
    for plan in json.loads(report.read_text())["plans"]:
        path = plan["path"]
        for old, new in remap.items():
            if path.startswith(old):
                path = new + path[len(old):]
        path = Path(path) if Path(path).is_absolute() else HERE.parent / path
        for f in plan["failures"]:
            if match in f["message"]:
                out.append({"report": report.name, "task": plan["task"], "plan": plan["plan"], "path": str(path),
                            "seed": f["seed"], "before": f["message"]})
    return out


def run(ep: dict, step_timeout_s: float | None) -> dict:
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode
    from humanoidgen.tasks.registry import load_task

    t0 = time.monotonic()
    out = dict(ep, time_limit_s=load_task(ep["task"]).time_limit_s)
    try:
        req = EpisodeRequest(ep["task"], ep["seed"], plan_path=ep["path"])
        if step_timeout_s is not None:
            req.step_timeout_s = step_timeout_s
        result, _ = run_task_episode(req)
        out.update(success=bool(result.success), sim_s=round(result.sim_seconds, 2),
                   message="" if result.success else failure_message(result))
    except Exception as exc:  # noqa: BLE001 - a harness error is a failure with its message
        out.update(success=False, sim_s=None, message=f"harness error: {type(exc).__name__}: {exc}")
    out["wall_s"] = round(time.monotonic() - t0, 1)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("reports", type=Path, nargs="+", help="reports of bench/foreign_plans.py")
    ap.add_argument("--match", default="time limit", help="rerun failures whose message contains this")
    ap.add_argument("--remap", action="append", default=[], metavar="OLD=NEW", help="move plan paths")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--step-timeout", type=float, default=None)
    ap.add_argument("--json-out", type=Path, required=True)
    args = ap.parse_args()
    remap = dict(r.split("=", 1) for r in args.remap)
    episodes = [ep for report in args.reports for ep in lost(report, args.match, remap)]
    print(f"{len(episodes)} episodes lost with {args.match!r} in their message", flush=True)
    t0 = time.monotonic()
    with ThreadPoolExecutor(args.workers) as pool:
        rows = []
        for row in pool.map(lambda ep: run(ep, args.step_timeout), episodes):
            rows.append(row)
            print(f"{'PASS' if row['success'] else 'FAIL'} {row['task']}/{row['plan']} seed {row['seed']}: "
                  f"{row['sim_s']} s simulated (limit {row['time_limit_s']:g} s) {row['message'][:160]}", flush=True)
    result = {"what": f"the episodes of {', '.join(r.name for r in args.reports)} lost with {args.match!r} in "
                      "their message, run again", "commit": commit(),
              "machine": machine(), "workers": args.workers,
              "generated": time.strftime("%Y-%m-%d %H:%M:%S"), "wall_s": round(time.monotonic() - t0, 1),
              "passed": sum(r["success"] for r in rows), "of": len(rows), "episodes": rows}
    args.json_out.write_text(json.dumps(result, indent=2) + "\n")
    print(f"{result['passed']} of {result['of']} pass now; wrote {args.json_out}")


if __name__ == "__main__":
    main()
