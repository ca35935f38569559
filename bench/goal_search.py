"""The planner's goal search (`generate_end_effector_pose`, planning/goal_search.py) on generated grips over the
hands' whole operable ranges: how many goals it finds and how long it takes, with and without its wider rungs
(fingers near the table, the wrist's freedom: `HumanoidMotionPlanner.wider_search`).

For each hand, `--n` scenes with one 4 cm cube at a random position in the hand's operable range (x over the whole
range, the far edge included) and a random yaw in [-30, 30] degrees; the hand pinches it from its annotations. Both
searches run on the same scenes. Prints success and solve time (median, p95, max; successes and failures apart)
and success per x bin.

Usage: python bench/goal_search.py [--n 30] [--seed 0]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from humanoidgen.objects.library import add_object
from humanoidgen.planning.planner import HumanoidMotionPlanner, PlanningError  # noqa: E402
from humanoidgen.sim.env import HumanoidEnv  # noqa: E402
from humanoidgen.sim.layout import OPERABLE_RANGE, SIDES  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402

BINS = np.array([-0.42, -0.34, -0.26, -0.24, -0.22, -0.19])


def solve(side: str, pos: tuple[float, float], yaw: float, wider: bool) -> tuple[bool, float, list[str]]:
    b = SceneBuilder()
    add_object(b, "cube", 0, pos=pos, yaw=yaw)
    env = HumanoidEnv(b.build())
    planner = HumanoidMotionPlanner(env, wider_search=wider)
    planner.hand_pre_pinch(side)
    c = planner.generate_constraints("cube", 0, "pinch", side)
    t0 = time.perf_counter()
    try:
        planner.generate_end_effector_pose(c, side)
        ok = True
    except PlanningError:
        ok = False
    return ok, time.perf_counter() - t0, list(planner.events)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=30, help="scenes per hand")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    print(f"goal search: cube pinches over each hand's whole operable range, seed {args.seed}")
    for side in SIDES:
        r = OPERABLE_RANGE[side]
        scenes = [((float(rng.uniform(*r.x)), float(rng.uniform(*r.y))), float(np.radians(rng.uniform(-30, 30))))
                  for _ in range(args.n)]
        xs = np.array([p[0] for p, _ in scenes])
        for wider in (False, True):
            out = [solve(side, p, yaw, wider) for p, yaw in scenes]
            ok = np.array([o[0] for o in out])
            t = np.array([o[1] for o in out]) * 1000
            turned = sum(any("wrist turned" in e for e in o[2]) for o in out)
            tsucc = t[ok] if ok.any() else np.array([np.nan])
            tfail = t[~ok] if (~ok).any() else np.array([np.nan])
            cells = [f"[{lo:+.2f},{hi:+.2f}) {ok[(xs >= lo) & (xs < hi)].mean() * 100:3.0f}% (n={((xs >= lo) & (xs < hi)).sum()})"
                     for lo, hi in zip(BINS[:-1], BINS[1:]) if ((xs >= lo) & (xs < hi)).any()]
            print(f"{side:5s} {'wider' if wider else 'exact':5s} n={len(ok)} success {ok.mean() * 100:5.1f}% "
                  f"(wrist turned: {turned})  time median {np.median(t):6.0f} ms  p95 {np.percentile(t, 95):6.0f} ms  "
                  f"max {t.max():6.0f} ms | successes median {np.median(tsucc):6.0f} ms | failures median "
                  f"{np.median(tfail):6.0f} ms")
            print("      by x: " + "  ".join(cells))


if __name__ == "__main__":
    main()
