"""Data-collection time per successful episode: without cameras, and recording the six cameras at 320x240
(RGB + depth) plus the 1024-point cloud, at 10 Hz and at the full 50 Hz control rate.

Usage: python bench/collection.py [--task block_stack_single] [--episodes 3]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402

from humanoidgen.episodes.recorder import RecorderConfig  # noqa: E402
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode  # noqa: E402
from humanoidgen.sim.cameras import CAMERA_NAMES  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--task", default="block_stack_single")
    ap.add_argument("--episodes", type=int, default=3)
    args = ap.parse_args()
    configs = {
        "no cameras": None,
        "6 cameras 320x240 + point cloud, 10 Hz": RecorderConfig(every=5, cameras=CAMERA_NAMES, point_cloud=True),
        "6 cameras 320x240 + point cloud, 50 Hz": RecorderConfig(every=1, cameras=CAMERA_NAMES, point_cloud=True),
    }
    for name, rec in configs.items():
        walls, sims, frames = [], [], []
        for i in range(args.episodes):
            t0 = time.perf_counter()
            result, arrays = run_task_episode(EpisodeRequest(args.task, seed=i, recorder=rec))
            if result.success:
                walls.append(time.perf_counter() - t0)
                sims.append(result.sim_seconds)
                frames.append(len(arrays["action"]) if arrays else 0)
        if walls:
            print(f"{name}: {np.mean(walls):.1f} s per successful episode ({len(walls)}/{args.episodes} ok; "
                  f"{np.mean(sims):.1f} s simulated, {np.mean(frames):.0f} frames)")
        else:
            print(f"{name}: no successful episode")


if __name__ == "__main__":
    main()
