"""Goal-pose solver (planning/goal_solver.py) on random palm-down grasp targets, collision constraints on.

For each hand: `--n` random targets for the grasp point (`grasp_point_base_<side>_hand`) at 0.05-0.15 m above
the table, with the palm down (`<side>_grasp_axis` parallel to (0, 0, -1)); hard point2point + parallel,
collisions against the table, the torso and the other arm. Two samples per hand:

- "reachable": x in [-0.42, -0.26], y over the hand's operable range (the palm-down reach ends near x = -0.24);
- "full range": x over the whole operable range [-0.42, -0.19], same y and heights.

Prints, per hand and sample: success rate, median / p95 / max solve time (all solves, and successful ones),
the reasons of failures, and for the full range the success rate per x bin. Successes are checked with an
independent forward kinematics (fresh MjData): a success whose grasp point is more than 2 mm or whose palm is
more than 1 degree off is counted as "bad success".

Usage: python bench/goal_solver.py [--n 200] [--seed 0]
"""

from __future__ import annotations

import argparse
import os
import time
from collections import Counter

os.environ.setdefault("OMP_NUM_THREADS", "1")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402

from humanoidgen.objects.hands import hand_axes, hand_points  # noqa: E402
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env  # noqa: E402
from humanoidgen.planning.collision import CollisionWorld  # noqa: E402
from humanoidgen.planning.constraints import Constraint  # noqa: E402
from humanoidgen.planning.goal_solver import GoalSolver  # noqa: E402
from humanoidgen.planning.kinematics import Kinematics  # noqa: E402
from humanoidgen.sim.env import HumanoidEnv  # noqa: E402
from humanoidgen.sim.layout import ARM_JOINTS, HAND_BASE_FRAME, OPERABLE_RANGE, SIDES, WRIST_BODY  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402

REACH_X = (-0.42, -0.26)
HEIGHTS = (0.05, 0.15)
DOWN = np.array([0.0, 0.0, -1.0])


def fk_check(env: HumanoidEnv, side: str, q: np.ndarray, target: np.ndarray) -> tuple[float, float]:
    """Grasp-point error (m) and palm angle from straight down (deg), from a fresh MjData."""
    m = env.model
    d = mujoco.MjData(m)
    d.qpos[:] = env.data.qpos
    for name, v in zip(ARM_JOINTS[side], q):
        d.qpos[m.jnt_qposadr[m.joint(name).id]] = v
    mujoco.mj_kinematics(m, d)
    b = m.body(WRIST_BODY[side]).id
    p, R = d.xpos[b], d.xmat[b].reshape(3, 3)
    err = float(np.linalg.norm(p + R @ hand_points(side)[f"grasp_point_base_{side}_hand"] - target))
    a = R @ hand_axes(side)[f"{side}_grasp_axis"]
    return err, float(np.degrees(np.arccos(np.clip(a @ DOWN, -1.0, 1.0))))


def run(env: HumanoidEnv, solver: GoalSolver, side: str, xr: tuple[float, float], n: int,
        rng: np.random.Generator) -> dict:
    yr = OPERABLE_RANGE[side].y
    frame = HAND_BASE_FRAME[side]
    hand_p = get_point_in_env(env, f"grasp_point_base_{side}_hand")
    hand_a = get_axis_in_env(env, f"{side}_grasp_axis")
    q0 = env.arm_qpos(side)
    times, ok, xs, reasons, bad = [], [], [], Counter(), 0
    for _ in range(n):
        target = np.array([rng.uniform(*xr), rng.uniform(*yr), rng.uniform(*HEIGHTS)])
        cons = [Constraint(env, "point2point", frame, hand_key_point=hand_p, object_key_point=target),
                Constraint(env, "parallel", frame, hand_axis=hand_a, object_axis=DOWN)]
        t0 = time.perf_counter()
        r = solver.solve(side, cons, q0, q0)
        times.append(time.perf_counter() - t0)
        ok.append(r.success)
        xs.append(target[0])
        if r.success:
            err, ang = fk_check(env, side, r.q, target)
            bad += err > 2e-3 or ang > 1.0
        else:
            for v in r.violations:
                reasons[v.split(":")[0] + (": " + v.split(" with ")[1].split(" ")[0] if v.startswith("collision") else "")] += 1
    return dict(times=np.array(times), ok=np.array(ok), xs=np.array(xs), reasons=reasons, bad=bad)


def report(side: str, label: str, res: dict, bins: np.ndarray | None = None) -> None:
    t, ok = res["times"] * 1000, res["ok"]
    ts = t[ok] if ok.any() else np.array([np.nan])
    print(f"{side:5s} {label:10s}  n={len(ok)}  success {ok.mean() * 100:5.1f}%  "
          f"time median {np.median(t):6.1f} ms  p95 {np.percentile(t, 95):6.1f} ms  max {t.max():6.0f} ms  "
          f"| successes: median {np.median(ts):5.1f} ms  p95 {np.percentile(ts, 95):5.1f} ms  "
          f"| bad successes {res['bad']}")
    if res["reasons"]:
        print("      failures: " + ", ".join(f"{k} x{v}" for k, v in res["reasons"].most_common()))
    if bins is not None:
        cells = []
        for lo, hi in zip(bins[:-1], bins[1:]):
            sel = (res["xs"] >= lo) & (res["xs"] < hi + 1e-12)
            if sel.any():
                cells.append(f"[{lo:+.2f},{hi:+.2f}) {ok[sel].mean() * 100:3.0f}% (n={sel.sum()})")
        print("      by x: " + "  ".join(cells))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=200, help="targets per hand and sample")
    ap.add_argument("--seed", type=int, default=0, help="seed of the random targets")
    args = ap.parse_args()

    env = HumanoidEnv(SceneBuilder().build())
    kin = Kinematics(env.model)
    kin.sync(env.data.qpos)
    solver = GoalSolver(kin, CollisionWorld(kin))
    rng = np.random.default_rng(args.seed)
    print(f"goal solver: palm-down grasp-point targets, heights {HEIGHTS[0]}-{HEIGHTS[1]} m, collisions on, "
          f"seed {args.seed}")
    for side in SIDES:
        full_x = OPERABLE_RANGE[side].x
        report(side, "reachable", run(env, solver, side, REACH_X, args.n, rng))
        report(side, "full range", run(env, solver, side, full_x, args.n, rng),
               bins=np.array([-0.42, -0.38, -0.34, -0.30, -0.26, -0.24, -0.22, -0.19]))


if __name__ == "__main__":
    main()
