"""The paper's policy study: tasks x numbers of demonstrations x policies, each trained on the first N
episodes of the task's zarr and evaluated closed-loop; a table, a JSON and a plot of success vs demos.

Missing data is collected first (as `hgen collect TASK --cameras head` records: 10 Hz, the head camera,
the fused point cloud; `max(demos)` episodes), then exported (`hgen dataset export --zarr`), into
DATA/<task> and DATA/<task>.zarr. A run whose last checkpoint exists is
not trained again, so an interrupted study continues where it stopped."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

from humanoidgen.policies import checkpoint as ck

PAPER_TASKS = ("block_handover", "blocks_stack_easy", "close_box_easy", "close_drawer", "close_laptop_easy",
               "cup_pour_easy", "dual_bottles_pick_easy", "open_box_easy", "open_drawer", "open_laptop_easy",
               "pyramid_stack", "block_stack_single", "empty_cup_place", "handover_and_storage")


@dataclass
class StudyConfig:
    tasks: tuple[str, ...] = PAPER_TASKS
    demos: tuple[int, ...] = (20, 50, 100)
    policies: tuple[str, ...] = ("dp", "dp3")
    data_root: Path = Path("data/policy_study")
    runs_root: Path = Path("runs/policy_study")
    overrides: dict[str, dict] = field(default_factory=dict)  # per policy, as `policy_type(..).config(...)` takes
    eval_episodes: int = 20
    eval_seeds: tuple[int, ...] = (0, 1, 2)
    device: str = "auto"
    collect_workers: int = 1
    baselines: bool = True  # the random and noop baselines on each row's scenes (`baseline_eval`)
    scenes: tuple[str, ...] = ("clean",)  # and/or "randomized": each run evaluated on each, one row per
    recipe: str | None = None  # the recipe's name the runs were trained with (for the rows; `overrides` hold it)


def _collect_child(task: str, n: int, folder: str, workers: int, resume: bool, progress: bool) -> None:
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.recorder import RecorderConfig

    rec = RecorderConfig(every=5, cameras=("head",), point_cloud=True)
    stats = collect(task, n, Path(folder), workers=workers, resume=resume, recorder=rec,
                    progress=(lambda k, t: print(f"\rcollect {task}: kept {k}/{n}, tried {t}", end="",
                                                 flush=True)) if progress else None)
    if progress:
        print(flush=True)
    if stats.kept < n:
        raise SystemExit(f"collected only {stats.kept} of {n} episodes of {task} in {stats.tried} attempts")


def ensure_data(task: str, n: int, cfg: StudyConfig, progress: bool = True) -> Path:
    """DATA/<task>.zarr with at least n episodes, collecting and exporting what is missing.

    The collection runs in a child process: its renderer loads Mesa's LLVM (llvmpipe), and torch's triton,
    which diffusers imports, brings another LLVM that crashes the process (a segfault in libc) when it is loaded
    after Mesa's. The child keeps the rendering out of the process that trains."""
    import zarr

    from humanoidgen.episodes.dataset import EpisodeStore, export_zarr

    out = Path(cfg.data_root) / f"{task}.zarr"
    if out.exists() and zarr.open_group(str(out), mode="r")["meta/episode_ends"].shape[0] >= n:
        return out
    folder = Path(cfg.data_root) / task
    store = EpisodeStore(folder)
    have = len(store.kept()) if store.meta_path.exists() else 0
    if have < n:
        args = json.dumps([task, n, str(folder), cfg.collect_workers, store.meta_path.exists(), progress])
        code = f"import json; from humanoidgen.policies.bench import _collect_child; _collect_child(*json.loads({args!r}))"
        child = subprocess.run([sys.executable, "-c", code], stderr=subprocess.PIPE, text=True)
        if child.returncode != 0:
            lines = child.stderr.strip().splitlines()
            raise RuntimeError(f"collecting {task} failed: {lines[-1] if lines else f'exit code {child.returncode}'}")
    export_zarr(EpisodeStore(folder), out)
    return out


def run_study(cfg: StudyConfig, progress: bool = True) -> list[dict]:
    from humanoidgen.policies.train import train

    rows = []
    for task in cfg.tasks:
        data = ensure_data(task, max(cfg.demos), cfg, progress)
        for policy in cfg.policies:
            for n in cfg.demos:
                over = _with(cfg.overrides.get(policy, {}), {"train": {"episodes": n}})
                run = Path(cfg.runs_root) / f"{task}_{policy}_{n}"
                result = None
                if not _finished(run, over.get("train", {}).get("epochs")):
                    result = train(policy, data, run, over, device=cfg.device, resume=(run / ck.LATEST).exists(),
                                   progress=progress)
                    if result.interrupted:
                        raise KeyboardInterrupt
                last = ck.run_checkpoints(run)[-1]
                for scenes in cfg.scenes:
                    row = _evaluated_row(cfg, task, policy, n, run, last, result, scenes, progress)
                    rows.append(row)
                    if progress:
                        print(format_row(row), flush=True)
    return rows


