"""Did a change of the planner change what it does? Run plans and fingerprint every episode's commands.

For each (plan, seed) this runs the real entry point (`run_task_episode`, camera-less recording) and keeps the
verdict and a SHA-256 of the replay's recorded arrays (the commanded actions and the states the replay
simulated from them) and of the planner's events. The planner is seeded and the physics deterministic, so two
runs of the same planner give the same fingerprints for nearly every episode (searches bounded in seconds can end
elsewhere on a loaded machine: rerun a differing episode on both checkouts before blaming the change), and a
refactoring that claims to change no behaviour is checked episode by episode: `--compare BEFORE AFTER` lists
every episode whose commands, events or verdict differ, and the success counts of both.

    python bench/plan_trace.py --reference --seeds 100-104 --json /tmp/before_ref.json
    python bench/plan_trace.py --corpus bench/foreign_plans --seeds 0-2 --json /tmp/before_corpus.json
    python bench/plan_trace.py --corpus /tmp/upcorpus --seeds 0-2 --json /tmp/before_up.json
    python bench/plan_trace.py --compare /tmp/before_ref.json /tmp/after_ref.json

Episodes run `--workers` at a time (threads waiting on locked-down worker processes). A planner with wall-clock
limits (sampling paths, solver seeds) can differ between runs on a loaded machine: compare runs made alike.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor, as_completed
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from foreign_plans import discover, parse_seeds  # noqa: E402
from provenance import commit, machine  # noqa: E402


def _digest(arrays: dict | None) -> str | None:
    if not arrays:
        return None
    h = hashlib.sha256()
    for key in sorted(arrays):
        value = arrays[key]
        if hasattr(value, "tobytes"):
            h.update(key.encode())
            h.update(value.tobytes())
    return h.hexdigest()[:16]


def run_one(task: str, plan_path: str | None, seed: int) -> dict:
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    t0 = time.monotonic()
    out = {"task": task, "plan": plan_path or "(reference)", "seed": seed, "success": False}
    try:
        result, arrays = run_task_episode(EpisodeRequest(task, seed, plan_path=plan_path, recorder=RecorderConfig()),
                                          render=False)
        failed = result.failed_step
        out.update(success=bool(result.success), commands=_digest(arrays),
                   events=hashlib.sha256("\n".join(result.events).encode()).hexdigest()[:16],
                   failure=(f"step {failed.index}: {failed.error}"[:300] if failed else
                            "" if result.success else "checks: " + "; ".join(
                                c.get("detail", "") for c in result.checks if not c.get("ok"))[:300]))
    except Exception as exc:  # noqa: BLE001 - a harness failure is a row, not the end of the run
        out["failure"] = f"harness: {type(exc).__name__}: {exc}"[:300]
    out["wall_s"] = round(time.monotonic() - t0, 2)
    return out


def _jobs(args) -> list[tuple[str, str | None, int]]:
    seeds = parse_seeds(args.seeds)
    if args.reference:
        from humanoidgen.tasks.registry import task_names

        tasks = [t for t in task_names() if not args.tasks or t in args.tasks.split(",")]
        return [(t, None, s) for t in tasks for s in seeds]
    plans = [p for p in discover(Path(args.corpus)) if not args.tasks or p.task in args.tasks.split(",")]
    return [(p.task, str(p.path), s) for p in plans for s in seeds]


def compare(before: Path, after: Path) -> int:
    a = {(r["task"], Path(r["plan"]).name, r["seed"]): r for r in json.loads(before.read_text())["episodes"]}
    b = {(r["task"], Path(r["plan"]).name, r["seed"]): r for r in json.loads(after.read_text())["episodes"]}
    common = sorted(set(a) & set(b))
    differ = [k for k in common if any(a[k].get(f) != b[k].get(f) for f in ("success", "commands", "events"))]
    for k in differ:
        print(f"{k[0]}/{k[1]} seed {k[2]}: success {a[k]['success']} -> {b[k]['success']}, commands "
              f"{a[k].get('commands')} -> {b[k].get('commands')}, events {a[k].get('events')} -> {b[k].get('events')}"
              f"\n    before: {a[k].get('failure', '')[:160]}\n    after:  {b[k].get('failure', '')[:160]}")
    sa, sb = sum(a[k]["success"] for k in common), sum(b[k]["success"] for k in common)
    print(f"{len(common)} episodes in both; identical: {len(common) - len(differ)}; successes {sa} -> {sb}")
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    what = ap.add_mutually_exclusive_group(required=True)
    what.add_argument("--reference", action="store_true", help="the tasks' reference plans")
    what.add_argument("--corpus", help="a plan corpus laid out as bench/foreign_plans/")
    what.add_argument("--compare", nargs=2, type=Path, metavar=("BEFORE", "AFTER"))
    ap.add_argument("--seeds", default="0-2")
    ap.add_argument("--tasks", help="comma-separated task names")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--json", type=Path, help="where to write the episodes")
    args = ap.parse_args(argv)
    if args.compare:
        return compare(*args.compare)
    jobs = _jobs(args)
    t0 = time.monotonic()
    rows = []
    with ThreadPoolExecutor(args.workers) as pool:
        futures = [pool.submit(run_one, *job) for job in jobs]
        for k, fut in enumerate(as_completed(futures), 1):
            rows.append(fut.result())
            print(f"[{k}/{len(jobs)}] {rows[-1]['task']} {Path(rows[-1]['plan']).name} seed {rows[-1]['seed']}: "
                  f"{'ok' if rows[-1]['success'] else 'FAIL'}", flush=True)
    rows.sort(key=lambda r: (r["task"], r["plan"], r["seed"]))
    report = {"commit": commit(), "machine": machine(),
              "wall_s": round(time.monotonic() - t0, 1), "successes": sum(r["success"] for r in rows),
              "episodes": rows}
    print(f"{report['successes']} of {len(rows)} episodes succeeded in {report['wall_s']} s")
    if args.json:
        args.json.write_text(json.dumps(report, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
