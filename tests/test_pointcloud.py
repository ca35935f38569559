import os

os.environ.setdefault("MUJOCO_GL", "egl")  # must precede any mujoco import

import time

import numpy as np
import pytest

from humanoidgen.sim.fps import reference_fps
from humanoidgen.sim.pointcloud import (
    DepthView,
    PointCloudConfig,
    crop_box,
    depth_to_points,
    farthest_point_sampling,
    fuse_point_cloud,
    intrinsics,
)


def look_at(pos, target, up=(0.0, 0.0, 1.0)) -> np.ndarray:
    """MuJoCo-style cam_mat (columns = camera x, y, z in world; looks along -z)."""
    fwd = np.asarray(target, float) - np.asarray(pos, float)
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, up)
    right /= np.linalg.norm(right)
    cam_up = np.cross(right, fwd)
    return np.stack([right, cam_up, -fwd], axis=1)


def plane_depth(w, h, fovy, pos, mat, plane_z=0.0) -> np.ndarray:
    """Analytic optical-axis depth image of the plane z=plane_z."""
    k = intrinsics(w, h, fovy)
    u = np.arange(w) + 0.5
    v = np.arange(h) + 0.5
    xn = (u[None, :] - k[0, 2]) / k[0, 0]
    yn = -(v[:, None] - k[1, 2]) / k[1, 1]
    # p_cam = d * (xn, yn, -1); world z = pos_z + d * (mat @ r)_z
    rz = mat[2, 0] * xn + mat[2, 1] * yn - mat[2, 2]
    return ((plane_z - pos[2]) / rz).astype(np.float32)


def test_intrinsics():
    k = intrinsics(64, 48, 90.0)
    assert k[1, 1] == pytest.approx(24.0)
    assert k[0, 0] == k[1, 1]
    assert (k[0, 2], k[1, 2]) == (32.0, 24.0)
    assert np.array_equal(k[2], [0, 0, 1])


def test_down_camera_plane_footprint():
    w, h, fovy = 80, 60, 60.0
    pos = np.array([0.0, 0.0, 1.0])
    mat = np.eye(3)  # identity: local -z == world -z, image up == world +y
    depth = np.ones((h, w), np.float32)
    pts, valid = depth_to_points(depth, fovy, pos, mat)
    assert pts.shape == (h * w, 3) and valid.all()
    assert np.abs(pts[:, 2]).max() < 1e-5
    f = h / (2 * np.tan(np.deg2rad(fovy) / 2))
    assert pts[:, 0].max() == pytest.approx((w / 2 - 0.5) / f)
    assert pts[:, 0].min() == pytest.approx(-(w / 2 - 0.5) / f)
    assert pts[:, 1].max() == pytest.approx((h / 2 - 0.5) / f)
    grid = pts.reshape(h, w, 3)
    # Top-left pixel -> image left (-x) and image up (+y).
    assert grid[0, 0, 0] < 0 and grid[0, 0, 1] > 0
    assert grid[-1, -1, 0] > 0 and grid[-1, -1, 1] < 0


def test_tilted_camera_plane_and_reprojection():
    w, h, fovy = 96, 72, 50.0
    pos = np.array([-0.9, 0.2, 0.7])
    mat = look_at(pos, [-0.3, 0.0, 0.0])
    assert np.allclose(mat.T @ mat, np.eye(3)) and np.linalg.det(mat) == pytest.approx(1.0)
    depth = plane_depth(w, h, fovy, pos, mat)
    assert (depth > 0).all()
    pts, valid = depth_to_points(depth, fovy, pos, mat)
    assert valid.all()
    assert np.abs(pts[:, 2]).max() < 1e-5
    # Reproject into the camera and recover pixel centres.
    k = intrinsics(w, h, fovy)
    pc = (pts - pos) @ mat
    u = k[0, 0] * pc[:, 0] / -pc[:, 2] + k[0, 2] - 0.5
    v = -k[1, 1] * pc[:, 1] / -pc[:, 2] + k[1, 2] - 0.5
    uu, vv = np.meshgrid(np.arange(w), np.arange(h))
    assert np.allclose(u, uu.ravel(), atol=1e-3)
    assert np.allclose(v, vv.ravel(), atol=1e-3)
    assert np.allclose(-pc[:, 2], depth.ravel(), atol=1e-5)


