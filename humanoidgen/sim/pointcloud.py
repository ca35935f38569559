"""Depth images -> world-frame point clouds for DP3-style datasets.

Numpy and numba; no MuJoCo import. The conventions follow MuJoCo's cameras:

* pinhole model with *vertical* field of view ``fovy`` and square pixels;
* the camera looks along its local ``-z`` axis, ``+x`` is image right and
  ``+y`` is image up;
* ``cam_mat = data.cam_xmat[i].reshape(3, 3)`` has the camera axes (in world
  coordinates) as its COLUMNS, so ``p_world = cam_pos + cam_mat @ p_cam``;
* depth from ``mujoco.Renderer`` (depth rendering enabled) is the distance
  along the optical axis in metres, not the ray length.

World frame used by the defaults: +x forward, +y left, +z up, table top at z=0.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import NamedTuple, Sequence

import numpy as np
from numba import njit

from humanoidgen.sim.cloud_floor import CLOUD_FLOOR, NEAR_HANDS_RADIUS, TABLE_CLOUD_FLOOR, check_near_hands
from humanoidgen.sim.cloud_focus import focused_sample
from humanoidgen.sim.fps import farthest_point_sampling

__all__ = [
    "DepthView",
    "PointCloudConfig",
    "intrinsics",
    "depth_to_points",
    "crop_box",
    "farthest_point_sampling",
    "fuse_point_cloud",
    "CLOUD_FLOOR",
    "TABLE_CLOUD_FLOOR",
    "workspace_cloud",
]


def intrinsics(width: int, height: int, fovy_deg: float) -> np.ndarray:
    """3x3 pinhole intrinsics matrix K for a MuJoCo camera.

    MuJoCo specifies only the vertical FOV; with square pixels fx == fy and the
    principal point sits exactly at the image centre (pixel-edge coordinates).
    """
    if width <= 0 or height <= 0:
        raise ValueError(f"image size must be positive, got {width}x{height}")
    if not 0.0 < fovy_deg < 180.0:
        raise ValueError(f"fovy_deg must be in (0, 180), got {fovy_deg}")
    f = height / (2.0 * np.tan(np.deg2rad(fovy_deg) / 2.0))
    return np.array(
        [[f, 0.0, width / 2.0], [0.0, f, height / 2.0], [0.0, 0.0, 1.0]],
        dtype=np.float64,
    )


def workspace_cloud(num_points: int, floor: float = CLOUD_FLOOR, near_hands: float = 0.0) -> "PointCloudConfig":
    """The recording's cloud settings: the workspace box over the table with its bottom at `floor` (m), and
    the share `near_hands` of the points drawn near the hands (`sim.cloud_focus`)."""
    lo = PointCloudConfig.crop_lo
    return PointCloudConfig(num_points=num_points, crop_lo=(lo[0], lo[1], floor), near_hands=near_hands)


def depth_to_points(
    depth: np.ndarray,
    fovy_deg: float,
    cam_pos: np.ndarray,
    cam_mat: np.ndarray,
    far: float = np.inf,
) -> tuple[np.ndarray, np.ndarray]:
    """Back-project a depth image into world-frame points.

    Returns ``(points, valid)``:

    * ``points``: ``(H*W, 3)`` float64, row-major pixel order (row ``v`` from
      the top, then column ``u``), i.e. aligned with ``image.reshape(H*W, ...)``
      so per-pixel attributes such as RGB can be selected with the same mask.
      Rows of invalid pixels are NaN so they can never be used by accident.
    * ``valid``: ``(H*W,)`` bool, False where depth is non-finite or
      ``>= far`` (MuJoCo reports the far clipping plane for empty background).

    Use ``points[valid]`` for the usable cloud.
    """
    depth = np.asarray(depth)
    if depth.ndim != 2:
        raise ValueError(f"depth must be (H, W), got shape {depth.shape}")
    h, w = depth.shape
    k = intrinsics(w, h, fovy_deg)
    fx, fy, cx, cy = k[0, 0], k[1, 1], k[0, 2], k[1, 2]

    d = depth.astype(np.float64).reshape(-1)
    valid = np.isfinite(d) & (d < far)
    xn, yn = _pixel_rays(h, w, fx, fy, cx, cy)

    d_safe = np.where(valid, d, np.nan)
    cam_mat = np.asarray(cam_mat, dtype=np.float64).reshape(3, 3)
    cam_pos = np.asarray(cam_pos, dtype=np.float64).reshape(3)
    # p_world = cam_pos + cam_mat @ (xn d, yn d, -d) (the camera looks along -z), written out per axis:
    # a (H*W, 3) @ (3, 3) product goes through BLAS, whose threads cost ~70x more than the product here.
    xd, yd = xn * d_safe, yn * d_safe
    points = np.empty((h * w, 3))
    for axis in range(3):
        m = cam_mat[axis]
        points[:, axis] = xd * m[0] + yd * m[1] - d_safe * m[2] + cam_pos[axis]
    return points, valid


@lru_cache(maxsize=16)
def _pixel_rays(h: int, w: int, fx: float, fy: float, cx: float, cy: float) -> tuple[np.ndarray, np.ndarray]:
    """Normalised image coordinates (x/z, y/z) of every pixel centre, row-major; read-only, cached per camera."""
    # +0.5: MuJoCo samples the ray through the pixel centre.
    u = np.arange(w, dtype=np.float64) + 0.5
    v = np.arange(h, dtype=np.float64) + 0.5
    xn = np.ascontiguousarray(np.broadcast_to((u - cx) / fx, (h, w)).reshape(-1))
    # Image rows grow downward while camera +y is up, hence the sign flip.
    yn = np.ascontiguousarray(np.broadcast_to((-(v - cy) / fy)[:, None], (h, w)).reshape(-1))
    xn.flags.writeable = yn.flags.writeable = False
    return xn, yn


def crop_box(points: np.ndarray, lo: Sequence[float], hi: Sequence[float]) -> np.ndarray:
    """Boolean mask of points inside the axis-aligned box [lo, hi] (inclusive).

    NaN rows compare False and are therefore excluded.
    """
    points = np.asarray(points)
    lo_a = np.asarray(lo, dtype=np.float64)
    hi_a = np.asarray(hi, dtype=np.float64)
    return np.all((points >= lo_a) & (points <= hi_a), axis=-1)


@dataclass
class PointCloudConfig:
    """Settings for :func:`fuse_point_cloud`.

    The default crop is a workspace box over the table in front of the robot
    (world frame: +x forward, +y left, +z up, table top at z=0); z starts just
    below 0 so the table surface itself survives depth noise.
    """

    num_points: int = 1024
    crop_lo: tuple[float, float, float] = (-0.65, -0.55, -0.01)
    crop_hi: tuple[float, float, float] = (0.05, 0.55, 0.6)
    use_rgb: bool = False
    far: float = np.inf  # depths >= far are treated as background
    seed: int = 0  # FPS seed, for reproducible datasets
    # Share of the points drawn from within `near_radius` of the focus points `fuse_point_cloud` is given (the
    # hands: `sim.cloud_focus`); 0: the whole crop sampled evenly.
    near_hands: float = 0.0
    near_radius: float = NEAR_HANDS_RADIUS

    def __post_init__(self) -> None:
        check_near_hands(self.near_hands)
        if not self.near_radius > 0:
            raise ValueError(f"near_radius must be positive, got {self.near_radius}")


class DepthView(NamedTuple):
    """One camera view. A plain 5-tuple in this order works too."""

    depth: np.ndarray  # (H, W) metres along the optical axis
    fovy_deg: float
    cam_pos: np.ndarray  # (3,)
    cam_mat: np.ndarray  # (3, 3), columns = camera axes in world
    rgb: np.ndarray | None = None  # (H, W, 3) uint8 or float in [0, 1]


def _cropped_points(depth, fovy_deg, cam_pos, cam_mat, cfg: PointCloudConfig) -> tuple[np.ndarray, np.ndarray]:
    """Pixel indices and world points of one view's pixels inside the crop box: `depth_to_points` followed
    by `crop_box`, value for value (the same double-precision expression, term by term), in one compiled
    pass over the pixels that computes points for valid pixels only and stops at the first axis outside the
    box (a 320x240 view: about 0.3 ms instead of numpy's 0.8)."""
    depth = np.asarray(depth)
    if depth.ndim != 2:
        raise ValueError(f"depth must be (H, W), got shape {depth.shape}")
    h, w = depth.shape
    k = intrinsics(w, h, fovy_deg)
    xn, yn = _pixel_rays(h, w, k[0, 0], k[1, 1], k[0, 2], k[1, 2])
    if depth.dtype not in (np.float32, np.float64):
        depth = depth.astype(np.float64)
    idx = np.empty(h * w, np.int64)
    pts = np.empty((h * w, 3))
    n = _crop_pixels(np.ascontiguousarray(depth).reshape(-1), xn, yn,
                     np.ascontiguousarray(cam_mat, dtype=np.float64).reshape(3, 3),
                     np.ascontiguousarray(cam_pos, dtype=np.float64).reshape(3),
                     np.asarray(cfg.crop_lo, np.float64), np.asarray(cfg.crop_hi, np.float64), float(cfg.far),
                     idx, pts)
    return idx[:n], pts[:n]


@njit(cache=True, nogil=True)
def _crop_pixels(depth, xn, yn, m, pos, lo, hi, far, idx, pts):  # pragma: no cover - compiled
    """Writes the kept pixels' indices and points into idx and pts; returns how many. For each axis the
    point is `xd * m[a, 0] + yd * m[a, 1] - d * m[a, 2] + pos[a]`, evaluated left to right as numpy does
    (no fused multiply-add: numba compiles without fastmath)."""
    n = 0
    for i in range(depth.shape[0]):
        d = np.float64(depth[i])
        if not (np.isfinite(d) and d < far):
            continue
        xd = xn[i] * d
        yd = yn[i] * d
        x = xd * m[0, 0] + yd * m[0, 1] - d * m[0, 2] + pos[0]
        if not (x >= lo[0] and x <= hi[0]):
            continue
        y = xd * m[1, 0] + yd * m[1, 1] - d * m[1, 2] + pos[1]
        if not (y >= lo[1] and y <= hi[1]):
            continue
        z = xd * m[2, 0] + yd * m[2, 1] - d * m[2, 2] + pos[2]
        if not (z >= lo[2] and z <= hi[2]):
            continue
        idx[n] = i
        pts[n, 0] = x
        pts[n, 1] = y
        pts[n, 2] = z
        n += 1
    return n


def _rgb_to_unit(rgb: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    rgb = np.asarray(rgb)
    if rgb.shape[:2] != shape or rgb.ndim != 3 or rgb.shape[2] < 3:
        raise ValueError(f"rgb must be (H, W, 3) matching depth {shape}, got {rgb.shape}")
    rgb = rgb[..., :3]
    if np.issubdtype(rgb.dtype, np.integer):
        out = rgb.astype(np.float64) / 255.0
    else:
        out = rgb.astype(np.float64)
    return np.clip(out, 0.0, 1.0).reshape(-1, 3)


def fuse_point_cloud(
    views: Sequence[DepthView | tuple],
    config: PointCloudConfig | None = None,
    focus: np.ndarray | None = None,
) -> np.ndarray:
    """Fuse several depth views into one cropped, FPS-downsampled cloud.

    Each view is ``(depth, fovy_deg, cam_pos, cam_mat, rgb_or_None)``. With ``config.near_hands`` > 0 and
    ``focus`` (K, 3) world points (the hands), that share of the points is drawn near them (`sim.cloud_focus`).
    Returns float32 ``(num_points, 3)``, or ``(num_points, 6)`` with RGB in
    [0, 1] appended when ``config.use_rgb`` (every view then needs rgb).
    Raises ValueError if no point survives the crop.
    """
    cfg = config if config is not None else PointCloudConfig()
    if len(views) == 0:
        raise ValueError("fuse_point_cloud needs at least one view")

    chunks: list[np.ndarray] = []
    for i, view in enumerate(views):
        depth, fovy, pos, mat, *rest = view
        rgb = rest[0] if rest else None
        keep, feats = _cropped_points(depth, fovy, pos, mat, cfg)
        if cfg.use_rgb:
            if rgb is None:
                raise ValueError(f"config.use_rgb is True but view {i} has no rgb")
            cols = _rgb_to_unit(rgb, np.asarray(depth).shape)[keep]
            feats = np.concatenate([feats, cols], axis=1)
        chunks.append(feats)

    cloud = np.concatenate(chunks, axis=0)
    if cloud.shape[0] == 0:
        raise ValueError(
            "no points left after cropping to "
            f"lo={cfg.crop_lo}, hi={cfg.crop_hi} (check camera poses / crop box)"
        )
    # FPS on xyz only: colour should not influence spatial coverage.
    if cfg.near_hands > 0 and focus is not None:
        idx = focused_sample(cloud[:, :3], cfg.num_points, cfg.near_hands, focus, cfg.near_radius, seed=cfg.seed)
    else:
        idx = farthest_point_sampling(cloud[:, :3], cfg.num_points, seed=cfg.seed)
    return cloud[idx].astype(np.float32)
