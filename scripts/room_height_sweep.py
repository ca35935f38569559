"""Which work-surface heights the reference plans tolerate: the same room with its surface forced to each
height (the robot's base follows the floor), a few tasks and seeds each. Writes JSON.

Usage: python scripts/room_height_sweep.py --tasks block_handover,close_box_hard --seeds 4 --out sweep.json
"""

from __future__ import annotations

import argparse
import json
import os
from dataclasses import replace

os.environ.setdefault("MUJOCO_GL", "egl")


def main() -> None:
    from tqdm import tqdm

    from humanoidgen.episodes.bench import _one
    from humanoidgen.episodes.task_episode import EpisodeRequest
    from humanoidgen.scenes.dressing import SceneDressing
    from humanoidgen.scenes.room import generate_room

    ap = argparse.ArgumentParser()
    ap.add_argument("--tasks", required=True)
    ap.add_argument("--heights", default="0.97,1.00,1.03,1.06,1.09")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--room", type=int, default=0)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    base = generate_room(args.room)
    rows = []
    jobs = [(t, float(h), 1000 + s) for t in args.tasks.split(",") for h in args.heights.split(",")
            for s in range(args.seeds)]
    for task, h, seed in tqdm(jobs, desc="height sweep"):
        room = replace(base, surface_height=h, o_prime=(base.o_prime[0], base.o_prime[1], h))
        out = _one(EpisodeRequest(task, seed, dressing=SceneDressing(room=room).to_dict()))
        rows.append({"task": task, "surface_height": h, "seed": seed, "success": bool(out["success"]),
                     "error": out["error"][:200]})
    summary = {}
    for r in rows:
        summary.setdefault(r["task"], {}).setdefault(f"{r['surface_height']:.3f}", []).append(r["success"])
    result = {"room": args.room, "seeds": args.seeds,
              "success": {t: {h: sum(v) / len(v) for h, v in hs.items()} for t, hs in summary.items()}, "runs": rows}
    with open(args.out, "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps(result["success"], indent=2))


if __name__ == "__main__":
    main()