def test_invalid_depth_masked():
    depth = np.full((4, 5), 2.0, np.float32)
    depth[0, 0] = np.nan
    depth[1, 1] = np.inf
    depth[2, 2] = 10.0
    pts, valid = depth_to_points(depth, 45.0, np.zeros(3), np.eye(3), far=5.0)
    assert valid.sum() == 20 - 3
    assert not valid[[0, 6, 12]].any()
    assert np.isnan(pts[~valid]).all() and np.isfinite(pts[valid]).all()


def test_crop_box_inclusive():
    p = np.array([[0, 0, 0], [1, 1, 1], [1.0001, 0, 0], [np.nan, 0, 0]], float)
    assert crop_box(p, [0, 0, 0], [1, 1, 1]).tolist() == [True, True, False, False]


def test_fps_determinism_and_uniqueness():
    pts = np.random.default_rng(1).random((5000, 3))
    a = farthest_point_sampling(pts, 256, seed=3)
    b = farthest_point_sampling(pts, 256, seed=3)
    c = farthest_point_sampling(pts, 256, seed=4)
    assert a.shape == (256,) and np.array_equal(a, b) and not np.array_equal(a, c)
    assert len(np.unique(a)) == 256


def _min_pairwise(p):
    d = np.linalg.norm(p[:, None] - p[None], axis=-1)
    d[np.diag_indices(len(p))] = np.inf
    return d.min()


def test_fps_spread_beats_random():
    g = np.linspace(0, 1, 50)
    grid = np.stack(np.meshgrid(g, g, [0.0]), -1).reshape(-1, 3)
    n = 64
    fps = farthest_point_sampling(grid, n, seed=0, oversample=None)
    rnd = np.random.default_rng(0).choice(len(grid), n, replace=False)
    assert _min_pairwise(grid[fps]) > 2 * _min_pairwise(grid[rnd])
    assert _min_pairwise(grid[fps]) > 0.1  # ~1/sqrt(64) spacing


def test_fps_padding_and_empty():
    pts = np.arange(15, dtype=float).reshape(5, 3)
    idx = farthest_point_sampling(pts, 12)
    assert idx.tolist() == [0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 0, 1]
    with pytest.raises(ValueError, match="0 points"):
        farthest_point_sampling(np.zeros((0, 3)), 8)


def test_fps_speed():
    pts = np.random.default_rng(0).random((76_800, 3))
    farthest_point_sampling(pts, 1024)  # warm-up
    t0 = time.perf_counter()
    farthest_point_sampling(pts, 1024)
    # Loose bound to stay robust on loaded CI; typical is a few ms (the plain loop: ~30 ms).
    assert time.perf_counter() - t0 < 0.3


@pytest.mark.parametrize("cloud", ["uniform", "surfaces", "ties", "duplicates", "small"])
@pytest.mark.parametrize("oversample", [8, None])
def test_fps_is_the_plain_greedy_loop_index_for_index(cloud, oversample):
    """Tolerance: none. The pruned, compiled FPS returns exactly the indices, in order, of the plain greedy
    loop the recorder used before (same candidates, same start, first index on equal distances)."""
    rng = np.random.default_rng(3)
    pts = {
        "uniform": rng.random((30_000, 3)),
        "surfaces": np.concatenate([np.c_[rng.random((20_000, 2)), np.zeros(20_000)],
                                    np.c_[np.full(5000, 0.3), rng.random((5000, 2)) * 0.2]]),
        "ties": np.round(rng.random((12_000, 3)) * 12) / 12,  # a coarse grid: many equal distances
        "duplicates": np.concatenate([rng.random((300, 3)), np.zeros((5000, 3))]),
        "small": rng.random((1500, 3)),
    }[cloud]
    for seed in (0, 7):
        fast = farthest_point_sampling(pts, 512, seed=seed, oversample=oversample)
        assert np.array_equal(fast, reference_fps(pts, 512, seed=seed, oversample=oversample))


def test_fused_cloud_equals_back_projection_crop_and_plain_fps():
    """fuse_point_cloud's own fast path (valid pixels only, cropped axis by axis) gives the cloud of the
    documented steps, value for value."""
    views = _two_views()
    for v in views:
        v.depth[::7, ::5] = np.inf  # some background
    cfg = PointCloudConfig(num_points=300)
    chunks = []
    for depth, fovy, pos, mat, _ in views:
        pts, valid = depth_to_points(depth, fovy, pos, mat)
        chunks.append(pts[valid & crop_box(pts, cfg.crop_lo, cfg.crop_hi)])
    cloud = np.concatenate(chunks)
    expected = cloud[reference_fps(cloud, 300)].astype(np.float32)
    assert np.array_equal(fuse_point_cloud(views, cfg), expected)


