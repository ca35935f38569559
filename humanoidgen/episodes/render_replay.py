"""Images and point clouds of a recorded episode, rendered after its physics from the recorded
configurations (see `EpisodeRecorder`): only attempts worth keeping pay for cameras.

Each recorded frame keeps the configuration the simulator's kinematics came from when the frame was taken
(`HumanoidEnv.kinematics_qpos`). Positioning a fresh MjData there with the same kinematics functions
(`mj_kinematics`, `mj_comPos`, `mj_camlight`) gives bit for bit the body, geom and camera poses the
simulator had, so the pictures equal those rendered during the run on the same model. The model may be a
copy of the scene with lighter robot visual meshes (the recording level of detail): same bodies, joints and
cameras, other pixels.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor

import mujoco
import numpy as np

from humanoidgen.episodes.depth_units import encode_depth
from humanoidgen.sim.cameras import CameraRig
from humanoidgen.sim.pointcloud import PointCloudConfig, fuse_point_cloud


def pose_data(model: mujoco.MjModel, data: mujoco.MjData, qpos: np.ndarray) -> None:
    """Put `data` at configuration `qpos`: kinematics, centres of mass and camera/light poses only."""
    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    mujoco.mj_comPos(model, data)
    mujoco.mj_camlight(model, data)


def render_recording(model: mujoco.MjModel, configurations: Sequence[np.ndarray], cameras: tuple[str, ...],
                     width: int, height: int, depth: bool = True, point_cloud_cameras: tuple[str, ...] = (),
                     num_points: int = 1024, threads: int | None = None) -> dict[str, np.ndarray]:
    """rgb/<camera> (T, H, W, 3) uint8 and depth/<camera> (T, H, W) uint16 mm for `cameras`, and, when
    `point_cloud_cameras` are given, point_cloud (T, num_points, 3) float32 fused from their depth.

    `threads` renderers (default: one per CPU, at most 2) each take a contiguous share of the frames, with
    their own GL context: the software renderer runs its vertex stage on the calling thread, so two of them
    keep two cores busy. Each frame depends only on its configuration: the result is the same for any number."""
    n = len(configurations)
    out: dict[str, np.ndarray] = {}
    for c in cameras:
        out[f"rgb/{c}"] = np.empty((n, height, width, 3), np.uint8)
        if depth:
            out[f"depth/{c}"] = np.empty((n, height, width), np.uint16)
    if point_cloud_cameras:
        out["point_cloud"] = np.empty((n, num_points, 3), np.float32)
    threads = max(1, min(threads or min(2, os.cpu_count() or 1), n))
    bounds = np.linspace(0, n, threads + 1).round().astype(int)
    job = (model, configurations, cameras, width, height, depth, point_cloud_cameras, num_points, out)
    if threads == 1:
        _render_frames(*job, range(n))
        return out
    with ThreadPoolExecutor(threads, thread_name_prefix="hgen-render") as pool:
        for done in [pool.submit(_render_frames, *job, range(a, b)) for a, b in zip(bounds[:-1], bounds[1:])]:
            done.result()
    return out


def _render_frames(model, configurations, cameras, width, height, depth, point_cloud_cameras, num_points,
                   out: dict[str, np.ndarray], frames_to_render: range) -> None:
    pc = PointCloudConfig(num_points=num_points)
    data = mujoco.MjData(model)
    with CameraRig(model, width, height) as rig:
        for t in frames_to_render:
            frames, cloud = render_configuration(rig, model, data, configurations[t], cameras, depth,
                                                 point_cloud_cameras, pc)
            for c in cameras:
                out[f"rgb/{c}"][t] = frames[c].rgb
                if depth:
                    out[f"depth/{c}"][t] = encode_depth(frames[c].depth)
            if cloud is not None:
                out["point_cloud"][t] = cloud


def render_configuration(rig: CameraRig, model: mujoco.MjModel, data: mujoco.MjData, qpos: np.ndarray,
                         cameras: tuple[str, ...], depth: bool, point_cloud_cameras: tuple[str, ...],
                         pc: PointCloudConfig) -> tuple[dict, np.ndarray | None]:
    """One recorded frame drawn from configuration `qpos`: the cameras' frames (RGB for `cameras`, depth where
    asked or needed for the cloud) and the point cloud fused from the float depth as rendered (not the stored
    millimetres), None without point-cloud cameras."""
    pose_data(model, data, qpos)
    frames = {c: rig.render(data, c, rgb=c in cameras, depth=depth or c in point_cloud_cameras, segmentation=False)
              for c in dict.fromkeys(cameras + point_cloud_cameras)}
    if not point_cloud_cameras:
        return frames, None
    return frames, fuse_point_cloud([(frames[c].depth, frames[c].fovy, frames[c].cam_pos, frames[c].cam_mat, None)
                                     for c in point_cloud_cameras], pc)
