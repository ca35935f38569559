"""Reachability of the pinch point with the palm down, over each hand's operable range.

For each side, a grid over OPERABLE_RANGE (x, y) at heights 0.02 / 0.08 / 0.15 m above the table; a target counts
as reachable when `solve_arm_ik_restarts` converges for the pinch point (wrist-yaw frame (0.20, -+0.03, 0), as
tests/test_scene.py PINCH_POINT) with the palm normal within 20 degrees of straight down. Prints the overall
fraction, a table of reachable fractions (rows: x bins, columns: y bins, all heights pooled) and the mean IK time.

Usage: python bench/reach.py [--step 0.03] [--pos-tol 0.005] [--n-random 12]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from humanoidgen.sim.env import HumanoidEnv  # noqa: E402
from humanoidgen.sim.ik import AxisGoal, solve_arm_ik_restarts  # noqa: E402
from humanoidgen.sim.layout import OPERABLE_RANGE, SIDES, Side, palm_normal_on_wrist  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402

PINCH_POINT: dict[Side, np.ndarray] = {"left": np.array([0.20, -0.03, 0.0]), "right": np.array([0.20, 0.03, 0.0])}
HEIGHTS = (0.02, 0.08, 0.15)


def grid(lo: float, hi: float, step: float) -> np.ndarray:
    n = int(np.floor((hi - lo) / step + 1e-9)) + 1
    return lo + step * np.arange(n)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--step", type=float, default=0.03, help="grid spacing in x and y (m)")
    ap.add_argument("--pos-tol", type=float, default=5e-3, help="IK position tolerance (m)")
    ap.add_argument("--n-random", type=int, default=12, help="random IK restarts after the initial-posture seed")
    args = ap.parse_args()
    env = HumanoidEnv(SceneBuilder().build())
    for side in SIDES:
        r = OPERABLE_RANGE[side]
        xs, ys = grid(*r.x, args.step), grid(*r.y, args.step)
        down = (AxisGoal(palm_normal_on_wrist(side), np.array([0.0, 0.0, -1.0]), cone_deg=20.0),)
        ok = np.zeros((len(xs), len(ys), len(HEIGHTS)), bool)
        times = []
        for i, x in enumerate(xs):
            for j, y in enumerate(ys):
                for k, z in enumerate(HEIGHTS):
                    t0 = time.perf_counter()
                    res = solve_arm_ik_restarts(env.model, env.data, side, PINCH_POINT[side], np.array([x, y, z]),
                                                down, seeds=[env.arm_qpos(side)], n_random=args.n_random,
                                                pos_tol=args.pos_tol)
                    times.append(time.perf_counter() - t0)
                    ok[i, j, k] = res.converged
        print(f"\n{side} hand: x {r.x}, y {r.y}, step {args.step} m, heights {HEIGHTS} m, "
              f"{ok.size} targets")
        print(f"  reachable overall: {ok.mean():.2f}  "
              + "  ".join(f"z={z:.2f}: {ok[:, :, k].mean():.2f}" for k, z in enumerate(HEIGHTS)))
        print(f"  IK time: mean {1e3 * np.mean(times):.1f} ms, max {1e3 * np.max(times):.1f} ms")
        print("  x \\ y  " + " ".join(f"{y:+6.2f}" for y in ys) + "    all")
        for i, x in enumerate(xs):
            print(f"  {x:+6.2f} " + " ".join(f"{ok[i, j].mean():6.2f}" for j in range(len(ys)))
                  + f" {ok[i].mean():6.2f}")


if __name__ == "__main__":
    main()
