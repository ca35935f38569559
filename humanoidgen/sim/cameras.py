"""The six cameras: where they sit, and rendering RGB, depth and segmentation from them.

On the robot (its robot file's `cameras`): a RealSense D435-like first-person head camera on the torso (about
43 degrees vertical field of view, the colour stream's fx = fy ~ 615 px at 640x480), and two wrist cameras
looking past each hand's fingers. Three third-person cameras watch the table from the front, the left and the
right.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import mujoco
import numpy as np

from humanoidgen.sim.geometry import look_at_quat
from humanoidgen.sim.layout import ROBOT


@dataclass(frozen=True)
class CameraSpec:
    """A camera fixed to a body (`body=None`: the world), looking from `eye` at `target`, both in that body's frame."""

    name: str
    eye: tuple[float, float, float]
    target: tuple[float, float, float]
    fovy: float
    body: str | None = None
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)


CAMERAS: tuple[CameraSpec, ...] = (
    # On the robot, in its body's frame (the robot file's `cameras`).
    *(CameraSpec(c.name, eye=c.eye, target=c.target, fovy=c.fovy, body=c.body, up=c.up) for c in ROBOT.data.cameras),
    CameraSpec("front", eye=(0.55, 0.0, 0.65), target=(-0.45, 0.0, 0.05), fovy=55.0),
    CameraSpec("left", eye=(-0.30, 1.05, 0.55), target=(-0.35, 0.0, 0.02), fovy=55.0),
    CameraSpec("right", eye=(-0.30, -1.05, 0.55), target=(-0.35, 0.0, 0.02), fovy=55.0),
)
CAMERA_NAMES: tuple[str, ...] = tuple(c.name for c in CAMERAS)


def add_cameras(spec: mujoco.MjSpec, cameras: tuple[CameraSpec, ...] = CAMERAS) -> None:
    for cam in cameras:
        parent = spec.worldbody if cam.body is None else spec.body(cam.body)
        parent.add_camera(
            name=cam.name,
            pos=cam.eye,
            quat=look_at_quat(np.array(cam.eye), np.array(cam.target), np.array(cam.up)),
            fovy=cam.fovy,
        )


def pose_data(model: mujoco.MjModel, data: mujoco.MjData, qpos: np.ndarray) -> None:
    """Put `data` at configuration `qpos`: kinematics, centres of mass and camera/light poses only (all a
    picture needs; the same functions the simulator ran, so the same poses bit for bit)."""
    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    mujoco.mj_comPos(model, data)
    mujoco.mj_camlight(model, data)


class StillLayerLike(Protocol):
    def under(self, rgb: np.ndarray, zbuf: np.ndarray) -> None: ...


@dataclass
class Frame:
    """One camera's images: RGB (H, W, 3) uint8, depth (H, W) float32 metres, segmentation (H, W) int32 labels."""

    rgb: np.ndarray
    depth: np.ndarray
    segmentation: np.ndarray
    fovy: float
    cam_pos: np.ndarray
    cam_mat: np.ndarray


