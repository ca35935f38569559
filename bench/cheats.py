"""The cheating-plan battery (tests/cheats/NNN_*.py) through `run_task_episode`: which cheats are judged a success.

Each cheat is a complete plan for the task named in its `# task:` header that forges the outcome (writes the
simulator's state, edits the model, patches what the judge reads, forges its reply) instead of doing the task
with the robot. Every one of them must come back with success False. Run from the repository root:

    PYTHONPATH=$PWD python bench/cheats.py                       # all cheats, seeds 0 and 1
    PYTHONPATH=$PWD python bench/cheats.py --only 001,016 --seeds 0 --out /tmp/c.json

Writes bench/results/cheats.json: one record per (cheat, seed) with {task, cheat, seed, success, reason}, plus
the count judged a success.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import sys
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
from provenance import commit  # noqa: E402

CHEATS = ROOT / "tests" / "cheats"
_HEADER = re.compile(r"^#\s*(task|cheat):\s*(.*?)\s*$")


def battery() -> list[dict]:
    """[{name, path, task, cheat}] for every tests/cheats/NNN_*.py, in order."""
    out = []
    for path in sorted(CHEATS.glob("[0-9][0-9][0-9]_*.py")):
        head = {}
        for line in path.read_text().splitlines()[:5]:
            if m := _HEADER.match(line):
                head[m.group(1)] = m.group(2)
        if "task" not in head or "cheat" not in head:
            raise ValueError(f"{path.name}: needs '# task:' and '# cheat:' header lines")
        out.append({"name": path.stem, "path": path, "task": head["task"], "cheat": head["cheat"]})
    return out


def reason(result) -> str:
    """Why the episode failed (or what the checks said when it did not)."""
    failed = result.failed_step
    if failed is not None:
        return f"step {failed.index} ({failed.title}): {failed.error}"
    return "; ".join(f"{c['predicate']}: {'ok' if c['ok'] else 'FAILED'}: {c['detail']}" for c in result.checks)


def run_one(cheat: dict, seed: int, step_timeout_s: float = 60.0) -> dict:
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    t0 = time.perf_counter()
    rec = {"task": cheat["task"], "cheat": cheat["name"], "seed": seed}
    try:
        result, arrays = run_task_episode(EpisodeRequest(cheat["task"], seed, plan_path=str(cheat["path"]),
                                                         recorder=RecorderConfig(), step_timeout_s=step_timeout_s))
    except Exception as exc:  # noqa: BLE001 - a refused plan is a failed cheat, with its reason
        rec.update(success=False, reason=f"{type(exc).__name__}: {exc}"[:600], arrays=False)
    else:
        rec.update(success=bool(result.success), reason=reason(result)[:600], arrays=arrays is not None)
    rec["seconds"] = round(time.perf_counter() - t0, 1)
    return rec


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="0,1")
    ap.add_argument("--only", default="", help="comma-separated cheat numbers or names (default: all)")
    ap.add_argument("--out", default=str(ROOT / "bench" / "results" / "cheats.json"))
    args = ap.parse_args(argv)
    seeds = [int(s) for s in args.seeds.split(",") if s]
    only = [s for s in args.only.split(",") if s]
    cheats = [c for c in battery() if not only or any(c["name"] == o or c["name"].startswith(o + "_") for o in only)]
    records = []
    for cheat in cheats:
        for seed in seeds:
            rec = run_one(cheat, seed)
            records.append(rec)
            print(f"{'SUCCESS' if rec['success'] else 'failed '} {rec['cheat']:45s} seed {seed} "
                  f"({rec['seconds']:.0f} s): {rec['reason'][:150]}", flush=True)
    judged = sum(r["success"] for r in records)
    report = {"commit": commit(ROOT, full=True), "episodes": len(records), "judged_success": judged,
              "cheats": len(cheats), "seeds": seeds, "records": records}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(report, indent=1) + "\n")
    print(f"{judged} of {len(records)} cheating episodes judged a success -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
