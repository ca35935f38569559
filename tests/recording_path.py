"""A fixed path for recording tests: the robot at its table with one cube, the arms swinging through a set
joint-space path (no planner, so the path depends only on the simulator). `tests/data/recording_reference.npz`
holds what the recorder wrote for this path before recording moved to replaying the physics (issue 14):
every state array in full and three frames of images, depth and point cloud."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402

from humanoidgen.episodes.recorder import RecorderConfig  # noqa: E402
from humanoidgen.sim.action import ARM_SLICE, HAND_SLICE  # noqa: E402
from humanoidgen.sim.pointcloud import TABLE_CLOUD_FLOOR  # noqa: E402

STEPS = 60
SETTLE_STEPS = 15
REFERENCE_FRAMES = (0, 6, 11)
# The reference's clouds were recorded with the table's surface in them (before `point_cloud_floor`).
CONFIG = dict(every=5, cameras=("head", "front", "left_wrist"), width=64, height=48, point_cloud=True,
              num_points=256, point_cloud_floor=TABLE_CLOUD_FLOOR)


def recorder_config(**kw) -> RecorderConfig:
    return RecorderConfig(**{**CONFIG, **kw})


def path_env():
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder

    builder = SceneBuilder()
    builder.add_cube()
    env = HumanoidEnv(builder.build())
    for _ in range(SETTLE_STEPS):
        env.step(env.init_action())
    return env


def path_actions(env) -> list[np.ndarray]:
    """Arm joints swing by up to 0.35 rad on smooth sines; the hands half close and open again."""
    base = env.init_action()
    out = []
    for k in range(STEPS):
        a = base.copy()
        s = np.sin(np.pi * k / STEPS)
        a[ARM_SLICE["left"]] += 0.35 * s * np.array([-1.0, 0.5, 0.3, 0.6, 0.2, -0.3, 0.1])
        a[ARM_SLICE["right"]] += 0.30 * s * np.array([-1.0, -0.5, -0.3, 0.6, -0.2, 0.3, -0.1])
        a[HAND_SLICE["right"]] += 0.5 * s
        out.append(a)
    return out