def _evaluated_row(cfg: StudyConfig, task: str, policy: str, n: int, run: Path, last: Path, result,
                   scenes: str, progress: bool = True) -> dict:
    """One row of the study: the run's last checkpoint evaluated on `scenes` (clean or randomized)."""
    from humanoidgen.policies.eval import evaluate

    t0 = time.perf_counter()
    report = evaluate(run, task, cfg.eval_episodes, cfg.eval_seeds, checkpoints=[last], device=cfg.device,
                      progress=progress, baselines=cfg.baselines, randomize=scenes == "randomized")
    state = ck.read(run / ck.LATEST)
    return {"task": task, "policy": policy, "demos": n, "scenes": scenes,
            "recipe": cfg.recipe,
            "success_mean": report.success_mean,
            "success_std": report.success_std, "rates": [r["success"] for r in report.to_dict()["rates"]],
            "epochs": int(state["epoch"]), "final_loss": float(state["losses"][-1]),
            "train_seconds": result.seconds if result else None,
            "seconds_per_epoch": result.seconds_per_epoch if result else None,
            "eval_seconds": time.perf_counter() - t0, "checkpoint": str(last),
            "episodes": [{"seed": o.seed, "scene_seed": o.scene_seed, "success": o.success,
                          "steps": o.steps, "final": o.final} for o in report.outcomes],
            **baseline_columns(report)}


def baseline_columns(report) -> dict:
    """A row's baseline columns: baseline_<name> (success mean on the row's scenes) and their details."""
    out: dict = {f"baseline_{name}": b.success_mean for name, b in report.baselines.items()}
    if report.baselines:
        out["baselines"] = {name: {"success_mean": b.success_mean, "success_std": b.success_std,
                                   "rates": [r["success"] for r in b.to_dict()["rates"]], **b.info,
                                   "successes": [o.scene_seed for o in b.outcomes if o.success]}
                            for name, b in report.baselines.items()}
    return out


def format_row(r: dict) -> str:
    train = f"{r['train_seconds'] / 60:.1f} min ({r['seconds_per_epoch']:.1f} s/epoch)" if r["train_seconds"] else "-"
    base = "".join(f"  {k[len('baseline_'):]} {100 * v:.0f}%" for k, v in r.items()
                   if k.startswith("baseline_") and isinstance(v, float))
    scenes = f" {r['scenes']:<10}" if "scenes" in r else ""
    return (f"{r['task']:<24} {r['policy']:<4} {r['demos']:>4} demos{scenes}  success {100 * r['success_mean']:5.1f}% "
            f"+- {100 * r['success_std']:4.1f}  train {train}  loss {r['final_loss']:.4f}"
            + (f"  baselines:{base}" if base else ""))


def write_results(rows: list[dict], cfg: StudyConfig, json_path: Path, plot_path: Path | None,
                  settings: dict | None = None) -> None:
    json_path.parent.mkdir(parents=True, exist_ok=True)
    meta = {k: (str(v) if isinstance(v, Path) else v) for k, v in asdict(cfg).items()}
    json_path.write_text(json.dumps({"settings": {**meta, **(settings or {})}, "rows": rows}, indent=2))
    if plot_path is not None:
        plot(rows, plot_path)


def plot(rows: list[dict], path: Path) -> bool:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot written")
        return False
    tasks = sorted({r["task"] for r in rows})
    fig, axes = plt.subplots(1, len(tasks), figsize=(4 * len(tasks), 3.4), squeeze=False)
    for ax, task in zip(axes[0], tasks):
        for policy in sorted({r["policy"] for r in rows if r["task"] == task}):
            for scenes, style in (("clean", "-"), ("randomized", "--")):
                pts = sorted((r["demos"], 100 * r["success_mean"], 100 * r["success_std"]) for r in rows
                             if r["task"] == task and r["policy"] == policy and r.get("scenes", "clean") == scenes)
                if not pts:
                    continue
                xs, ys, es = zip(*pts)
                label = policy.upper() + (" randomized" if scenes == "randomized" else "")
                ax.errorbar(xs, ys, yerr=es, marker="o", capsize=3, ls=style, label=label)
        for name, style in (("random", "--"), ("noop", ":")):
            vals = [100 * r[f"baseline_{name}"] for r in rows if r["task"] == task and f"baseline_{name}" in r]
            if vals:  # the baselines on the same scenes, the most any row saw
                ax.axhline(max(vals), color="grey", ls=style, lw=1, label=f"{name} baseline")
        ax.set_title(task)
        ax.set_xlabel("demonstrations")
        ax.set_ylim(-5, 105)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("success (%)")
    axes[0][-1].legend()
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def _finished(run: Path, epochs: int | None = None) -> bool:
    """Whether the run has trained all its epochs: its own, or `epochs` where the study asks for more (a run of
    18 epochs asked again with 40 resumes and trains 22 more instead of being evaluated as it is)."""
    latest = run / ck.LATEST
    if not latest.exists():
        return False
    state = ck.read(latest)
    return int(state["epoch"]) >= max(int(state["config"]["train"]["epochs"]), int(epochs or 0))


def _with(base: dict, extra: dict) -> dict:
    out = dict(base)
    for k, v in extra.items():
        out[k] = _with(out.get(k, {}), v) if isinstance(v, dict) else v
    return out
