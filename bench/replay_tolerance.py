"""How much arm-posture error a task's demonstrations tolerate: each kept episode's recorded actions replayed
open-loop in the task's gym environment (the policy's env, at the data's action rate), with a constant offset
drawn per episode and joint (normal, `sigma` rad) added to one arm's joint targets; the share that still passes
the task's predicates, per sigma.

A trained policy's posture error is of this kind (a few hundredths of a radian, steady over a move); a task whose
replays fail at an error the policies of other tasks make is one that asks for more precision than the data
teaches. Measured on close_drawer against open_box_easy (docs/results/policies.md).

    python bench/replay_tolerance.py data/close_drawer --side left --sigmas 0,0.01,0.02,0.04 --episodes 16
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from provenance import commit, machine  # noqa: E402

ROOT = Path(__file__).resolve().parent
SETTLE_ACTIONS = 20  # the last action held this long more: a drawer still sliding shut may yet pass


def replay(env, actions: np.ndarray, seed: int) -> tuple[bool, str]:
    """One episode's actions, then the last held SETTLE_ACTIONS more: whether the task's predicates passed, and
    what they said at the end (how a failed replay failed: for close_drawer, how far the drawer got and how far
    one hold of the handle moved it)."""
    from humanoidgen.policies.rollout import final_detail

    _, info = env.reset(seed=seed)
    if info.get("success"):
        return True, final_detail(info)
    for a in [*actions, *[actions[-1]] * SETTLE_ACTIONS]:
        _, _, terminated, _, info = env.step(a)
        if terminated:
            return True, final_detail(info)
    return bool(info.get("success")), final_detail(info)


def tolerance(folder: Path, side: str, sigmas: list[float], episodes: int, draw_seed: int = 1000) -> dict:
    """{"task", "episodes", "passed": {sigma: n}} over the first `episodes` kept episodes of the store."""
    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.sim.action import ARM_SLICE

    store = EpisodeStore(folder)
    meta = json.loads(store.meta_path.read_text())
    kept = store.kept()[:episodes]
    if not kept:
        raise SystemExit(f"error: {folder} has no kept episodes")
    cfg = TaskEnvConfig.from_recorder(dict(meta.get("recorder") or {}), meta.get("control_hz", 50.0), cameras=(),
                                      depth=False, point_cloud=False)
    env = HumanoidTaskEnv(meta["task"], config=cfg)
    arm = ARM_SLICE[side]
    # each episode's actions read once (and nothing else of it: its pictures are most of the file)
    recorded = [np.asarray(store.load(rec["episode"], ("action",))["action"], dtype=np.float64) for rec in kept]
    passed, failed = {}, {}
    try:
        for sigma in sigmas:
            n, failed[sigma] = 0, []
            for k, (rec, action) in enumerate(zip(kept, recorded)):
                actions = action.copy()
                actions[:, arm] += np.random.default_rng(draw_seed + k).normal(0.0, sigma, arm.stop - arm.start)
                ok, detail = replay(env, actions, int(rec["seed"]))
                n += ok
                if not ok:
                    failed[sigma].append({"seed": int(rec["seed"]), "final": detail})
            passed[sigma] = n
            print(f"{meta['task']}: sigma {sigma:g} rad on the {side} arm, {n} of {len(kept)} replays passed",
                  flush=True)
    finally:
        env.close()
    return {"task": meta["task"], "side": side, "episodes": len(kept), "passed": passed, "failed": failed}


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("data", type=Path, nargs="+", help="collected episode folders (hgen collect --out)")
    p.add_argument("--side", default="left", help="the arm offset: left or right (one per folder, comma list)")
    p.add_argument("--sigmas", default="0,0.01,0.02,0.04", help="offset scales (rad), comma list")
    p.add_argument("--episodes", type=int, default=16, help="kept episodes replayed per folder")
    p.add_argument("--name", default="replay_tolerance", help="results go to bench/results/<name>.json")
    args = p.parse_args()
    sides = [s.strip() for s in args.side.split(",")]
    if len(sides) == 1:
        sides *= len(args.data)
    if len(sides) != len(args.data) or any(s not in ("left", "right") for s in sides):
        print("error: --side is left or right, one for all folders or one per folder", file=sys.stderr)
        return 2
    sigmas = [float(s) for s in args.sigmas.split(",")]
    t0 = time.perf_counter()
    head = commit()  # the code that runs, read before it does
    rows = [tolerance(folder, side, sigmas, args.episodes) for folder, side in zip(args.data, sides)]
    out = ROOT / "results" / f"{args.name}.json"
    out.write_text(json.dumps({"commit": head, "machine": machine(), "sigmas": sigmas,
                               "data": [str(d) for d in args.data], "minutes": round((time.perf_counter() - t0) / 60, 1),
                               "rows": rows}, indent=1))
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
