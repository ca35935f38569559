"""The paper's policy study: tasks x numbers of demonstrations x policies, each trained on the first N
episodes of the task's zarr and evaluated closed-loop; a table, a JSON and a plot of success vs demos.

Missing data is collected first (as `hgen collect TASK --cameras head` records: 10 Hz, the head camera,
the fused point cloud; `max(demos)` episodes), then exported (`hgen dataset export --zarr`), into
DATA/<task> and DATA/<task>.zarr; randomized training data (`train_scenes`, as `hgen collect --room random
--randomize-visuals` records it: the scenes evaluation's `randomize` draws) into DATA/<task>_randomized(.zarr),
trained into RUNS/<task>_<policy>_<n>_randomized. A run whose last checkpoint exists is not trained again, and a
row evaluated before (the same checkpoint, scenes, episodes and seeds: RUN/study_rows.jsonl) is not evaluated
again, so an interrupted study continues where it stopped."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

from humanoidgen.policies import checkpoint as ck
from humanoidgen.policies.study_rows import SCENES, rows_from_eval

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
    train_scenes: tuple[str, ...] = ("clean",)  # and/or "randomized": the data each run is trained on
    recipe: str | None = None  # the recipe's name the runs were trained with (for the rows; `overrides` hold it)
    eval_max_steps: int | None = None  # actions per evaluation episode; None: the task's time limit (tests shorten)

    def __post_init__(self) -> None:
        for name in ("scenes", "train_scenes"):
            bad = [s for s in getattr(self, name) if s not in SCENES]
            if bad or not getattr(self, name):
                raise ValueError(f"{name} must be a non-empty list of {', '.join(SCENES)}; got {getattr(self, name)}")


def collect_dressing(scenes: str) -> dict:
    """`collect`'s dressing arguments for training data of `scenes`: randomized data is drawn as evaluation's
    randomized scenes are (`scenes.dressing.RANDOMIZED`), each episode from its own seed."""
    from humanoidgen.scenes.dressing import RANDOMIZED

    return dict(RANDOMIZED) if scenes == "randomized" else {"room": None, "randomize_visuals": False}


def data_name(task: str, scenes: str) -> str:
    """The data's folder and zarr name under DATA (and the run's suffix): <task> or <task>_randomized."""
    return task if scenes == "clean" else f"{task}_{scenes}"


def _collect_child(task: str, n: int, folder: str, workers: int, resume: bool, progress: bool,
                   scenes: str = "clean") -> None:
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.recorder import RecorderConfig

    rec = RecorderConfig(every=5, cameras=("head",), point_cloud=True)
    stats = collect(task, n, Path(folder), workers=workers, resume=resume, recorder=rec,
                    progress=(lambda k, t: print(f"\rcollect {task} ({scenes}): kept {k}/{n}, tried {t}", end="",
                                                 flush=True)) if progress else None, **collect_dressing(scenes))
    if progress:
        print(flush=True)
    if stats.kept < n:
        raise SystemExit(f"collected only {stats.kept} of {n} episodes of {task} in {stats.tried} attempts")


def ensure_data(task: str, n: int, cfg: StudyConfig, progress: bool = True, scenes: str = "clean") -> Path:
    """DATA/<task>.zarr (randomized scenes: DATA/<task>_randomized.zarr) with at least n episodes, collecting
    and exporting what is missing.

    The collection runs in a child process: its renderer loads Mesa's LLVM (llvmpipe), and torch's triton,
    which diffusers imports, brings another LLVM that crashes the process (a segfault in libc) when it is loaded
    after Mesa's. The child keeps the rendering out of the process that trains."""
    import zarr

    from humanoidgen.episodes.dataset import EpisodeStore, export_zarr

    out = Path(cfg.data_root) / f"{data_name(task, scenes)}.zarr"
    if out.exists() and zarr.open_group(str(out), mode="r")["meta/episode_ends"].shape[0] >= n:
        return out
    folder = Path(cfg.data_root) / data_name(task, scenes)
    store = EpisodeStore(folder)
    have = len(store.kept()) if store.meta_path.exists() else 0
    if have < n:
        args = json.dumps([task, n, str(folder), cfg.collect_workers, store.meta_path.exists(), progress, scenes])
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
        for trained_on in cfg.train_scenes:
            data = ensure_data(task, max(cfg.demos), cfg, progress, trained_on)
            for policy in cfg.policies:
                for n in cfg.demos:
                    over = _with(cfg.overrides.get(policy, {}), {"train": {"episodes": n}})
                    run = Path(cfg.runs_root) / data_name(f"{task}_{policy}_{n}", trained_on)
                    result = None
                    if not _finished(run, over.get("train", {}).get("epochs")):
                        result = train(policy, data, run, over, device=cfg.device,
                                       resume=(run / ck.LATEST).exists(), progress=progress)
                        if result.interrupted:
                            raise KeyboardInterrupt
                    last = ck.run_checkpoints(run)[-1]
                    for scenes in cfg.scenes:
                        key = _eval_key(cfg, last, scenes)
                        row = _stored_row(run, key)
                        if row is None:
                            row = _evaluated_row(cfg, task, n, run, last, result, scenes, trained_on, progress)
                            _store_row(run, key, row)
                        rows.append({**row, "train_scenes": trained_on})
                        if progress:
                            print(format_row(rows[-1]), flush=True)
    return rows


