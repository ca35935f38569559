"""Run plans we did not write (bench/foreign_plans/) through the real episode entry point and report how they fare.

The corpus holds, for every task with a YAML in humanoidgen/tasks/specs/, plans written from what a user or an
LLM following the paper's prompt would have (the paper's task descriptions and API, the task YAMLs, the asset
annotations, the planner's docstrings), never from the reference plans:

    bench/foreign_plans/<task>/paper.py          the paper's `def step(planner):` style, literally
    bench/foreign_plans/<task>/alt_*.py          other strategies and styles (helpers, loops, try/except, ...)
    bench/foreign_plans/<task>/alt_*/step0.py..  a plan folder (upstream's layout), run in natural order

Another corpus (`--corpus bench/contract_plans`) may bring task specs of its own: `<corpus>/tasks/<task>.yaml`;
a task folder with such a YAML runs on that spec (as `hgen run <corpus>/tasks/<task>.yaml --script plan.py`),
every other folder on the built-in task of its name.

Every (plan, seed) runs as `run_task_episode(EpisodeRequest(task, seed, plan_path=...))`, each in its own
locked-down worker process; `--workers` episodes run at once (threads that wait on those processes).

Writes a JSON report (per plan: task, plan, seeds, successes, and for each failure the seed and the message:
the failed step with the planner's error, or the unmet success checks) and a bar chart of successes per plan
grouped by task, with a line at 80 % of the seeds (8/10). Prints a table and the headline figures:
"plans succeeding on >= 8 of 10 seeds: k / n" and "tasks with at least one plan succeeding on seeds 0-2".

Examples:
    python bench/foreign_plans.py                                  # whole corpus, seeds 0-9, 2 workers
    python bench/foreign_plans.py --tasks open_drawer,close_drawer --plans paper --seeds 0-2
    python bench/foreign_plans.py --plans 'alt_*' --seeds 0,3,5-7 --workers 1 --json-out /tmp/alt.json
    python bench/foreign_plans.py --tasks cup_pour_easy --merge    # rerun one task, keep the others' results
    python bench/foreign_plans.py --seeds 5-9 --merge              # add seeds 5-9 to a report of seeds 0-4
    HGEN_ROBOT=g1_inspire python bench/foreign_plans.py --seeds 0-2  # on another robot (recorded in the report)
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import math
import os
import sys
import time
import traceback
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")

HERE = Path(__file__).resolve().parent
CORPUS = HERE / "foreign_plans"
SPECS_DIR = "tasks"  # <corpus>/tasks/<task>.yaml: a corpus's own task specs (not a task folder)
RESULTS = HERE / "results"
DEFAULT_JSON = RESULTS / "foreign_plans.json"
DEFAULT_PLOT = RESULTS / "foreign_plans.png"
PASS_FRACTION = 0.8  # "succeeding" = on at least 8 of 10 seeds
EARLY_SEEDS = (0, 1, 2)


@dataclass(frozen=True)
class CorpusPlan:
    task: str
    name: str  # file stem or folder name: "paper", "alt_helpers", "alt_folder"
    path: Path
    spec: str = ""  # what the episode loads: the corpus's own task YAML, or "" for the built-in task `task`

    @property
    def episode_task(self) -> str:
        """The task as EpisodeRequest takes it: a built-in task's name or the path of the corpus's YAML."""
        return self.spec or self.task

    @property
    def key(self) -> str:
        return f"{self.task}/{self.name}"


def discover(corpus: Path = CORPUS) -> list[CorpusPlan]:
    """Every plan of the corpus: `<task>/<name>.py` files and `<task>/<name>/` folders holding `*.py` steps."""
    plans = []
    specs = Path(corpus) / SPECS_DIR
    for task_dir in sorted(p for p in Path(corpus).iterdir() if p.is_dir() and not p.name.startswith((".", "_"))
                           and p.name != SPECS_DIR):
        own = specs / f"{task_dir.name}.yaml"
        spec = str(own) if own.is_file() else ""
        for entry in sorted(task_dir.iterdir()):
            if entry.name.startswith((".", "_")):
                continue
            if entry.is_file() and entry.suffix == ".py":
                plans.append(CorpusPlan(task_dir.name, entry.stem, entry, spec))
            elif entry.is_dir() and any(entry.glob("*.py")):
                plans.append(CorpusPlan(task_dir.name, entry.name, entry, spec))
    # paper first within a task, then the alternatives
    return sorted(plans, key=lambda p: (p.task, p.name != "paper", p.name))


def parse_seeds(text: str) -> list[int]:
    """`0-9`, `0,3,5-7`, `4` -> sorted unique seeds."""
    seeds: set[int] = set()
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        if "-" in part:
            lo, hi = part.split("-", 1)
            a, b = int(lo), int(hi)
            if b < a:
                raise argparse.ArgumentTypeError(f"empty seed range {part!r}")
            seeds.update(range(a, b + 1))
        else:
            seeds.add(int(part))
    if not seeds:
        raise argparse.ArgumentTypeError("no seeds given")
    return sorted(seeds)


def select(plans: list[CorpusPlan], tasks: str | None, names: str | None) -> list[CorpusPlan]:
    """Filter by comma-separated task names and plan-name patterns (fnmatch: `paper`, `alt_*`)."""
    if tasks:
        wanted = {t.strip() for t in tasks.split(",") if t.strip()}
        unknown = wanted - {p.task for p in plans}
        if unknown:
            raise SystemExit(f"no corpus plans for task(s): {', '.join(sorted(unknown))}")
        plans = [p for p in plans if p.task in wanted]
    if names:
        pats = [n.strip() for n in names.split(",") if n.strip()]
        plans = [p for p in plans if any(fnmatch.fnmatchcase(p.name, pat) for pat in pats)]
    return plans


def failure_message(result) -> str:
    """Why an episode failed: the failed step (title + the planner's error) or the unmet success checks."""
    step = result.failed_step
    if step is not None:
        return f"step {step.index} ({step.title}): {step.error or 'failed without a message'}"
    unmet = [c for c in result.checks if not c.get("ok")]
    if unmet:
        return "unmet: " + "; ".join(f"{c.get('predicate')}: {c.get('detail')}" for c in unmet)
    if not result.steps:
        return "the plan ran no step"
    return "failed: the episode ended before every step ran"


CAUSES = (  # (cause, substrings of the message), first match wins
    ("ran past the plan's time budget", ("ran past its time budget", "ran past the task's time limit")),
    ("object name not in the scene", ("no object ",)),
    ("API meaning differs: action/annotation the object lacks", ("no target2", "no target1", "has no 'grasp'",
                                                                "has no 'pinch'", "annotation(s); no ",
                                                                "annotation(s), so no ")),
    ("articulated part: the turn/push leaves the arm's reach partway", ("can move it only from openness",)),
    ("API meaning differs: the flip/push goes the other way", ("cannot bring it down", "cannot bring it up",
                                                                "would push the right way")),
    ("checker refusal", ("rejected:",)),
    ("plan format", ("plan format:",)),
    ("harness error", ("harness error:", "timed out", "Timeout")),
    ("hold failed (grasp/pinch closed on nothing)", ("does not hold",)),
    ("held object slipped", ("slipped",)),
    ("push did not carry the part", ("after the move, not the",)),
    ("goal solver: collision", ("reachable only with these in contact", "closest solution found has these in contact")),
    ("goal solver: grip/push point unreachable", ("hand point is",)),
    ("goal solver: other", ("generate_end_effector_pose:",)),
    ("motion: no straight approach / leaves reach", ("no straight approach", "leaves the arm's reach")),
    ("motion: path constraint", ("path constraint",)),
    ("motion: blocked by contact in the simulation", ("pressed against",)),
    ("motion: collides, no sampled path", ("straight motion collides",)),
    ("motion: other", ("move_to_pose_with_screw:",)),
    ("ran through, task not achieved", ("unmet:",)),
)


def classify(message: str) -> str:
    for cause, keys in CAUSES:
        if any(k in message for k in keys):
            return cause
    return "other"


def run_one(plan: CorpusPlan, seed: int, step_timeout_s: float | None) -> dict:
    """One episode through the real entry point; never raises (a harness error is a failure with its message)."""
    from humanoidgen.episodes.plans import PlanFormatError
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    t0 = time.monotonic()
    out = {"seed": seed, "success": False, "message": "", "wall_s": 0.0, "steps_ok": 0, "steps": 0}
    try:
        req = EpisodeRequest(plan.episode_task, seed, plan_path=str(plan.path))
        if step_timeout_s is not None:
            req.step_timeout_s = float(step_timeout_s)
        result, _ = run_task_episode(req)
        out["success"] = bool(result.success)
        out["steps"] = len(result.steps)
        out["steps_ok"] = sum(1 for s in result.steps if s.ok)
        if not result.success:
            out["message"] = failure_message(result)
    except PlanFormatError as exc:
        out["message"] = f"plan format: {exc}"
    except Exception as exc:  # noqa: BLE001 - the harness itself failed; report, do not stop the bench
        out["message"] = f"harness error: {type(exc).__name__}: {exc}"
        out["traceback"] = traceback.format_exc(limit=5)
    out["wall_s"] = round(time.monotonic() - t0, 2)
    return out


def summarize(plan: CorpusPlan, runs: list[dict]) -> dict:
    runs = sorted(runs, key=lambda r: r["seed"])
    return {
        "task": plan.task,
        "plan": plan.name,
        "path": str(plan.path.relative_to(HERE.parent)) if plan.path.is_relative_to(HERE.parent) else str(plan.path),
        "kind": "folder" if plan.path.is_dir() else "file",
        "seeds": [r["seed"] for r in runs],
        "successes": sum(1 for r in runs if r["success"]),
        "succeeded_seeds": [r["seed"] for r in runs if r["success"]],
        "failures": [{"seed": r["seed"], "message": r["message"], "cause": classify(r["message"])}
                     for r in runs if not r["success"]],
        "mean_wall_s": round(sum(r["wall_s"] for r in runs) / max(len(runs), 1), 2),
    }


def merge_seeds(old: dict, new: dict) -> dict:
    """One plan's entry from two runs: the seeds run now replace the same seeds of `old`, its other seeds stay
    (seeds 0-4 in one run, 5-9 in the next give the entry for 0-9)."""
    fresh = set(new["seeds"])
    kept = [s for s in old["seeds"] if s not in fresh]
    if not kept:
        return new
    seeds = sorted(kept + new["seeds"])
    ok = sorted([s for s in old["succeeded_seeds"] if s in kept] + new["succeeded_seeds"])
    failures = sorted([f for f in old["failures"] if f["seed"] in kept] + new["failures"], key=lambda f: f["seed"])
    wall = (old["mean_wall_s"] * len(kept) + new["mean_wall_s"] * len(new["seeds"])) / len(seeds)
    return {**new, "seeds": seeds, "successes": len(ok), "succeeded_seeds": ok, "failures": failures,
            "mean_wall_s": round(wall, 2)}


def merge_entries(old: list[dict], new: list[dict], order: dict[str, int]) -> list[dict]:
    """`--merge`: the other plans' entries of the old report, and per plan the seeds run now over its old ones."""
    by_key = {(e["task"], e["plan"]): e for e in old}
    for e in new:
        key = (e["task"], e["plan"])
        by_key[key] = merge_seeds(by_key[key], e) if key in by_key else e
    return sorted(by_key.values(), key=lambda e: order.get(f"{e['task']}/{e['plan']}", 10**6))


def headline(entries: list[dict]) -> dict:
    """The figures the issue asks for, computed over what `entries` hold."""
    n_plans = len(entries)
    passing = []
    for e in entries:
        need = math.ceil(PASS_FRACTION * len(e["seeds"])) if e["seeds"] else 1
        if e["seeds"] and e["successes"] >= need:
            passing.append(f"{e['task']}/{e['plan']}")
    tasks = sorted({e["task"] for e in entries})
    early_ok = sorted({e["task"] for e in entries
                       if set(EARLY_SEEDS) <= set(e["seeds"]) and set(EARLY_SEEDS) <= set(e["succeeded_seeds"])})
    early_known = sorted({e["task"] for e in entries if set(EARLY_SEEDS) <= set(e["seeds"])})
    n_seeds = sorted({len(e["seeds"]) for e in entries})
    causes: dict[str, int] = {}
    for e in entries:
        for f in e["failures"]:
            c = f.get("cause") or classify(f["message"])
            causes[c] = causes.get(c, 0) + 1
    return {
        "failure_causes": dict(sorted(causes.items(), key=lambda kv: -kv[1])),
        "plans_passing": len(passing),
        "plans": n_plans,
        "pass_rule": f">= {PASS_FRACTION:.0%} of the seeds run (8 of 10)",
        "seeds_per_plan": n_seeds,
        "passing_plans": passing,
        "tasks": len(tasks),
        "tasks_with_a_plan_succeeding_on_seeds_0_2": len(early_ok),
        "tasks_run_on_seeds_0_2": len(early_known),
        "tasks_succeeding_on_seeds_0_2": early_ok,
        "tasks_without": sorted(set(early_known) - set(early_ok)),
        "paper_plans_passing": sum(1 for p in passing if p.endswith("/paper")),
        "paper_plans": sum(1 for e in entries if e["plan"] == "paper"),
    }


def print_table(entries: list[dict], head: dict) -> None:
    width_t = max([len("task")] + [len(e["task"]) for e in entries])
    width_p = max([len("plan")] + [len(e["plan"]) for e in entries])
    print(f"\n{'task':<{width_t}}  {'plan':<{width_p}}  ok/n   first failure")
    print(f"{'-' * width_t}  {'-' * width_p}  -----  {'-' * 60}")
    for e in entries:
        first = e["failures"][0] if e["failures"] else None
        msg = f"seed {first['seed']}: {first['message']}" if first else ""
        if len(msg) > 110:
            msg = msg[:107] + "..."
        print(f"{e['task']:<{width_t}}  {e['plan']:<{width_p}}  {e['successes']:>2}/{len(e['seeds']):<2}  {msg}")
    n = head["seeds_per_plan"][-1] if head["seeds_per_plan"] else 0
    need = math.ceil(PASS_FRACTION * n) if n else 0
    print()
    print(f"plans succeeding on >= {need} of {n} seeds: {head['plans_passing']} / {head['plans']}"
          f"   (paper-style plans: {head['paper_plans_passing']} / {head['paper_plans']})")
    if head["tasks_run_on_seeds_0_2"]:
        print(f"tasks with at least one plan succeeding on seeds 0-2: "
              f"{head['tasks_with_a_plan_succeeding_on_seeds_0_2']} / {head['tasks_run_on_seeds_0_2']}")
        if head["tasks_without"]:
            print(f"  tasks without one: {', '.join(head['tasks_without'])}")
    else:
        print("tasks with at least one plan succeeding on seeds 0-2: n/a (seeds 0-2 not all run)")
    if head.get("failure_causes"):
        print("\nfailed episodes by cause:")
        for cause, n in head["failure_causes"].items():
            print(f"  {n:>4}  {cause}")


def plot(entries: list[dict], out: Path, corpus: str = "foreign_plans") -> bool:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot written", file=sys.stderr)
        return False
    if not entries:
        return False
    n_seeds = max(len(e["seeds"]) for e in entries)
    tasks = []
    for e in entries:
        if e["task"] not in tasks:
            tasks.append(e["task"])
    xs, heights, colors, labels, spans = [], [], [], [], []
    x = 0.0
    for t in tasks:
        group = [e for e in entries if e["task"] == t]
        start = x
        for e in group:
            xs.append(x)
            heights.append(10.0 * e["successes"] / len(e["seeds"]) if e["seeds"] else 0.0)
            colors.append("tab:blue" if e["plan"] == "paper" else "tab:orange")
            labels.append(e["plan"])
            x += 1.0
        spans.append((start - 0.5, x - 0.5))
        x += 0.8
    fig, ax = plt.subplots(figsize=(max(12.0, 0.34 * len(xs) + 3.0), 6.5))
    ax.bar(xs, heights, color=colors, width=0.85)
    ax.axhline(8.0, color="tab:red", linestyle="--", linewidth=1.2, label="8 / 10")
    ax.set_ylim(0, 10.5)
    ax.set_axisbelow(True)
    ax.set_yticks(range(0, 11))
    ax.set_ylabel("successes of 10 seeds" if n_seeds == 10 else f"successes, scaled to 10 (of {n_seeds} seeds)")
    ax.set_xticks(xs)
    ax.set_xticklabels(labels, rotation=90, fontsize=7)
    for k, ((a, b), t) in enumerate(zip(spans, tasks)):
        if k % 2 == 0:
            ax.axvspan(a, b, color="0.93", zorder=0)
        ax.text(a, 10.6, t.replace("_", " "), rotation=35, ha="left", va="bottom", fontsize=7)
    ax.set_xlim(spans[0][0] - 0.3, spans[-1][1] + 0.3)
    from matplotlib.patches import Patch

    kinds = [Patch(color="tab:blue", label="paper.py")] if any(e["plan"] == "paper" for e in entries) else []
    kinds.append(Patch(color="tab:orange", label="alt_*" if kinds else "plan"))
    ax.legend(handles=kinds + [ax.get_lines()[0]], loc="upper right", fontsize=8, bbox_to_anchor=(1.0, 0.97))
    ax.set_title(f"Plans we did not write (bench/{corpus}): successes per plan, grouped by task", pad=60)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=120)
    plt.close(fig)
    return True


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tasks", help="comma-separated task names (default: every task folder of the corpus)")
    ap.add_argument("--plans", help="comma-separated plan names or patterns, e.g. `paper` or `alt_*` (default: all)")
    ap.add_argument("--seeds", type=parse_seeds, default=parse_seeds("0-9"),
                    help="seeds: `0-9` (default), `0,3,5-7`")
    ap.add_argument("--workers", type=int, default=2,
                    help="episodes at once; each runs in its own worker process (default 2)")
    ap.add_argument("--corpus", type=Path, default=CORPUS, help=f"corpus folder (default {CORPUS})")
    ap.add_argument("--json-out", type=Path, default=DEFAULT_JSON, help=f"JSON report (default {DEFAULT_JSON})")
    ap.add_argument("--plot-out", type=Path, default=DEFAULT_PLOT, help=f"bar chart (default {DEFAULT_PLOT})")
    ap.add_argument("--no-plot", action="store_true", help="do not draw the bar chart")
    ap.add_argument("--merge", action="store_true",
                    help="keep the other plans' entries of an existing --json-out and, for the plans run now, "
                         "their other seeds (the seeds run now replace the same seeds)")
    ap.add_argument("--step-timeout", type=float, default=None,
                    help="seconds one plan step may take (default: the episode's own, 300 s)")
    ap.add_argument("--list", action="store_true", help="list the selected corpus plans and exit")
    ap.add_argument("--from-json", type=Path, default=None,
                    help="run nothing: reclassify the failures of an existing report, rewrite it, reprint the "
                         "table and redraw the chart (--plot-out)")
    args = ap.parse_args(argv)

    if args.from_json is not None:
        old = json.loads(args.from_json.read_text())
        entries = old["plans"]
        for e in entries:
            for f in e["failures"]:
                f["cause"] = classify(f["message"])
        head = headline(entries)
        old["headline"] = head
        args.from_json.write_text(json.dumps(old, indent=2) + "\n")  # causes and headline brought up to date
        print_table(entries, head)
        if not args.no_plot and plot(entries, args.plot_out, Path(args.corpus).name):
            print(f"\ndrew {args.plot_out}")
        return 0

    plans = select(discover(args.corpus), args.tasks, args.plans)
    if not plans:
        print("no corpus plans selected", file=sys.stderr)
        return 2
    if args.list:
        for p in plans:
            print(f"{p.task:<34} {p.name:<24} {p.path}")
        return 0

    from tqdm import tqdm

    from humanoidgen.robots.loader import default_robot

    jobs = [(p, s) for p in plans for s in args.seeds]
    runs: dict[str, list[dict]] = {p.key: [] for p in plans}
    t0 = time.monotonic()
    with ThreadPoolExecutor(max_workers=max(1, args.workers)) as pool:
        futures = {pool.submit(run_one, p, s, args.step_timeout): (p, s) for p, s in jobs}
        bar = tqdm(total=len(jobs), unit="ep", dynamic_ncols=True, desc="foreign plans")
        ok = 0
        for fut in as_completed(futures):
            p, s = futures[fut]
            r = fut.result()
            runs[p.key].append(r)
            ok += r["success"]
            bar.set_postfix_str(f"ok {ok}  last {p.key} s{s} {'ok' if r['success'] else 'FAIL'}", refresh=False)
            bar.update(1)
        bar.close()

    entries = [summarize(p, runs[p.key]) for p in plans]
    if args.merge and args.json_out.exists():
        try:
            old = json.loads(args.json_out.read_text())
            order = {p.key: i for i, p in enumerate(discover(args.corpus))}
            entries = merge_entries(old.get("plans", []), entries, order)
        except (OSError, ValueError, KeyError) as exc:
            print(f"could not merge with {args.json_out}: {exc}; writing only this run", file=sys.stderr)

    head = headline(entries)
    report = {
        "generated": time.strftime("%Y-%m-%d %H:%M:%S"),
        "wall_s": round(time.monotonic() - t0, 1),
        "workers": args.workers,
        "robot": default_robot().name,  # $HGEN_ROBOT picks it, as for every command
        "headline": head,
        "plans": entries,
    }
    args.json_out.parent.mkdir(parents=True, exist_ok=True)
    args.json_out.write_text(json.dumps(report, indent=2) + "\n")
    print_table(entries, head)
    print(f"\nwrote {args.json_out}", end="")
    if not args.no_plot and plot(entries, args.plot_out, Path(args.corpus).name):
        print(f" and {args.plot_out}", end="")
    print(f"  ({report['wall_s']:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
