"""Lay out the paper authors' published plans as a corpus for bench/foreign_plans.py, without copying them here.

The HumanoidGen authors publish one generated plan per task (a folder of `step0.py ... stepN.py` in the paper's
`def step(planner):` form) in their repository, under `humanoidgen/motion_planning/h1_2/solution/generated/`. They
were written next to the authors' planner, not ours, so they are the nearest thing to the held-out corpus the
project is measured on. This script copies those of our tasks' folders (only the `step<N>.py` files: upstream runs
them by name) from a local clone into `<out>/<task>/upstream/`, for:

    git clone https://github.com/TeleHuman/HumanoidGen /tmp/HumanoidGen
    python bench/upstream_corpus.py /tmp/HumanoidGen --out /tmp/upcorpus
    python bench/foreign_plans.py --corpus /tmp/upcorpus --seeds 0-2 --json-out bench/results/upstream_plans.json

The plans stay outside this repository (their code is the authors'); only the measurement is committed.
"""

from __future__ import annotations

import argparse
import re
import shutil
import sys
from pathlib import Path

GENERATED = Path("humanoidgen/motion_planning/h1_2/solution/generated")
STEP_FILE = re.compile(r"step\d+\.py")
SPECS = Path(__file__).resolve().parents[1] / "humanoidgen" / "tasks" / "specs"


def our_tasks() -> list[str]:
    return sorted(p.stem for p in SPECS.glob("*.yaml"))


def lay_out(clone: Path, out: Path) -> dict[str, int]:
    """Copy each of our tasks' upstream step files into out/<task>/upstream/; returns task -> number of steps."""
    src_root = clone / GENERATED
    if not src_root.is_dir():
        raise SystemExit(f"{clone}: no {GENERATED} (is this a clone of TeleHuman/HumanoidGen?)")
    found: dict[str, int] = {}
    for task in our_tasks():
        steps = sorted((p for p in (src_root / task).glob("step*.py") if STEP_FILE.fullmatch(p.name)),
                       key=lambda p: int(p.stem[4:]))
        if not steps:
            continue
        dest = out / task / "upstream"
        if dest.exists():
            shutil.rmtree(dest)
        dest.mkdir(parents=True)
        for p in steps:
            shutil.copyfile(p, dest / p.name)
        found[task] = len(steps)
    return found


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("clone", type=Path, help="a local clone of github.com/TeleHuman/HumanoidGen")
    ap.add_argument("--out", type=Path, default=Path("/tmp/upcorpus"), help="corpus folder to write (default /tmp/upcorpus)")
    args = ap.parse_args()
    found = lay_out(args.clone, args.out)
    missing = [t for t in our_tasks() if t not in found]
    for task, n in found.items():
        print(f"{task:34s} {n:3d} steps")
    print(f"{len(found)} tasks laid out in {args.out}" + (f"; upstream has no plan for: {', '.join(missing)}" if missing else ""))
    return 0 if found else 1


if __name__ == "__main__":
    sys.exit(main())
