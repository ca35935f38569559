"""Policy study on this machine's CPU with a reduced recipe: DP3 on close_drawer, open_box_easy and
dual_bottles_pick_easy, DP on close_drawer, 50 demonstrations each, evaluated closed-loop (3 seeds x 20
episodes). Writes bench/results/policies_<name>.json (rows: task, policy, demos, success_mean, success_std,
training time, time per epoch) and a plot of success vs demonstrations beside it.

The reduced recipe (the paper's is 3,000 epochs of a 512/1024/2048 U-Net at batch 256, for a GPU):
    U-Net 64/128/256, 2 observation steps, 7 action steps, horizon 8, batch 64, AdamW 3e-4 (200 warm-up
    steps), DP3 512 points, DP images 84x112 cropped to 76x100, EPOCHS epochs (default 150).

Data missing under --data-root is collected first (about 10 s per close_drawer episode here).

    python bench/policies.py                              # the full reduced study (hours on 2 cores)
    python bench/policies.py --tasks close_drawer --policies dp3 --epochs 30 --episodes 10 --name short
    python bench/policies.py --paper --device cuda        # the paper's recipe and study, on a GPU
    python bench/policies.py --recipe fast --tasks close_drawer --policies dp3 --epochs 40 --name cpu_fast

A run trained and evaluated by hand joins a table: its saved report into rows (how it was trained said here),
then --combine with others:
    python bench/policies.py --from-eval eval.json --recipe fast --epochs 40 --train-scenes randomized --name mine

Clean-trained against randomized-trained (issue 37), each evaluated on clean and on randomized scenes (the
randomized data is collected as `hgen collect --room random --randomize-visuals` records it):
    python bench/policies.py --recipe fast --tasks open_box_easy --policies dp3 --epochs 40 \
        --train-scenes clean,randomized --eval-scenes clean,randomized --name cpu_fast_randomized

--recipe fast: DP3 with 256 points, AdamW peak 1e-3, 4 executed actions of 8 (about 28 s an epoch here);
--config '{"train": {"save_every": 2}}' merges more settings into the recipe (validated first).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MUJOCO_GL", "egl")

ROOT = Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT.parent))
sys.path.insert(0, str(ROOT))
from provenance import commit, machine  # noqa: E402 (bench/provenance.py: the commit, "+changes" where tracked files differ)
from humanoidgen.policies.recipes import RECIPES, merge  # noqa: E402 (the recipes: humanoidgen/policies/recipes.py)

# (task, policy) pairs of the reduced study, as the issue sizes it.
REDUCED_RUNS = (("close_drawer", "dp3"), ("open_box_easy", "dp3"), ("dual_bottles_pick_easy", "dp3"),
                ("close_drawer", "dp"))


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--tasks", help="comma list (default: the reduced study's pairs)")
    p.add_argument("--policies", default="dp,dp3")
    p.add_argument("--demos", default="50")
    p.add_argument("--epochs", type=int, default=150)
    p.add_argument("--episodes", type=int, default=20, help="evaluation episodes per seed")
    p.add_argument("--seeds", default="0,1,2")
    p.add_argument("--data-root", type=Path, default=Path("data/policy_study"))
    p.add_argument("--runs-root", type=Path, default=Path("runs/policy_study"))
    p.add_argument("--name", default="cpu_reduced", help="results go to bench/results/policies_<name>.json")
    p.add_argument("--threads", type=int, default=1, help="torch threads (1: on a shared 2-core machine a second "
                                                          "thread made training ~10x slower)")
    p.add_argument("--device", default="auto")
    p.add_argument("--paper", action="store_true", help="the paper's recipe and study: 14 tasks x 20/50/100 x both")
    p.add_argument("--recipe", choices=sorted(RECIPES), default="reduced",
                   help="the recipe (reduced: the first CPU one; fast: 256 points, lr 1e-3; paper: the GPU one)")
    p.add_argument("--config", default=None,
                   help="JSON merged into the recipe of every policy run, e.g. '{\"train\": {\"epochs\": 40}}'")
    p.add_argument("--train-scenes", default="clean", help="clean, randomized or both: the demonstrations each run "
                                                          "is trained on (randomized: DATA/<task>_randomized)")
    p.add_argument("--eval-scenes", default="clean", help="clean, randomized or both: each run evaluated on each")
    p.add_argument("--combine", help="comma list of earlier --name runs: their rows into one JSON and plot "
                                     "(--name), e.g. a clean-trained and a randomized-trained run made side by side")
    p.add_argument("--from-eval", help="a saved `hgen policy eval --out` report, or a comma list of reports of one "
                                      "checkpoint on other seeds (evaluations run side by side: pooled into one "
                                      "row per scenes): its rows (with --demos, --recipe, --train-scenes saying how "
                                      "the run was trained; the epochs read from the checkpoint, else --epochs) "
                                      "into policies_<name>.json and a plot, for --combine")
    args = p.parse_args()
    if args.combine:
        return combine(_names(args.combine), args.name)
    if args.from_eval:
        return from_eval(args)

    import torch

    from humanoidgen.policies.bench import PAPER_TASKS, StudyConfig, format_row, run_study, write_results

    torch.set_num_threads(args.threads)
    demos = tuple(int(d) for d in args.demos.split(","))
    seeds = tuple(int(s) for s in args.seeds.split(","))
    policies = [q.strip() for q in args.policies.split(",")]
    if args.paper:
        pairs = [(t, q) for t in PAPER_TASKS for q in ("dp", "dp3")]
        demos = (20, 50, 100)
        recipe = {q: {} for q in ("dp", "dp3")}
    else:
        tasks = [t.strip() for t in args.tasks.split(",")] if args.tasks else None
        pairs = [(t, q) for t, q in REDUCED_RUNS if q in policies] if tasks is None else \
            [(t, q) for t in tasks for q in policies]
        extra = json.loads(args.config) if args.config else {}
        recipe = {q: merge(merge(o, {"train": {"epochs": args.epochs}}), extra) for q, o in RECIPES[args.recipe].items()}
        from humanoidgen.policies.registry import policy_type

        for q in policies:  # a bad setting is refused here, before any data is collected
            policy_type(q).config(recipe[q])
    rows, t0, head = [], time.perf_counter(), commit()  # the code that runs, read before it does
    for task, policy in pairs:
        cfg = StudyConfig(tasks=(task,), demos=demos, policies=(policy,), data_root=args.data_root,
                          runs_root=args.runs_root, overrides=recipe, eval_episodes=args.episodes, eval_seeds=seeds,
                          device=args.device, recipe="paper" if args.paper else args.recipe,
                          train_scenes=_names(args.train_scenes), scenes=_names(args.eval_scenes))
        rows += run_study(cfg)
    print("\n".join(format_row(r) for r in rows))
    out = ROOT / "results" / f"policies_{args.name}.json"
    settings = {"recipe": "paper" if args.paper else args.recipe, "overrides": recipe, "pairs": pairs,
                "torch_threads": args.threads, "torch": torch.__version__, "cpu_count": os.cpu_count(),
                "commit": head, "machine": f"{platform.machine()}, Python {platform.python_version()}",
                "total_minutes": round((time.perf_counter() - t0) / 60, 1)}
    write_results(rows, cfg, out, out.with_suffix(".png"), settings)
    print(f"wrote {out} and {out.with_suffix('.png')}")
    return 0


def combine(names: tuple[str, ...], name: str) -> int:
    """The rows of bench/results/policies_<n>.json for each n, into policies_<name>.json and .png (each row with
    its 95% Wilson intervals, `success_ci95`, for the policy and the baselines; rows of one checkpoint on the same
    scenes from other evaluation seeds pooled into one: `pool_rows`)."""
    from humanoidgen.policies.bench import plot
    from humanoidgen.policies.study_rows import pool_rows, with_intervals

    parts = {n: json.loads((ROOT / "results" / f"policies_{n}.json").read_text()) for n in names}
    rows = pool_rows([with_intervals(r) for part in parts.values() for r in part["rows"]])
    out = ROOT / "results" / f"policies_{name}.json"
    out.write_text(json.dumps({"settings": {"combined": list(names), **{n: part["settings"] for n, part in
                                                                        parts.items()}}, "rows": rows}, indent=2))
    plot(rows, out.with_suffix(".png"))
    print(f"wrote {out} and {out.with_suffix('.png')} ({len(rows)} rows)")
    return 0


def from_eval(args) -> int:
    """policies_<name>.json (and its plot) from a saved evaluation report of a run trained by hand."""
    from humanoidgen.policies.bench import plot
    from humanoidgen.policies.study_rows import SCENES, pool_rows, rows_from_eval

    if args.train_scenes not in SCENES:
        print(f"error: --train-scenes with --from-eval is one of {', '.join(SCENES)} (got {args.train_scenes!r})",
              file=sys.stderr)
        return 2
    reports = [Path(x) for x in args.from_eval.split(",") if x.strip()]
    for report in reports:
        if not report.exists():
            print(f"error: no evaluation report at {report}", file=sys.stderr)
            return 2
    rows = []
    for report in reports:
        try:
            rows += rows_from_eval(json.loads(report.read_text()), int(args.demos.split(",")[0]), args.recipe,
                                   args.epochs, args.train_scenes)
        except (ValueError, KeyError) as exc:
            print(f"error: {report} is not a `hgen policy eval --out` report ({exc})", file=sys.stderr)
            return 2
    try:
        rows = pool_rows(rows)
    except ValueError as exc:  # reports that share seeds: the same episodes twice
        print(f"error: {exc}", file=sys.stderr)
        return 2
    from humanoidgen.policies import checkpoint as ck

    for row in rows:  # the epochs the checkpoint was trained, where it is still there to say
        if Path(row["checkpoint"]).is_file():
            state = ck.read(Path(row["checkpoint"]))
            row["epochs"] = int(state.get("epoch", state.get("meta", {}).get("epoch", row["epochs"])))
            config = state.get("config", {})
            row["action_frame"] = config.get("action_frame", "absolute")
            if "num_points" in config:  # DP3's points read: a recipe's setting a run may change
                row["num_points"] = int(config["num_points"])
            row["observe_hands"] = bool(config.get("observe_hands", False))
            recorder = state.get("meta", {}).get("recorder") or {}  # what the policy's cloud was drawn like
            row["point_cloud_near_hands"] = float(recorder.get("point_cloud_near_hands", 0.0))
            perturbation = training_perturbation(state.get("meta", {}))
            if perturbation:
                row["perturbation"] = perturbation
    out = ROOT / "results" / f"policies_{args.name}.json"
    out.write_text(json.dumps({"settings": {"from_eval": [str(r) for r in reports], "recipe": args.recipe,
                                            "epochs": args.epochs, "train_scenes": args.train_scenes,
                                            "commit": commit(), "machine": machine()},
                               "rows": rows}, indent=2))
    plot(rows, out.with_suffix(".png"))
    print("\n".join(f"{r['task']} {r['policy']} trained {r['train_scenes']}, {r['scenes']} scenes: "
                    f"{100 * r['success_mean']:.1f}% +- {100 * r['success_std']:.1f}" for r in rows))
    print(f"wrote {out} and {out.with_suffix('.png')}")
    return 0


def training_perturbation(meta: dict) -> dict | None:
    """How the training data was perturbed (`hgen dataset perturb`), from the checkpoint's meta or, for a run
    trained before the export carried it, from its zarr's attributes; None for data recorded as planned."""
    if meta.get("perturbation"):
        return dict(meta["perturbation"])
    if not meta.get("data") or not Path(meta["data"]).is_dir():
        return None
    import zarr

    try:
        found = zarr.open_group(str(meta["data"]), mode="r").attrs.get("perturbation")
    except (OSError, ValueError, zarr.errors.BaseZarrError):  # not a zarr (any more): nothing to say
        return None
    return dict(found) if found else None


def _names(text: str) -> tuple[str, ...]:
    return tuple(s.strip() for s in text.split(",") if s.strip())


if __name__ == "__main__":
    sys.exit(main())
