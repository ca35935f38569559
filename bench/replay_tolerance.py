"""How much arm-posture error a task's demonstrations tolerate: each kept episode's recorded actions replayed
open-loop in the task's gym environment (the policy's env, at the data's action rate), with a constant offset
drawn per episode and joint (normal, `sigma` rad) added to one arm's joint targets; the share that still passes
the task's predicates, per sigma.

Each replay also tallies what the acting hand rested on: for the thumb and for the other fingers (and palm), the
object geoms they touched and for how many actions (`grips`). close_drawer's grip, for one, holds the handle by its
left post, the thumb on the post's outer face 4.4 cm from the bar's middle: a hand shifted along the bar puts the
thumb past the post, on nothing.

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
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from provenance import commit, machine  # noqa: E402

from humanoidgen.policies.perturb import SETTLE_ACTIONS  # noqa: E402  (the last action held this long more)

ROOT = Path(__file__).resolve().parent


def touching(env, side: str) -> set[tuple[str, str]]:
    """(hand part, object geom) pairs in contact now: "thumb" or "fingers" (any other finger or the palm) of the
    `side` hand against a geom of one of the scene's objects."""
    from humanoidgen.planning.hand_ops import hand_part

    model, data = env.sim.model, env.sim.data
    objects = {model.body(o.body).id for o in env.sim.scene.objects}
    out = set()
    for c in data.contact[: data.ncon]:
        for mine, other in ((c.geom1, c.geom2), (c.geom2, c.geom1)):
            if int(model.body_rootid[model.geom_bodyid[other]]) not in objects:
                continue
            part = hand_part(model, model.geom_bodyid[mine], side)
            if part is not None:
                out.add(("thumb" if part == "thumb" else "fingers", model.geom(other).name))
    return out


def replay(env, actions: np.ndarray, seed: int, side: str = "left", dressing: dict | None = None
           ) -> tuple[bool, str, dict]:
    """One episode's actions, then the last held SETTLE_ACTIONS more: whether the task's predicates passed, what
    they said at the end (how a failed replay failed: for close_drawer, how far the drawer got and how far one hold
    of the handle moved it), and what the `side` hand rested on ({"thumb": {geom: actions}, "fingers": ...}).
    `dressing`: the room and look the episode was collected in (its record's; None: the clean tabletop)."""
    from humanoidgen.policies.rollout import final_detail

    grip: dict[str, Counter] = {"thumb": Counter(), "fingers": Counter()}
    _, info = env.reset(seed=seed, options={"dressing": dressing})
    ok = bool(info.get("success"))
    for a in [] if ok else [*actions, *[actions[-1]] * SETTLE_ACTIONS]:
        _, _, terminated, _, info = env.step(a)
        for part, geom in touching(env, side):
            grip[part][geom] += 1
        if terminated:
            ok = True
            break
    ok = ok or bool(info.get("success"))
    return ok, final_detail(info), {part: dict(c.most_common()) for part, c in grip.items()}


def thumb_summary(grips: list[dict]) -> str:
    """Where the thumb rested longest in each replay, tallied for the passed and the failed ones:
    "drawer_0_handle_post_left (passed 12, failed 1), drawer_0_handle_bar (failed 3)"."""
    tally: dict[str, Counter] = {}
    for g in grips:
        where = max(g["thumb"], key=g["thumb"].get) if g["thumb"] else "nothing"
        tally.setdefault(where, Counter())["passed" if g["passed"] else "failed"] += 1
    return ", ".join(f"{where} ({', '.join(f'{k} {v}' for k, v in sorted(c.items(), reverse=True))})"
                     for where, c in sorted(tally.items(), key=lambda kv: -sum(kv[1].values())))


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
    passed, failed, grips = {}, {}, {}
    try:
        for sigma in sigmas:
            n, failed[sigma], grips[sigma] = 0, [], []
            for k, (rec, action) in enumerate(zip(kept, recorded)):
                actions = action.copy()
                actions[:, arm] += np.random.default_rng(draw_seed + k).normal(0.0, sigma, arm.stop - arm.start)
                ok, detail, grip = replay(env, actions, int(rec["seed"]), side, rec.get("dressing"))
                n += ok
                grips[sigma].append({"seed": int(rec["seed"]), "passed": ok, **grip})
                if not ok:
                    failed[sigma].append({"seed": int(rec["seed"]), "final": detail})
            passed[sigma] = n
            print(f"{meta['task']}: sigma {sigma:g} rad on the {side} arm, {n} of {len(kept)} replays passed; "
                  f"the thumb mostly on {thumb_summary(grips[sigma])}", flush=True)
    finally:
        env.close()
    return {"task": meta["task"], "side": side, "episodes": len(kept), "passed": passed, "failed": failed,
            "grips": grips}


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
