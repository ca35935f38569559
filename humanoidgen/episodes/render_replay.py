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
import threading
from collections.abc import Iterator, Sequence
from concurrent.futures import Future, ThreadPoolExecutor

import mujoco
import numpy as np

from humanoidgen.episodes.depth_units import encode_depth
from humanoidgen.sim.cameras import CameraRig, pose_data
from humanoidgen.sim.layout import ROBOT, SIDES, WRIST_BODY
from humanoidgen.sim.pointcloud import CLOUD_FLOOR, PointCloudConfig, fuse_point_cloud, workspace_cloud
from humanoidgen.sim.still_layer import STILL_GROUP, StillLayer, StillParts, layered_model, moving_groups, still_parts

# Frames each renderer draws per turn: two turns of two renderers held at once are 32 frames, about 75 MB for
# six 320x240 RGB-D cameras, whatever the episode's length.
CHUNK_FRAMES = 8
_CONTEXT_LOCK = threading.Lock()


def render_recording(model: mujoco.MjModel, configurations: Sequence[np.ndarray], cameras: tuple[str, ...],
                     width: int, height: int, depth: bool = True, point_cloud_cameras: tuple[str, ...] = (),
                     num_points: int = 1024, threads: int | None = None, still_layers: bool = True,
                     cloud_floor: float = CLOUD_FLOOR, near_hands: float = 0.0) -> dict[str, np.ndarray]:
    """rgb/<camera> (T, H, W, 3) uint8 and depth/<camera> (T, H, W) uint16 mm for `cameras`, and, when
    `point_cloud_cameras` are given, point_cloud (T, num_points, 3) float32 fused from their depth; all in
    memory (`iter_frames` hands them over frame by frame); the cloud's points above `cloud_floor` (m over the
    table top: `sim.pointcloud.workspace_cloud`), the share `near_hands` of them drawn near the hands."""
    n = len(configurations)
    out = {key: np.empty((n, *shape), dtype) for key, (shape, dtype) in
           frame_layout(cameras, width, height, depth, bool(point_cloud_cameras), num_points).items()}
    for t, frame in iter_frames(model, configurations, cameras, width, height, depth, point_cloud_cameras,
                                num_points, threads, still_layers=still_layers, cloud_floor=cloud_floor,
                                near_hands=near_hands):
        for key, value in frame.items():
            out[key][t] = value
    return out


def frame_layout(cameras: tuple[str, ...], width: int, height: int, depth: bool, point_cloud: bool,
                 num_points: int) -> dict[str, tuple[tuple[int, ...], np.dtype]]:
    """Shape (of one frame) and dtype of every array a recorded frame has, in the order they are written."""
    out: dict[str, tuple[tuple[int, ...], np.dtype]] = {}
    for c in cameras:
        out[f"rgb/{c}"] = ((height, width, 3), np.dtype(np.uint8))
        if depth:
            out[f"depth/{c}"] = ((height, width), np.dtype(np.uint16))
    if point_cloud:
        out["point_cloud"] = ((num_points, 3), np.dtype(np.float32))
    return out


def iter_frames(model: mujoco.MjModel, configurations: Sequence[np.ndarray], cameras: tuple[str, ...],
                width: int, height: int, depth: bool = True, point_cloud_cameras: tuple[str, ...] = (),
                num_points: int = 1024, threads: int | None = None, chunk: int = CHUNK_FRAMES,
                still_layers: bool = True, cloud_floor: float = CLOUD_FLOOR, near_hands: float = 0.0
                ) -> Iterator[tuple[int, dict[str, np.ndarray]]]:
    """(t, arrays of frame t) in time order, rendered `chunk` frames per renderer at a time: the caller
    (compressing, writing) works on one chunk while the renderers draw the next, and only two chunks are
    ever held.

    `threads` renderers (default: one per CPU, at most 2) each draw a contiguous share of a chunk with their
    own GL context: the software renderer runs its vertex stage on the calling thread, so two of them keep
    two cores busy. Each frame depends only on its configuration: the frames are the same for any number.

    With `still_layers`, what stays still through the whole recording is drawn once per still camera and each
    frame draws only what moves (`sim.still_layer`): the same pixels, 28% less CPU on a hand-over."""
    n = len(configurations)
    threads = max(1, min(threads or min(2, os.cpu_count() or 1), n))
    still = still_parts(model, configurations) if still_layers else None
    if still is not None and still.worth_layering:
        model = layered_model(model, still)
    else:
        still = None
    renderers = [_Renderer(model, width, height, still) for _ in range(threads)]
    job = (configurations, cameras, depth, point_cloud_cameras, workspace_cloud(num_points, cloud_floor, near_hands))
    try:
        pending = _submit(renderers, job, 0, min(n, chunk * threads))
        done = 0
        while pending:
            start = done + sum(len(f.result()) for f in pending)  # the chunk after this one, submitted now
            frames = [frame for f in pending for frame in f.result()]
            pending = _submit(renderers, job, start, min(n, start + chunk * threads)) if start < n else []
            for frame in frames:
                yield done, frame
                done += 1
    finally:
        for r in renderers:
            r.close()


