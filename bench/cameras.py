"""Six-camera frame sets per second (RGB + depth + segmentation from each of the six cameras).

Usage: MUJOCO_GL=egl python bench/cameras.py [--width 320 --height 240 --sets 30] [--modalities rgb,depth]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("MUJOCO_GL", "egl")

from humanoidgen.sim.cameras import CameraRig  # noqa: E402
from humanoidgen.sim.env import HumanoidEnv  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--sets", type=int, default=30)
    ap.add_argument("--modalities", default="rgb,depth", help="comma list of rgb, depth, segmentation")
    args = ap.parse_args()
    b = SceneBuilder()
    b.add_cube()
    scene = b.build()
    env = HumanoidEnv(scene)
    mods = set(args.modalities.split(","))
    kw = dict(rgb="rgb" in mods, depth="depth" in mods, segmentation="segmentation" in mods)
    with CameraRig(scene.model, args.width, args.height, scene.geom_labels) as rig:
        rig.render_all(env.data, **kw)  # warm-up: GL context and shaders
        t0 = time.perf_counter()
        for _ in range(args.sets):
            env.step(env.init_action())
            rig.render_all(env.data, **kw)
        wall = time.perf_counter() - t0
    what = "+".join(sorted(mods))
    print(f"{args.width}x{args.height}, {what}: {args.sets / wall:.1f} sets of six per second "
          f"({1000 * wall / args.sets / 6:.1f} ms per camera), MUJOCO_GL={os.environ['MUJOCO_GL']}")


if __name__ == "__main__":
    main()
