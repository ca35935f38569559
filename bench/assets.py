"""Asset library speed: building a table scene with five objects, and answering point/axis queries.

Usage: python bench/assets.py [--queries 10000]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from humanoidgen.objects.library import add_object
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.scene import SceneBuilder

OBJECTS = [("cube", 0), ("cube", 1), ("cup", 0), ("bowl", 0), ("drawer", 0)]


def build() -> tuple[float, HumanoidEnv]:
    t0 = time.perf_counter()
    b = SceneBuilder()
    for k, (name, type_id) in enumerate(OBJECTS):
        add_object(b, name, type_id, pos=(-0.30 if name != "drawer" else -0.05, -0.30 + 0.15 * k))
    scene = b.build()
    return time.perf_counter() - t0, HumanoidEnv(scene)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--queries", type=int, default=10_000)
    args = ap.parse_args()
    cold, _ = build()
    warm = [build()[0] for _ in range(3)]
    _, env = build()
    print(f"scene with {len(OBJECTS)} objects: first build {cold:.2f} s (MuJoCo processes the robot meshes once "
          f"per process), then median {np.median(warm):.2f} s")
    calls = [
        lambda: get_point_in_env(env, "center", "cube", 0),
        lambda: get_point_in_env(env, "pinch_point_base_right_hand"),
        lambda: get_point_in_env(env, "handle_upper", "drawer", 0),
        lambda: get_point_in_env(env, "handle_upper", "drawer", 0, openness=0.7),
        lambda: get_axis_in_env(env, "right_grasp_axis"),
        lambda: get_axis_in_env(env, "x", obj_type="cup", obj_id=0),
        lambda: get_axis_in_env(env, "opening", obj_type="bowl", obj_id=0),
    ]
    t0 = time.perf_counter()
    for i in range(args.queries):
        calls[i % len(calls)]()
    wall = time.perf_counter() - t0
    print(f"{args.queries} point/axis queries: {wall:.2f} s ({1e6 * wall / args.queries:.0f} us each; "
          "queries at an openness simulate the part's pose and cost the most)")


if __name__ == "__main__":
    main()
