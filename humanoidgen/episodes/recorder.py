"""Recording an episode while it runs: every `every`-th control step, the 26-D action, the driven joints,
both end-effector poses, every object's pose, the full simulator configuration (for exact replay), and
optionally images from the six cameras and a fused, cropped, downsampled point cloud."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from humanoidgen.sim.cameras import CAMERA_NAMES, CameraRig
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.geometry import mat_to_quat
from humanoidgen.sim.pointcloud import PointCloudConfig, fuse_point_cloud


@dataclass
class RecorderConfig:
    every: int = 1  # record every n-th control step (50 Hz control, every=2 -> 25 Hz data)
    cameras: tuple[str, ...] = ()  # e.g. CAMERA_NAMES for all six; () records no images
    width: int = 320
    height: int = 240
    depth: bool = True
    point_cloud: bool = False
    point_cloud_cameras: tuple[str, ...] = ("head", "front", "left", "right")
    num_points: int = 1024

    def __post_init__(self) -> None:
        unknown = set(self.cameras) - set(CAMERA_NAMES)
        if unknown:
            raise ValueError(f"unknown cameras {sorted(unknown)}; cameras: {', '.join(CAMERA_NAMES)}")
        if self.every < 1:
            raise ValueError("every must be >= 1")


@dataclass
class EpisodeRecorder:
    env: HumanoidEnv
    config: RecorderConfig = field(default_factory=RecorderConfig)
    frames: dict[str, list] = field(default_factory=dict)
    _count: int = 0

    def __post_init__(self) -> None:
        cams = set(self.config.cameras) | (set(self.config.point_cloud_cameras) if self.config.point_cloud else set())
        self._rig = CameraRig(self.env.model, self.config.width, self.config.height) if cams else None
        self._cams = tuple(c for c in CAMERA_NAMES if c in cams)
        self._pc = PointCloudConfig(num_points=self.config.num_points)

    def close(self) -> None:
        if self._rig is not None:
            self._rig.close()
            self._rig = None

    def __call__(self, action: np.ndarray) -> None:
        """Planner `on_step` hook: called after each control step with the action just applied."""
        self._count += 1
        if (self._count - 1) % self.config.every:
            return
        env = self.env
        rec = self.frames
        rec.setdefault("action", []).append(np.asarray(action, np.float32))
        rec.setdefault("joint_pos", []).append(env.joint_positions().astype(np.float32))
        rec.setdefault("qpos", []).append(env.data.qpos.astype(np.float64).copy())
        rec.setdefault("time", []).append(env.time)
        ee = []
        for side in ("left", "right"):
            p, R = env.hand_pose(side)
            ee.append(np.concatenate([p, mat_to_quat(R)]))
        rec.setdefault("ee_pose", []).append(np.concatenate(ee).astype(np.float32))
        objs = [np.concatenate(env.object_pose(o.body)) for o in env.scene.objects]
        rec.setdefault("object_pose", []).append(np.array(objs, np.float32).reshape(len(objs), 7))
        if self._rig is None:
            return
        frames = {c: self._rig.render(env.data, c, rgb=c in self.config.cameras,
                                      depth=self.config.depth or self.config.point_cloud, segmentation=False)
                  for c in self._cams}
        for c in self.config.cameras:
            rec.setdefault(f"rgb/{c}", []).append(frames[c].rgb)
            if self.config.depth:
                rec.setdefault(f"depth/{c}", []).append(frames[c].depth)
        if self.config.point_cloud:
            views = [(frames[c].depth, frames[c].fovy, frames[c].cam_pos, frames[c].cam_mat, None)
                     for c in self.config.point_cloud_cameras]
            rec.setdefault("point_cloud", []).append(fuse_point_cloud(views, self._pc).astype(np.float32))

    def arrays(self) -> dict[str, np.ndarray]:
        return {k: np.stack(v) for k, v in self.frames.items()}