def test_back_projection_matches_the_matrix_product_form():
    """Tolerance 1e-12 m: points written out per axis equal cam_pos + cam_mat @ p_cam up to rounding."""
    w, h, fovy = 80, 60, 50.0
    pos = np.array([-0.9, 0.2, 0.7])
    mat = look_at(pos, [-0.3, 0.0, 0.0])
    depth = plane_depth(w, h, fovy, pos, mat)
    pts, _ = depth_to_points(depth, fovy, pos, mat)
    k = intrinsics(w, h, fovy)
    u, v = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    d = depth.astype(np.float64).ravel()
    p_cam = np.stack([(u.ravel() - k[0, 2]) / k[0, 0] * d, -(v.ravel() - k[1, 2]) / k[1, 1] * d, -d], axis=1)
    assert np.abs(pts - (p_cam @ mat.T + pos)).max() < 1e-12


def _two_views(rgb=False):
    w, h = 64, 48
    views = []
    for pos in ([0.4, 0.0, 0.8], [-0.3, 0.8, 0.6]):
        pos = np.array(pos)
        mat = look_at(pos, [-0.3, 0.0, 0.0])
        depth = plane_depth(w, h, 55.0, pos, mat)
        col = None
        if rgb:
            col = np.random.default_rng(0).integers(0, 256, (h, w, 3), dtype=np.uint8)
        views.append(DepthView(depth, 55.0, pos, mat, col))
    return views


def test_fuse_xyz():
    cfg = PointCloudConfig(num_points=512)
    views = [tuple(v) for v in _two_views()]  # plain tuples are accepted
    cloud = fuse_point_cloud(views, cfg)
    assert cloud.shape == (512, 3) and cloud.dtype == np.float32
    assert crop_box(cloud, cfg.crop_lo, cfg.crop_hi).all()
    assert np.abs(cloud[:, 2]).max() < 1e-5
    assert np.array_equal(cloud, fuse_point_cloud(views, cfg))


def test_fuse_rgb():
    cfg = PointCloudConfig(num_points=256, use_rgb=True)
    cloud = fuse_point_cloud(_two_views(rgb=True), cfg)
    assert cloud.shape == (256, 6)
    assert cloud[:, 3:].min() >= 0.0 and cloud[:, 3:].max() <= 1.0
    with pytest.raises(ValueError, match="no rgb"):
        fuse_point_cloud(_two_views(rgb=False), cfg)


def test_fuse_empty_crop_raises():
    cfg = PointCloudConfig(crop_lo=(5, 5, 5), crop_hi=(6, 6, 6))
    with pytest.raises(ValueError, match="no points left"):
        fuse_point_cloud(_two_views(), cfg)


MJCF = """
<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <geom name="box" type="box" pos="0 0 0.05" size="0.05 0.05 0.05"/>
    <camera name="cam" pos="0 -0.5 0.7" xyaxes="1 0 0 0 0.7 0.5" fovy="45"/>
  </worldbody>
</mujoco>
"""


def test_matches_mujoco_render():
    import mujoco

    model = mujoco.MjModel.from_xml_string(MJCF)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    renderer = mujoco.Renderer(model, 48, 64)  # (height, width); set-up installs EGL, so this must work
    try:
        renderer.enable_depth_rendering()
        renderer.update_scene(data, camera="cam")
        depth = renderer.render()
    finally:
        renderer.close()
    assert depth.shape == (48, 64)

    cid = model.camera("cam").id
    pts, valid = depth_to_points(
        depth, float(model.cam_fovy[cid]), data.cam_xpos[cid],
        data.cam_xmat[cid].reshape(3, 3),
    )
    p = pts[valid]
    assert len(p) == 48 * 64  # the floor fills the whole view
    in_fp = (np.abs(p[:, 0]) < 0.045) & (np.abs(p[:, 1]) < 0.045)
    out_fp = (np.abs(p[:, 0]) > 0.06) | (np.abs(p[:, 1]) > 0.06)
    plane = p[out_fp]
    assert len(plane) > 1000
    assert np.abs(plane[:, 2]).max() < 2e-3
    top = p[in_fp & (p[:, 2] > 0.05)]
    assert len(top) > 5
    assert np.abs(top[:, 2] - 0.1).max() < 2e-3
