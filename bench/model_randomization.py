"""Reference plans on the library's models: each task's reference plan on held-out seeds, once on the task's own
(primitive) models and once with `--randomize-models` (every object of a family with models to draw on the
model its seed draws; needs `hgen assets fetch --objects`), through `hgen bench`'s runner. Writes one JSON row
per episode (task, seed, column, success, error, models) and a bar chart of both columns per task.

Usage: python bench/model_randomization.py [--tasks empty_cup_place,open_drawer] [--seeds 1000-1019]
       [--columns primitive,library] [--out bench/results/model_randomization.json]
       [--plot bench/results/model_randomization.png] [--redo library]
A (task, column) already complete in --out is kept (an interrupted run resumes); --redo names columns to run
again (after a fix). --plot-only redraws the chart from --out.
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from provenance import commit  # noqa: E402

TASKS = ("empty_cup_place", "cup_pour_easy", "dual_bottles_pick_easy", "dual_bottles_pick_hard", "open_drawer",
         "close_laptop_easy", "open_box_easy")
COLUMNS = ("primitive", "library")
TARGET_POINTS = 10  # the issue's target: library success within this many points of the primitive models'


def run_column(task: str, column: str, seeds: range) -> list[dict]:
    """The column's episodes; a library column of a task none of whose objects has a library model to draw
    is not run (it would be the primitive column again): its rows say so (success None)."""
    from humanoidgen.episodes.bench import run_bench
    from humanoidgen.tasks.models import with_models
    from humanoidgen.tasks.registry import load_task

    spec = load_task(task)
    if column == "library" and not with_models(spec, {}, randomize=True).randomize_models:
        families = sorted({o.type for o in spec.objects})
        note = f"no library model to draw for the task's objects ({', '.join(families)})"
        return [{"task": task, "column": column, "seed": s, "success": None, "error": note, "models": None}
                for s in seeds]
    (report,) = run_bench([spec], episodes=len(seeds), seed=seeds.start, randomize_models=column == "library")
    return [{"task": task, "column": column, "seed": r["seed"], "success": bool(r["success"]),
             "error": r["error"] or None, "models": {k: m["model"] for k, m in r.get("models", {}).items()}
             if column == "library" else None} for r in report.records]


def summary(rows: list[dict]) -> list[dict]:
    out = []
    for task in dict.fromkeys(r["task"] for r in rows):
        entry = {"task": task}
        for col in COLUMNS:
            got = [r for r in rows if r["task"] == task and r["column"] == col]
            entry[col] = {"successes": sum(bool(r["success"]) for r in got),
                          "episodes": sum(r["success"] is not None for r in got)}
            if got and all(r["success"] is None for r in got):
                entry[col]["note"] = got[0]["error"]
        by_model: dict[str, list[int]] = {}
        for r in rows:
            if r["task"] == task and r["column"] == "library" and r["success"] is not None:
                for name in {n for n in (r["models"] or {}).values() if not n.isdigit()}:  # imported ones
                    tally = by_model.setdefault(name, [0, 0])
                    tally[0] += bool(r["success"])
                    tally[1] += 1
        if by_model:
            entry["library"]["by_model"] = {k: f"{a}/{b}" for k, (a, b) in sorted(by_model.items())}
        p, lib = entry["primitive"], entry["library"]
        if p["episodes"] and lib["episodes"]:
            entry["gap_points"] = round(100 * (p["successes"] / p["episodes"] - lib["successes"] / lib["episodes"]), 1)
            entry["within_target"] = entry["gap_points"] <= TARGET_POINTS
        out.append(entry)
    return out


def plot(data: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    s = data["summary"]
    x = np.arange(len(s))
    fig, ax = plt.subplots(figsize=(8.5, 4))
    for k, (col, color) in enumerate(zip(COLUMNS, ("#4C72B0", "#DD8452"))):
        vals = [100 * e[col]["successes"] / max(e[col]["episodes"], 1) for e in s]
        bars = ax.bar(x + (k - 0.5) * 0.38, vals, 0.38, color=color, edgecolor="black", linewidth=0.5,
                      label={"primitive": "the task's own (primitive) models",
                             "library": "--randomize-models over the library"}[col])
        for b, e in zip(bars, s):
            label = f"{e[col]['successes']}/{e[col]['episodes']}" if e[col]["episodes"] else "no\nlibrary\nmodel"
            ax.text(b.get_x() + b.get_width() / 2, b.get_height() + 1, label, ha="center", fontsize=7)
    ax.set_xticks(x, [e["task"] for e in s], rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("success (%)")
    ax.set_ylim(0, 112)
    m = data["meta"]
    ax.set_title(f"Reference plans, seeds {m['seeds']}: the task's own models vs the object library "
                 f"(at {str(m['commit']).split()[0]})", fontsize=9, pad=24)
    ax.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, fontsize=8, frameon=False)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tasks", default=",".join(TASKS))
    ap.add_argument("--seeds", default="1000-1019")
    ap.add_argument("--columns", default=",".join(COLUMNS))
    ap.add_argument("--redo", default="", help="columns to run again even where --out has them")
    ap.add_argument("--out", type=Path, default=Path("bench/results/model_randomization.json"))
    ap.add_argument("--plot", type=Path, default=Path("bench/results/model_randomization.png"))
    ap.add_argument("--plot-only", action="store_true")
    ap.add_argument("--commit", default=None, help="the commit to record (default: this checkout's HEAD; for a run "
                    "from an exported tree)")
    args = ap.parse_args()
    a, b = (int(x) for x in args.seeds.split("-"))
    seeds = range(a, b + 1)
    old = json.loads(args.out.read_text()) if args.out.is_file() else {}
    rows = old.get("rows", []) if isinstance(old, dict) else []
    meta = old.get("meta", {}) if isinstance(old, dict) else {}
    redo = set(filter(None, args.redo.split(",")))
    if not args.plot_only:
        for task in args.tasks.split(","):
            for col in args.columns.split(","):
                have = [r for r in rows if r["task"] == task and r["column"] == col and r["seed"] in seeds]
                if len(have) == len(seeds) and col not in redo:
                    continue
                t0 = time.perf_counter()
                new = run_column(task, col, seeds)
                rows = [r for r in rows if not (r["task"] == task and r["column"] == col)] + new
                meta.setdefault("columns", {})[f"{task}/{col}"] = {"commit": args.commit or commit(),
                                                                    "seconds": round(time.perf_counter() - t0)}
                print(f"{task} {col}: {sum(bool(r['success']) for r in new)}/{len(new)}", flush=True)
                order = {t: k for k, t in enumerate(TASKS)}
                rows.sort(key=lambda r: (order.get(r["task"], 99), r["task"], COLUMNS.index(r["column"]), r["seed"]))
                meta.update(commit=args.commit or commit(), seeds=args.seeds,
                            machine=f"{platform.machine()}, {__import__('os').cpu_count()} cores (shared)")
                args.out.write_text(json.dumps({"meta": meta, "summary": summary(rows), "rows": rows}, indent=1))
    data = {"meta": meta, "summary": summary(rows), "rows": rows}
    args.out.write_text(json.dumps(data, indent=1))
    plot(data, args.plot)
    for e in data["summary"]:
        print(json.dumps(e))


if __name__ == "__main__":
    main()