class _Renderer:
    """A thread of its own holding one GL context (a context is current in one thread only)."""

    def __init__(self, model: mujoco.MjModel, width: int, height: int, still: StillParts | None) -> None:
        self.model = model
        self.pool = ThreadPoolExecutor(1, thread_name_prefix="hgen-render")
        self.rig = self.pool.submit(_new_rig, model, width, height, (STILL_GROUP,) if still else ())
        self.data = mujoco.MjData(model)
        # Each renderer draws its own layers (one frame's work per still camera), from its own context.
        self.layers = StillLayers(still.cameras) if still else None

    def frames(self, job: tuple, frames: range) -> list[dict[str, np.ndarray]]:
        configurations, cameras, depth, point_cloud_cameras, pc = job
        rig = self.rig.result()
        out = []
        for t in frames:
            views, cloud = render_configuration(rig, self.model, self.data, configurations[t], cameras, depth,
                                                point_cloud_cameras, pc, self.layers)
            frame = {}
            for c in cameras:
                frame[f"rgb/{c}"] = views[c].rgb
                if depth:
                    frame[f"depth/{c}"] = encode_depth(views[c].depth)
            if cloud is not None:
                frame["point_cloud"] = cloud
            out.append(frame)
        return out

    def close(self) -> None:
        try:
            self.pool.submit(self.rig.result().close).result()
        finally:
            self.pool.shutdown(wait=True, cancel_futures=True)


def _new_rig(model: mujoco.MjModel, width: int, height: int, extra_groups: tuple[int, ...]) -> CameraRig:
    # One context at a time: two threads creating MuJoCo render contexts at once were seen to hang for good
    # (one of them waiting inside libmujoco on a static initialisation the other had finished).
    with _CONTEXT_LOCK:
        return CameraRig(model, width, height, extra_groups=extra_groups)


class StillLayers:
    """The still cameras of a recording and their layers, drawn on first use (`sim.still_layer`)."""

    def __init__(self, cameras: frozenset[str]) -> None:
        self.cameras = cameras
        self._layers: dict[str, StillLayer] = {}

    def render(self, rig: CameraRig, data: mujoco.MjData, camera: str, depth: bool):
        """`camera`'s frame (colour, and depth if asked): over its layer if it is still, else all of it."""
        if camera not in self.cameras:
            return rig.render(data, camera, depth=depth, segmentation=False)
        layer = self._layers.get(camera)
        if layer is None:  # the still geoms are where they are in every frame: any frame draws the layer
            layer = self._layers[camera] = StillLayer(*rig.draw_raw(data, camera, (STILL_GROUP,)), rig.zero_far)
        return rig.render(data, camera, depth=depth, segmentation=False, groups=moving_groups(rig.groups),
                          over=layer)


def _submit(renderers: list[_Renderer], job: tuple, a: int, b: int) -> list[Future]:
    """Frames a..b, split into contiguous shares, one per renderer, in order."""
    bounds = np.linspace(a, b, len(renderers) + 1).round().astype(int)
    return [r.pool.submit(r.frames, job, range(lo, hi)) for r, lo, hi in zip(renderers, bounds[:-1], bounds[1:])]


def render_configuration(rig: CameraRig, model: mujoco.MjModel, data: mujoco.MjData, qpos: np.ndarray,
                         cameras: tuple[str, ...], depth: bool, point_cloud_cameras: tuple[str, ...],
                         pc: PointCloudConfig, layers: StillLayers | None = None) -> tuple[dict, np.ndarray | None]:
    """One recorded frame drawn from configuration `qpos`: the cameras' frames (RGB for `cameras`, depth where
    asked or needed for the cloud) and the point cloud fused from the float depth as rendered (not the stored
    millimetres), None without point-cloud cameras. With `layers`, still cameras draw over their still layer.
    A cloud focused on the hands (`pc.near_hands`) centres on their grasp points (`focus_points`)."""
    pose_data(model, data, qpos)
    frames = {}
    for c in dict.fromkeys(cameras + point_cloud_cameras):
        want_depth = depth or c in point_cloud_cameras
        if layers is not None and c in cameras:
            frames[c] = layers.render(rig, data, c, want_depth)
        else:
            frames[c] = rig.render(data, c, rgb=c in cameras, depth=want_depth, segmentation=False)
    if not point_cloud_cameras:
        return frames, None
    focus = focus_points(model, data) if pc.near_hands else None
    return frames, fuse_point_cloud([(frames[c].depth, frames[c].fovy, frames[c].cam_pos, frames[c].cam_mat, None)
                                     for c in point_cloud_cameras], pc, focus)


def focus_points(model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
    """(2, 3) where each hand's whole-hand grasp is centred (its hand file's `grasp_point_base_<side>_hand`, a
    point every hand file names for the planner API), in the world at `data`'s pose: what a focused cloud
    (`sim.cloud_focus`) samples around."""
    out = []
    for side in SIDES:
        body = model.body(WRIST_BODY[side]).id
        local = ROBOT.hand.points(side)[f"grasp_point_base_{side}_hand"]
        out.append(data.xpos[body] + data.xmat[body].reshape(3, 3) @ local)
    return np.array(out)
