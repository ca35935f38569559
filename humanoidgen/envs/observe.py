"""Observations of the running scene, named and computed as `episodes.recorder` records them: joint_pos,
ee_pose, rgb/<camera>, depth/<camera>, point_cloud (fused from the point-cloud cameras' depth with the
recorder's crop box and farthest-point sampling).

Pictures are drawn as a recording draws them (`episodes.render_replay`): from the configuration the
simulator's kinematics came from, with the robot's visual meshes at the recording's level of detail (a copy
of the scene built at that detail when it is not the simulator's own), and depth goes through the stored
millimetres, so a policy sees here exactly what its training data holds."""

from __future__ import annotations

import mujoco
import numpy as np
from gymnasium import spaces

from humanoidgen.envs.config import TaskEnvConfig
from humanoidgen.episodes.depth_units import decode_depth, encode_depth
from humanoidgen.episodes.render_replay import render_configuration
from humanoidgen.sim.action import ACTION_DIM
from humanoidgen.sim.cameras import CameraRig
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.pointcloud import workspace_cloud


def observation_space(cfg: TaskEnvConfig) -> spaces.Dict:
    inf = np.inf
    out: dict[str, spaces.Space] = {
        "joint_pos": spaces.Box(-inf, inf, (ACTION_DIM,), np.float32),
        "ee_pose": spaces.Box(-inf, inf, (14,), np.float32),  # per hand: position, quaternion (w, x, y, z)
    }
    for cam in cfg.cameras:
        out[f"rgb/{cam}"] = spaces.Box(0, 255, (cfg.height, cfg.width, 3), np.uint8)
        if cfg.depth:
            out[f"depth/{cam}"] = spaces.Box(0.0, inf, (cfg.height, cfg.width), np.float32)  # inf: nothing seen
    if cfg.point_cloud:
        out["point_cloud"] = spaces.Box(-inf, inf, (cfg.num_points, 3), np.float32)
    return spaces.Dict(out)


class Observer:
    """Renders what the config asks for from one scene (a new Observer per scene: the rig holds its model)."""

    def __init__(self, sim: HumanoidEnv, cfg: TaskEnvConfig, render_model=None) -> None:
        """`render_model`: the scene at the recording's visual detail (`render_model_for`); None: sim's own."""
        self.sim, self.cfg = sim, cfg
        cams = set(cfg.cameras) | (set(cfg.point_cloud_cameras) if cfg.point_cloud else set())
        self._model = render_model if render_model is not None else sim.model
        self._data = mujoco.MjData(self._model) if cams else None
        self._rig = CameraRig(self._model, cfg.width, cfg.height) if cams else None
        self._pc = workspace_cloud(cfg.num_points, cfg.point_cloud_floor, cfg.point_cloud_near_hands)

    def close(self) -> None:
        if self._rig is not None:
            self._rig.close()
            self._rig = None

    def __call__(self) -> dict[str, np.ndarray]:
        sim, cfg = self.sim, self.cfg
        obs = {"joint_pos": sim.joint_positions().astype(np.float32), "ee_pose": sim.ee_poses().astype(np.float32)}
        if self._rig is None:
            return obs
        frames, cloud = render_configuration(self._rig, self._model, self._data, sim.kinematics_qpos(),
                                             tuple(cfg.cameras), cfg.depth,
                                             tuple(cfg.point_cloud_cameras) if cfg.point_cloud else (), self._pc)
        for c in cfg.cameras:
            obs[f"rgb/{c}"] = frames[c].rgb
            if cfg.depth:
                obs[f"depth/{c}"] = decode_depth(encode_depth(frames[c].depth))  # as stored: whole mm
        if cloud is not None:
            obs["point_cloud"] = cloud.astype(np.float32)
        return obs


def render_model_for(spec, seed: int, sim: HumanoidEnv, cfg: TaskEnvConfig, dressing=None):
    """The model a recording with these settings draws seed `seed`'s scene with (None: the simulator's own),
    built as the episode worker builds it."""
    if not (cfg.cameras or cfg.point_cloud):
        return None
    from humanoidgen.episodes.recorder import matching_render_model
    from humanoidgen.sim.meshes import recording_faces, visual_detail, visual_faces
    from humanoidgen.tasks.scene import build_layout

    faces = cfg.visual_faces if cfg.visual_faces is not None else recording_faces(cfg.width, cfg.height)
    if faces == visual_faces():
        return None
    with visual_detail(faces):
        scene, _ = build_layout(spec.sample_layout(seed), settle_s=0.0, aliases=spec.aliases(), dressing=dressing)
    return matching_render_model(sim.model, scene.model)