def _evaluated_row(cfg: StudyConfig, task: str, n: int, run: Path, last: Path, result, scenes: str,
                   trained_on: str, progress: bool = True) -> dict:
    """One row of the study: the run's last checkpoint evaluated on `scenes` (clean or randomized), built as a
    saved report's rows are (`study_rows.rows_from_eval`), with the training's figures beside it."""
    from humanoidgen.policies.eval import evaluate

    t0 = time.perf_counter()
    report = evaluate(run, task, cfg.eval_episodes, cfg.eval_seeds, checkpoints=[last], device=cfg.device,
                      progress=progress, baselines=cfg.baselines, randomize=scenes == "randomized",
                      max_steps=cfg.eval_max_steps)
    state = ck.read(run / ck.LATEST)
    (row,) = rows_from_eval(report.to_dict(), n, cfg.recipe, int(state["epoch"]), trained_on)
    return {**row, "final_loss": float(state["losses"][-1]),
            "train_seconds": result.seconds if result else None,
            "seconds_per_epoch": result.seconds_per_epoch if result else None,
            "eval_seconds": time.perf_counter() - t0}


EVALUATED = "study_rows.jsonl"  # in each run: the rows evaluated so far, each under the key that made it


def _eval_key(cfg: StudyConfig, last: Path, scenes: str) -> dict:
    """What decides an evaluated row: the checkpoint, the scenes and how many, the baselines, the episode length."""
    return {"checkpoint": Path(last).name, "scenes": scenes, "episodes": cfg.eval_episodes,
            "seeds": list(cfg.eval_seeds), "baselines": cfg.baselines, "max_steps": cfg.eval_max_steps}


def _stored_row(run: Path, key: dict) -> dict | None:
    """The row a previous study evaluated under `key` (an interrupted study does not evaluate it again), or None."""
    path = Path(run) / EVALUATED
    if not path.exists():
        return None
    for line in path.read_text().splitlines():
        try:
            item = json.loads(line)
        except json.JSONDecodeError:  # a line cut short by an interruption
            continue
        if item.get("key") == key:
            return item["row"]
    return None


def _store_row(run: Path, key: dict, row: dict) -> None:
    path = Path(run) / EVALUATED
    cut = path.exists() and not path.read_text().endswith("\n")  # a line cut short stays a line of its own
    with open(path, "a") as f:
        f.write(("\n" if cut else "") + json.dumps({"key": key, "row": row}) + "\n")


