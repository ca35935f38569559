"""The baselines on every task: the no-op baseline (hold the start posture) and the random baseline (uniform
joint targets, each held 4 actions) within two ranges, the joint limits and the reference plans' action range
(what `hgen policy eval` draws in beside a policy trained on such demonstrations), on the evaluation scenes
(seed s, episode i: scene 100000 + 1000 s + i), at the recordings' 10 Hz and each task's time limit.

A task whose baseline passes more than 10% of its scenes does not measure a policy (issue 37).

The reference plans' range: the actions of the first --demos successful reference-plan episodes on
collection seeds 0, 1, ... (no cameras), cached in --data-root/ranges.json.

    python bench/baselines.py                                   # all tasks, 20 scenes each
    python bench/baselines.py --tasks close_drawer --episodes 20 --seeds 0,1,2 --name close_drawer
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
os.environ.setdefault("MUJOCO_GL", "egl")

ROOT = Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT))
from provenance import commit  # noqa: E402

PASS_LIMIT = 0.10  # a baseline above this share of scenes: the task does not measure a policy


def plan_range(task: str, demos: int, cache: Path) -> dict:
    """{"low", "high", "episodes", "seeds"}: the action range of the first `demos` successful reference-plan
    episodes of `task` (seeds 0, 1, ...), from `cache` when it holds them."""
    import numpy as np

    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    known = json.loads(cache.read_text()) if cache.exists() else {}
    if task in known and known[task]["episodes"] >= demos:
        return known[task]
    actions, seeds, seed = [], [], 0
    while len(seeds) < demos and seed < 4 * demos:
        result, arrays = run_task_episode(EpisodeRequest(task, seed, recorder=RecorderConfig(every=5)), render=False)
        if result.success and arrays is not None:
            actions.append(arrays["action"])
            seeds.append(seed)
        seed += 1
    if not seeds:
        raise RuntimeError(f"{task}: no successful reference-plan episode in {seed} attempts")
    a = np.concatenate(actions)
    known[task] = {"low": a.min(axis=0).tolist(), "high": a.max(axis=0).tolist(), "episodes": len(seeds),
                   "seeds": seeds}
    cache.parent.mkdir(parents=True, exist_ok=True)
    cache.write_text(json.dumps(known, indent=1))
    return known[task]


def measure(task: str, episodes: int, seeds: tuple[int, ...], demos: int, cache: Path) -> list[dict]:
    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.policies.baseline_eval import blind, evaluate_baseline, joint_limits
    from humanoidgen.policies.baselines import ActionRange

    env = HumanoidTaskEnv(task, config=blind(TaskEnvConfig()))
    runs = [("noop", None, "-"), ("random", joint_limits(env), "joint limits")]
    if demos:
        r = plan_range(task, demos, cache)
        runs.append(("random", ActionRange.of(r["low"], r["high"], f"reference plans ({r['episodes']} episodes)"),
                     "reference plans"))
    rows = []
    try:
        for name, action_range, label in runs:
            t0 = time.perf_counter()
            rep = evaluate_baseline(name, task, episodes, seeds, action_range=action_range, progress=False, env=env)
            wins = [o for o in rep.outcomes if o.success]
            rows.append({"task": task, "baseline": name, "range": label, "success_mean": rep.success_mean,
                         "success_std": rep.success_std, "scenes": len(rep.outcomes), "successes": len(wins),
                         "success_scenes": [o.scene_seed for o in wins],
                         "success_steps": [o.steps for o in wins], "success_final": [o.final for o in wins],
                         "seconds": round(time.perf_counter() - t0, 1), "max_steps": env.max_steps})
            print(f"{task:<34} {name:<6} {label:<16} {len(wins):>3}/{len(rep.outcomes)}"
                  f"{'  ABOVE 10%' if rep.success_mean > PASS_LIMIT else ''}  ({rows[-1]['seconds']} s)", flush=True)
    finally:
        env.close()
    return rows


def plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tasks = sorted({r["task"] for r in rows})
    kinds = [("noop", "-"), ("random", "joint limits"), ("random", "reference plans")]
    fig, ax = plt.subplots(figsize=(max(8, 0.5 * len(tasks)), 4.2))
    width = 0.8 / len(kinds)
    for k, (name, label) in enumerate(kinds):
        ys = [next((100 * r["success_mean"] for r in rows if r["task"] == t and r["baseline"] == name
                    and r["range"] == label), 0.0) for t in tasks]
        ax.bar([i + (k - 1) * width for i in range(len(tasks))], ys, width,
               label=name if name == "noop" else f"random ({label})")
    ax.axhline(100 * PASS_LIMIT, color="red", ls="--", lw=1, label="10%")
    ax.set_xticks(range(len(tasks)), tasks, rotation=70, ha="right", fontsize=8)
    ax.set_ylabel("scenes passed (%)")
    ax.set_ylim(0, 100)
    ax.legend(fontsize=8)
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--tasks", help="comma list (default: every task)")
    p.add_argument("--episodes", type=int, default=20, help="scenes per evaluation seed")
    p.add_argument("--seeds", default="0", help="evaluation seeds")
    p.add_argument("--demos", type=int, default=5, help="reference-plan episodes for the action range (0: skip)")
    p.add_argument("--data-root", type=Path, default=Path("data/baselines"))
    p.add_argument("--name", default="", help="results go to bench/results/baselines[_NAME].json and .png")
    args = p.parse_args()

    from humanoidgen.policies.baselines import RANDOM_HOLD_ACTIONS
    from humanoidgen.tasks.registry import task_names

    tasks = [t.strip() for t in args.tasks.split(",")] if args.tasks else task_names()
    seeds = tuple(int(s) for s in args.seeds.split(","))
    rows, t0 = [], time.perf_counter()
    for task in tasks:
        rows += measure(task, args.episodes, seeds, args.demos, args.data_root / "ranges.json")
    stem = "baselines" + (f"_{args.name}" if args.name else "")
    out = ROOT / "results" / f"{stem}.json"
    settings = {"episodes": args.episodes, "seeds": list(seeds), "demos": args.demos, "hold_actions": RANDOM_HOLD_ACTIONS,
                "action_hz": 10, "commit": commit(), "cpu_count": os.cpu_count(), "machine": platform.machine(),
                "minutes": round((time.perf_counter() - t0) / 60, 1)}
    out.parent.mkdir(parents=True, exist_ok=True)
    cache = args.data_root / "ranges.json"
    ranges = {t: r for t, r in json.loads(cache.read_text()).items() if t in tasks} if cache.exists() else {}
    out.write_text(json.dumps({"settings": settings, "rows": rows, "plan_ranges": ranges}, indent=1))
    plot(rows, out.with_suffix(".png"))
    above = sorted({r["task"] for r in rows if r["success_mean"] > PASS_LIMIT})
    print(f"wrote {out} and {out.with_suffix('.png')}; tasks with a baseline above 10%: {', '.join(above) or 'none'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
