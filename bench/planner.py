"""Planner speed and reliability on a pick-and-place: the right hand pinches cube 0 and stacks it on cube 1,
over randomized placements. Reports goal-solve time, motion-planning time per move, success rate and the
wall time of an episode (planning plus simulation).

Usage: python bench/planner.py [--episodes 20] [--seed 0]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from test_planner import cube_on_cube, pick_and_place  # noqa: E402  (the same script the tests run)

from humanoidgen.objects.library import add_object
from humanoidgen.planning.planner import HumanoidMotionPlanner, PlanningError  # noqa: E402
from humanoidgen.sim.env import HumanoidEnv  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--episodes", type=int, default=20)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    ok, walls, plan_times, solve_times, sim_seconds, failures = 0, [], [], [], [], []
    for ep in range(args.episodes):
        b = SceneBuilder()
        add_object(b, "cube", 0, pos=(rng.uniform(-0.37, -0.31), rng.uniform(-0.24, -0.14)))
        add_object(b, "cube", 1, pos=(rng.uniform(-0.33, -0.29), rng.uniform(-0.06, 0.0)))
        env = HumanoidEnv(b.build())
        planner = HumanoidMotionPlanner(env, seed=ep)
        t0 = time.perf_counter()
        try:
            pick_and_place(planner)
            success = cube_on_cube(env)
        except PlanningError as exc:
            success = False
            failures.append(str(exc)[:160])
        walls.append(time.perf_counter() - t0)
        ok += success
        plan_times += planner.plan_seconds
        solve_times += [r.solve_time for r in planner.goal_results]
        sim_seconds.append(env.time)
    pt, st = np.array(plan_times) * 1000, np.array(solve_times) * 1000
    print(f"pick-and-place: {ok}/{args.episodes} successful")
    print(f"goal solves: median {np.median(st):.0f} ms, p95 {np.percentile(st, 95):.0f} ms ({len(st)} solves)")
    print(f"motion planning per move: median {np.median(pt):.0f} ms, p95 {np.percentile(pt, 95):.0f} ms ({len(pt)} moves)")
    print(f"episode: {np.mean(walls):.2f} s wall for {np.mean(sim_seconds):.1f} s simulated (planning + physics, no cameras)")
    for f in failures:
        print("  failed:", f)


if __name__ == "__main__":
    main()