def format_row(r: dict) -> str:
    train = f"{r['train_seconds'] / 60:.1f} min ({r['seconds_per_epoch']:.1f} s/epoch)" if r["train_seconds"] else "-"
    base = "".join(f"  {k[len('baseline_'):]} {100 * v:.0f}%" for k, v in r.items()
                   if k.startswith("baseline_") and isinstance(v, float))
    scenes = f" {r['scenes']:<10}" if "scenes" in r else ""
    if "train_scenes" in r:
        scenes = f" trained {r['train_scenes']:<10} evaluated{scenes}"
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
    """Success per task: against the number of demonstrations, or, where the rows have one number, bars of each
    training (clean or randomized data) evaluated clean and randomized beside the baselines on those scenes."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot written")
        return False
    tasks = sorted({r["task"] for r in rows})
    bars = len({r["demos"] for r in rows}) == 1
    fig, axes = plt.subplots(1, len(tasks), figsize=((5.2 if bars else 4) * len(tasks), 3.6), squeeze=False)
    for ax, task in zip(axes[0], tasks):
        (_bars if bars else _lines)(ax, [r for r in rows if r["task"] == task])
        ax.set_title(task)
        ax.set_ylim(-5, 105)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("success (%)")
    axes[0][-1].legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def _lines(ax, rows: list[dict]) -> None:
    """Success vs demonstrations, one line per policy, training data and evaluation scenes."""
    for policy, trained in sorted({(r["policy"], r.get("train_scenes", "clean")) for r in rows}):
        for scenes, style in (("clean", "-"), ("randomized", "--")):
            pts = sorted((r["demos"], 100 * r["success_mean"], 100 * r["success_std"]) for r in rows
                         if r["policy"] == policy and r.get("train_scenes", "clean") == trained
                         and r.get("scenes", "clean") == scenes)
            if not pts:
                continue
            xs, ys, es = zip(*pts)
            label = policy.upper() + ("" if trained == "clean" else " trained randomized") + (
                " randomized" if scenes == "randomized" else "")
            ax.errorbar(xs, ys, yerr=es, marker="o", capsize=3, ls=style, label=label)
    for name, style in (("random", "--"), ("noop", ":")):
        vals = [100 * r[f"baseline_{name}"] for r in rows if f"baseline_{name}" in r]
        if vals:  # the baselines on the same scenes, the most any row saw
            ax.axhline(max(vals), color="grey", ls=style, lw=1, label=f"{name} baseline")
    ax.set_xlabel("demonstrations")


def _bars(ax, rows: list[dict]) -> None:
    """One group per (policy, training data) and per baseline; in each a bar per evaluation scenes."""
    groups = sorted({(r["policy"], r.get("train_scenes", "clean")) for r in rows})
    names = [n for n in ("random", "noop") if any(f"baseline_{n}" in r for r in rows)]
    labels = [f"{p.upper()}\ntrained {t}" for p, t in groups] + [f"{n}\nbaseline" for n in names]
    for k, (scenes, colour) in enumerate((("clean", "C0"), ("randomized", "C1"))):
        on = [r for r in rows if r.get("scenes", "clean") == scenes]
        if not on:
            continue
        ys, es = [], []
        for p, t in groups:
            hit = [r for r in on if r["policy"] == p and r.get("train_scenes", "clean") == t]
            ys.append(100 * hit[0]["success_mean"] if hit else float("nan"))
            es.append(100 * hit[0]["success_std"] if hit else 0.0)
        for n in names:  # the most any row saw on these scenes (each row's random range is its own data's)
            best = max((r for r in on if f"baseline_{n}" in r), key=lambda r: r[f"baseline_{n}"], default=None)
            ys.append(100 * best[f"baseline_{n}"] if best else float("nan"))
            es.append(100 * best.get("baselines", {}).get(n, {}).get("success_std", 0.0) if best else 0.0)
        xs = [i + (k - 0.5) * 0.38 for i in range(len(labels))]
        ax.bar(xs, ys, 0.38, yerr=es, capsize=3, color=colour, label=f"evaluated {scenes}")
        for x, y in zip(xs, ys):
            if y == y:  # not NaN
                ax.text(x, y + 2, f"{y:.0f}", ha="center", fontsize=7)
    ax.set_xticks(range(len(labels)), labels, fontsize=8)
    ax.set_xlabel(f"{rows[0]['demos']} demonstrations")


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
