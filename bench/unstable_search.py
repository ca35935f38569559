"""Can the robot's commands alone make a replay go unstable (MuJoCo's auto-reset to qpos0, which shuts every
closing task's drawer, box or laptop; `episodes.replay.BROKEN_WARNINGS`)? A random search, in-process: the
left fingertip at close_drawer's open drawer (the reference plan's first move), then 5 s of commands at the
ends of the ctrlrange, on a random subset of the 26 joints, flipping every 1-5 control steps, from that same
state, for `--seconds` of wall time. Run from the repository root:

    PYTHONPATH=$PWD HGEN_ASSETS=/work/shared/assets python bench/unstable_search.py --seconds 240

Writes bench/results/unstable_search.json: trials, control steps, the largest joint speed seen, any trial that
raised one of the warnings.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import mujoco
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
STATE = mujoco.mjtState.mjSTATE_INTEGRATION


def main() -> None:
    from plan_runs import task_planner

    from humanoidgen.episodes.replay import BROKEN_WARNINGS
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=240.0)
    ap.add_argument("--out", default=str(ROOT / "bench" / "results" / "unstable_search.json"))
    args = ap.parse_args()
    _, env = build_scene(load_task("close_drawer"), 0)
    planner = task_planner(env, seed=0)
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left")
    _, pose = planner.generate_end_effector_pose(c, hand_name="left")
    planner.move_to_pose_with_screw(pose, "left")
    start = np.empty(mujoco.mj_stateSize(env.model, STATE))
    mujoco.mj_getState(env.model, env.data, start, STATE)
    lo, hi = env.clip(np.full(26, -1e3)), env.clip(np.full(26, 1e3))
    rng = np.random.default_rng(1)
    t0, trials, steps, fastest, found = time.time(), 0, 0, 0.0, []
    while time.time() - t0 < args.seconds:
        trials += 1
        mujoco.mj_setState(env.model, env.data, start, STATE)
        base, period = env.joint_positions(), int(rng.integers(1, 6))
        mask = rng.random(26) < rng.uniform(0.2, 1.0)
        for k in range(250):
            a = np.where(mask, np.where((np.arange(26) + (k // period) % 2) % 2 == 0, lo, hi), base)
            env.step(a)
            steps += 1
            fastest = max(fastest, float(np.abs(env.data.qvel).max()))
            if any(env.data.warning[w].number for w in BROKEN_WARNINGS):
                found.append({"trial": trials, "step": k, "period": period, "joints": np.flatnonzero(mask).tolist()})
                mujoco.mj_resetData(env.model, env.data)  # clears the counts for the next trial
                break
    out = {"task": "close_drawer", "seed": 0, "trials": trials, "control_steps": steps,
           "max_joint_speed": round(fastest, 1), "unstable": found, "seconds": args.seconds}
    Path(args.out).write_text(json.dumps(out, indent=1))
    print(json.dumps({k: v for k, v in out.items() if k != "unstable"} | {"unstable": len(found)}))


if __name__ == "__main__":
    main()