@dataclass
class CameraRig:
    """Renders the scene's cameras at one resolution. Segmentation labels come from `geom_labels`.

    One lit pass gives colour and depth; segmentation takes a second, flat-colour pass whose colours encode
    geom ids. Shadows are off by default: on a software renderer they cost about twice the colour pass.
    """

    model: mujoco.MjModel
    width: int = 320
    height: int = 240
    geom_labels: np.ndarray | None = None
    shadows: bool = False
    max_geom: int = 2000
    hide_robot: bool = False  # pictures of objects alone
    # Geom groups drawn besides MuJoCo's default three (their meshes are uploaded too): `still_layer.STILL_GROUP`
    # for a rig that draws still geoms apart.
    extra_groups: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        vis = self.model.vis.global_
        if self.width > vis.offwidth or self.height > vis.offheight:
            raise ValueError(
                f"camera resolution {self.width}x{self.height} exceeds the model's offscreen buffer "
                f"{vis.offwidth}x{vis.offheight}"
            )
        from mujoco import gl_context

        self._opt = mujoco.MjvOption()
        if self.hide_robot:
            from humanoidgen.sim.robot import ROBOT_VISUAL_GROUP

            self._opt.geomgroup[ROBOT_VISUAL_GROUP] = 0
        for g in self.extra_groups:
            self._opt.geomgroup[g] = 1
        self._gl = gl_context.GLContext(self.width, self.height)
        self._gl.make_current()
        self._con = mujoco.MjrContext(drawn_meshes_only(self.model, self._opt),
                                      mujoco.mjtFontScale.mjFONTSCALE_100.value)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN.value, self._con)
        self._con.readDepthMap = mujoco.mjtDepthMap.mjDEPTH_ZEROFAR
        self._scn = mujoco.MjvScene(self.model, maxgeom=self.max_geom)
        self._cam = mujoco.MjvCamera()
        self._cam.type = mujoco.mjtCamera.mjCAMERA_FIXED
        self._pert = mujoco.MjvPerturb()
        self._rect = mujoco.MjrRect(0, 0, self.width, self.height)
        self._rgb = np.empty((self.height, self.width, 3), np.uint8)
        self._depth = np.empty((self.height, self.width), np.float32)
        extent = self.model.stat.extent
        self._near = np.float32(self.model.vis.map.znear * extent)
        self._far = np.float32(self.model.vis.map.zfar * extent)

    def close(self) -> None:
        if getattr(self, "_gl", None) is not None:
            self._gl.make_current()
            self._con.free()
            self._gl.free()
            self._gl = None

    def __enter__(self) -> "CameraRig":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    @property
    def zero_far(self) -> bool:
        """Depth-buffer values read 0 at the far plane and grow nearer (MuJoCo's reversed map, set above)."""
        return self._con.readDepthMap == mujoco.mjtDepthMap.mjDEPTH_ZEROFAR

    @property
    def groups(self) -> tuple[int, ...]:
        """The geom groups this rig draws."""
        return tuple(int(g) for g in np.flatnonzero(np.asarray(self._opt.geomgroup)))

    def render(
        self, data: mujoco.MjData, camera: str, rgb: bool = True, depth: bool = True, segmentation: bool = True,
        groups: tuple[int, ...] | None = None, over: "StillLayerLike | None" = None,
    ) -> Frame:
        """`camera`'s frame of `data`: only geoms of `groups` (default: the rig's `groups`), and, with `over`,
        drawn over a layer of what was left out (`still_layer.StillLayer`: colour and depth only)."""
        if over is not None and (segmentation or not rgb):
            raise ValueError("a still layer goes under colour and depth only: render it with segmentation=False")
        cam_id = self.model.camera(camera).id
        self._update_scene(data, cam_id, groups)
        flags = self._scn.flags
        rgb_img = np.zeros((0, 0, 3), np.uint8)
        depth_img = np.zeros((0, 0), np.float32)
        seg_img = np.zeros((0, 0), np.int32)
        if rgb:
            # The lit pass fills the depth buffer too: read both from it.
            flags[mujoco.mjtRndFlag.mjRND_SHADOW] = self.shadows
            mujoco.mjr_render(self._rect, self._scn, self._con)
            mujoco.mjr_readPixels(self._rgb, self._depth if depth or over is not None else None, self._rect,
                                  self._con)
            if over is not None:
                over.under(self._rgb, self._depth)
            rgb_img = np.flipud(self._rgb).copy()
            if depth:
                depth_img = np.flipud(self._metric_depth(self._depth)).copy()
        if segmentation or (depth and not rgb):
            flags[mujoco.mjtRndFlag.mjRND_SEGMENT] = True
            flags[mujoco.mjtRndFlag.mjRND_IDCOLOR] = True
            try:
                mujoco.mjr_render(self._rect, self._scn, self._con)
            finally:
                flags[mujoco.mjtRndFlag.mjRND_SEGMENT] = False
                flags[mujoco.mjtRndFlag.mjRND_IDCOLOR] = False
            mujoco.mjr_readPixels(self._rgb, self._depth, self._rect, self._con)
            if depth and not rgb:
                depth_img = np.flipud(self._metric_depth(self._depth)).copy()
            if segmentation:
                seg_img = np.flipud(self._labels(self._rgb)).copy()
        return Frame(
            rgb=rgb_img,
            depth=depth_img,
            segmentation=seg_img,
            fovy=float(self.model.cam_fovy[cam_id]),
            cam_pos=data.cam_xpos[cam_id].copy(),
            cam_mat=data.cam_xmat[cam_id].reshape(3, 3).copy(),
        )

    def draw_raw(self, data: mujoco.MjData, camera: str, groups: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
        """Colour and depth-buffer values of `camera`'s lit pass over geoms of `groups`, as the renderer holds
        them (bottom row first, depth not yet in metres, see `zero_far`): copies, for `still_layer.StillLayer`."""
        self._update_scene(data, self.model.camera(camera).id, groups)
        self._scn.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = self.shadows
        mujoco.mjr_render(self._rect, self._scn, self._con)
        mujoco.mjr_readPixels(self._rgb, self._depth, self._rect, self._con)
        return self._rgb.copy(), self._depth.copy()

    def _update_scene(self, data: mujoco.MjData, cam_id: int, groups: tuple[int, ...] | None) -> None:
        self._gl.make_current()
        self._cam.fixedcamid = cam_id
        saved = None
        if groups is not None:  # the groups decide which geoms go into the scene: set them for this update only
            saved = np.array(self._opt.geomgroup)
            self._opt.geomgroup[:] = 0
            for g in groups:
                self._opt.geomgroup[g] = 1
        try:
            mujoco.mjv_updateScene(self.model, data, self._opt, self._pert, self._cam,
                                   mujoco.mjtCatBit.mjCAT_ALL.value, self._scn)
        finally:
            if saved is not None:
                self._opt.geomgroup[:] = saved

    def render_all(self, data: mujoco.MjData, cameras: tuple[str, ...] = CAMERA_NAMES, **kw: bool) -> dict[str, Frame]:
        return {name: self.render(data, name, **kw) for name in cameras}

    def _metric_depth(self, zbuf: np.ndarray) -> np.ndarray:
        """OpenGL depth-buffer values -> distance along the optical axis (metres), as mujoco.Renderer does."""
        near, far = self._near, self._far
        c = np.float32(-0.5) * (-(far + near) / (far - near)) - np.float32(0.5)
        d = np.float32(-0.5) * (-(np.float32(2) * far * near) / (far - near))
        return (d / (zbuf.astype(np.float64) + c)).astype(np.float32)

    def _labels(self, idcolor: np.ndarray) -> np.ndarray:
        """Flat id colours -> segmentation labels: per geom label (or geom id without labels), -1 for nothing."""
        c = idcolor.astype(np.int64)
        segid = c[..., 0] + (c[..., 1] << 8) + (c[..., 2] << 16)  # 0: background, k: scene geom k-1
        n = self._scn.ngeom
        table = np.full(n + 1, -1, dtype=np.int32)
        for g in self._scn.geoms[:n]:
            if g.segid >= 0 and g.objtype == mujoco.mjtObj.mjOBJ_GEOM:
                table[g.segid + 1] = g.objid if self.geom_labels is None else self.geom_labels[g.objid]
        return table[np.clip(segid, 0, n)]


def drawn_meshes_only(model: mujoco.MjModel, opt: mujoco.MjvOption) -> mujoco.MjModel:
    """What a render context is made from: `model` itself, or, when some meshes are used by no geom of a
    group `opt` draws, a copy in which those meshes have no faces. A context uploads every mesh of its model,
    and the robot's hidden collision meshes are 610k of the scene's 807k faces: without them a context takes
    about 0.1 s of CPU instead of 0.35 (two per recorded episode). The pictures are the same (tested): the
    context's other meshes, and the scene drawn with it, are those of `model`."""
    mesh = mujoco.mjtGeom.mjGEOM_MESH
    groups = np.asarray(opt.geomgroup)
    is_mesh = model.geom_type == mesh
    drawn_group = groups[np.clip(model.geom_group, 0, len(groups) - 1)] != 0
    used = np.zeros(model.nmesh, bool)
    used[model.geom_dataid[is_mesh & drawn_group]] = True
    if used.all():
        return model
    import copy

    trimmed = copy.copy(model)
    trimmed.mesh_facenum[~used] = 0
    return trimmed
