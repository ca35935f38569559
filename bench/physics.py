"""Physics steps per second of the full table scene (robot + one cube) on one core, 2 ms step.

Usage: python bench/physics.py [--seconds 10]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402

from humanoidgen.sim.env import HumanoidEnv  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--seconds", type=float, default=10.0, help="simulated seconds per run")
    args = ap.parse_args()
    b = SceneBuilder()
    b.add_cube()
    t0 = time.perf_counter()
    scene = b.build()
    build_s = time.perf_counter() - t0
    env = HumanoidEnv(scene)
    rng = np.random.default_rng(0)
    n_ctrl = int(args.seconds * env.control_hz)
    # A moving robot (sinusoidal arm and hand targets) exercises contacts and constraints, not just rest.
    base = env.init_action()
    phases = rng.uniform(0, 2 * np.pi, base.size)
    t0 = time.perf_counter()
    for k in range(n_ctrl):
        a = base + 0.15 * np.sin(2 * np.pi * 0.5 * k / env.control_hz + phases)
        env.step(a)
    wall = time.perf_counter() - t0
    steps = n_ctrl * env.n_substeps
    print(f"scene build (compile): {build_s:.2f} s")
    print(f"timestep {scene.model.opt.timestep * 1000:.1f} ms, nq={scene.model.nq}, ngeom={scene.model.ngeom}")
    print(f"physics: {steps / wall:,.0f} steps/s ({steps} steps in {wall:.2f} s, realtime x{args.seconds / wall:.1f})")
    print(f"mujoco {mujoco.__version__}")


if __name__ == "__main__":
    main()
