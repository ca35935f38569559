"""Recording an episode: while it runs, every `every`-th control step, the 26-D action, the driven joints,
both end-effector poses, every object's pose and the full simulator configuration (for exact replay); after
it, for an attempt worth keeping, images from the cameras and a fused, cropped, downsampled point cloud,
rendered from the configurations recorded (`episodes.render_replay`): failed attempts cost no rendering. In a
plan worker, the configurations go back to the caller, which renders them (`episodes.image_job`).

Images are drawn with robot visual meshes of a level of detail chosen for the camera resolution
(`sim.meshes.recording_faces`); `visual_faces=sim.meshes.DEFAULT_MAX_FACES` draws them at the full detail
of `hgen render`, which is also the detail the simulator's own model has. Depth is uint16 millimetres
(`episodes.depth_units`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from humanoidgen.sim.cameras import CAMERA_NAMES
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.meshes import DEFAULT_MAX_FACES, recording_faces
from humanoidgen.sim.cloud_floor import CLOUD_FLOOR, check_near_hands


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
    # Height (m above the table top) below which cloud points are dropped: the table's surface is left out
    # (sim.pointcloud.CLOUD_FLOOR says why); meta.json records it, and datasets without it kept the table.
    point_cloud_floor: float = CLOUD_FLOOR
    # Share of the cloud's points drawn near the hands (`sim.cloud_focus`); 0: the workspace sampled evenly.
    point_cloud_near_hands: float = 0.0
    # Faces per robot visual mesh in the images; None: chosen for the resolution (sim.meshes.recording_faces).
    visual_faces: int | None = None

    def __post_init__(self) -> None:
        unknown = (set(self.cameras) | set(self.point_cloud_cameras)) - set(CAMERA_NAMES)
        if unknown:
            raise ValueError(f"unknown cameras {sorted(unknown)}; cameras: {', '.join(CAMERA_NAMES)}")
        if self.every < 1:
            raise ValueError("every must be >= 1")
        if not -0.05 <= self.point_cloud_floor <= 0.3:
            raise ValueError(f"point_cloud_floor must be in [-0.05, 0.3] m above the table top, got "
                             f"{self.point_cloud_floor}")
        check_near_hands(self.point_cloud_near_hands)
        if self.visual_faces is not None and not 4 <= self.visual_faces <= DEFAULT_MAX_FACES:
            raise ValueError(f"visual_faces must be in [4, {DEFAULT_MAX_FACES}], got {self.visual_faces}")

    @property
    def renders(self) -> bool:
        return bool(self.cameras) or self.point_cloud

    @property
    def faces(self) -> int:
        """Faces per robot visual mesh the images are drawn with."""
        return self.visual_faces if self.visual_faces is not None else recording_faces(self.width, self.height)


@dataclass
class EpisodeRecorder:
    env: HumanoidEnv
    config: RecorderConfig = field(default_factory=RecorderConfig)
    frames: dict[str, list] = field(default_factory=dict)
    _count: int = 0

    def __post_init__(self) -> None:
        # Per recorded frame: the configuration its kinematics came from (see HumanoidEnv.kinematics_qpos),
        # kept in memory only, for rendering.
        self.configurations: list[np.ndarray] = []

    def close(self) -> None:
        """Nothing to release: the renderer lives only while `arrays` renders."""

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
        rec.setdefault("ee_pose", []).append(env.ee_poses().astype(np.float32))
        objs = [np.concatenate(env.object_pose(o.body)) for o in env.scene.objects]
        rec.setdefault("object_pose", []).append(np.array(objs, np.float32).reshape(len(objs), 7))
        if self.config.renders:
            self.configurations.append(env.kinematics_qpos())

    def arrays(self, images: bool = True, model: mujoco.MjModel | None = None) -> dict[str, np.ndarray]:
        """The recorded arrays; with `images` (and cameras configured), rendered ones too, drawn with `model`
        (default: the simulator's own, full-detail model; see `render_model`)."""
        out = {k: np.stack(v) for k, v in self.frames.items()}
        if images and self.config.renders and self.configurations:
            from humanoidgen.episodes.render_replay import render_recording

            cfg = self.config
            out.update(render_recording(model if model is not None else self.env.model, self.configurations,
                                        cfg.cameras, cfg.width, cfg.height, cfg.depth,
                                        cfg.point_cloud_cameras if cfg.point_cloud else (), cfg.num_points,
                                        cloud_floor=cfg.point_cloud_floor,
                                        near_hands=cfg.point_cloud_near_hands))
        return out


def matching_render_model(sim_model: mujoco.MjModel, render_model: mujoco.MjModel) -> mujoco.MjModel:
    """`render_model` (the same scene built at another visual detail) checked against the simulator's model
    and given its clipping planes, so that depth means the same in both."""
    for name in ("nq", "nbody", "njnt", "ngeom", "ncam", "nlight", "nsite"):
        if getattr(sim_model, name) != getattr(render_model, name):
            raise RuntimeError(f"the render model differs from the simulated one in {name} "
                               f"({getattr(render_model, name)} vs {getattr(sim_model, name)})")
    render_model.stat.extent = sim_model.stat.extent
    render_model.stat.center[:] = sim_model.stat.center
    return render_model
