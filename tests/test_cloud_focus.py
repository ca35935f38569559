"""sim/cloud_focus.py and the settings that name it: a point cloud with a share of its points drawn near the hands.

The share holds exactly in the whole cloud and within one point in every prefix (a policy reads the first
num_points); with no point near a hand, or a share of 0, the cloud is the even sample it always was; the env
centres the focus where the planner API puts each hand's grasp point, and its cloud holds the share there."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np
import pytest

from humanoidgen.sim.cloud_floor import NEAR_HANDS_RADIUS
from humanoidgen.sim.cloud_focus import focused_sample, near_mask
from humanoidgen.sim.fps import farthest_point_sampling
from humanoidgen.sim.pointcloud import PointCloudConfig, fuse_point_cloud


def _cloud(n: int = 20000) -> np.ndarray:
    return np.random.default_rng(0).uniform([-0.6, -0.5, 0.0], [0.0, 0.5, 0.4], (n, 3))


def test_the_share_is_drawn_near_the_centres_and_every_prefix_keeps_it():
    pts = _cloud()
    centres = np.array([[-0.3, 0.2, 0.2], [-0.3, -0.2, 0.2]])
    idx = focused_sample(pts, 256, 0.5, centres, 0.1)
    assert idx.shape == (256,) and len(set(idx.tolist())) == 256
    near = near_mask(pts[idx], centres, 0.1)
    # the whole-crop half lands near a hand at the ball's share of the box's volume (about 3%), not 50%
    assert 128 <= near.sum() <= 128 + 16
    focused = near_mask(pts[focused_sample(pts, 256, 0.5, centres, 0.1)], centres, 0.1)
    even = near_mask(pts[farthest_point_sampling(pts, 256)], centres, 0.1)
    assert focused.sum() > 5 * even.sum()
    # the near half is sampled by FPS too: spread over both balls, not heaped in one
    on_left = np.linalg.norm(pts[idx] - centres[0], axis=1) <= 0.1
    assert 40 <= on_left.sum() <= 100
    # any prefix holds its share of the near sample: the first 64 points of a 256-point cloud hold 32 of them
    near_sampled = np.isin(idx, np.flatnonzero(near_mask(pts, centres, 0.1)))
    for k in (8, 64, 100, 256):
        assert abs(near_sampled[:k].sum() - 0.5 * k) <= 1 + 0.05 * k


def test_no_point_near_a_hand_or_no_share_is_the_even_sample():
    pts = _cloud()
    even = farthest_point_sampling(pts, 128)
    np.testing.assert_array_equal(focused_sample(pts, 128, 0.0, np.zeros((2, 3)), 0.1), even)
    np.testing.assert_array_equal(focused_sample(pts, 128, 0.5, np.array([[5.0, 5.0, 5.0]]), 0.1), even)


def test_fuse_focuses_only_when_given_the_hands_and_settings_refuse_a_bad_share():
    from test_pointcloud import _two_views

    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.episodes.recorder import RecorderConfig

    views = _two_views()
    plain = fuse_point_cloud(views, PointCloudConfig(num_points=256))
    focus = plain[:1].astype(np.float64)  # a point on the plane the views see
    cfg = PointCloudConfig(num_points=256, near_hands=0.5, near_radius=0.05)
    np.testing.assert_array_equal(fuse_point_cloud(views, cfg), plain)  # no focus given: the even sample
    cloud = fuse_point_cloud(views, cfg, focus)
    assert near_mask(cloud, focus, 0.05).sum() >= 128 > near_mask(plain, focus, 0.05).sum()
    for bad in (-0.1, 1.0, float("nan")):
        with pytest.raises(ValueError, match="point_cloud_near_hands must be in"):
            PointCloudConfig(near_hands=bad)
        with pytest.raises(ValueError, match="point_cloud_near_hands must be in"):
            TaskEnvConfig(point_cloud_near_hands=bad)
        with pytest.raises(ValueError, match="point_cloud_near_hands must be in"):
            RecorderConfig(point_cloud_near_hands=bad)
    with pytest.raises(ValueError, match="near_radius"):
        PointCloudConfig(near_radius=0.0)
    # what a dataset records, an env built from it observes
    assert TaskEnvConfig.from_recorder({"point_cloud_near_hands": 0.5}).point_cloud_near_hands == 0.5
    assert TaskEnvConfig.from_recorder({}).point_cloud_near_hands == 0.0


def test_the_env_focuses_on_the_planner_apis_grasp_points():
    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.episodes.render_replay import focus_points
    from humanoidgen.objects.queries import get_point_in_env

    counts = {}
    for share in (0.0, 0.5):
        env = HumanoidTaskEnv("close_drawer", config=TaskEnvConfig(cameras=(), num_points=256,
                                                                   point_cloud_near_hands=share))
        try:
            obs, _ = env.reset(seed=0)
            sim = env.unwrapped.sim
            centres = focus_points(sim.model, sim.data)
            for k, side in enumerate(("left", "right")):
                np.testing.assert_allclose(centres[k], get_point_in_env(sim, f"grasp_point_base_{side}_hand"),
                                           atol=1e-9)
            counts[share] = int(near_mask(obs["point_cloud"], centres, NEAR_HANDS_RADIUS).sum())
        finally:
            env.close()
    assert counts[0.5] >= 128 and counts[0.5] > 2 * counts[0.0], counts


def test_a_collected_episode_records_the_focused_cloud_and_the_command_refuses_a_bad_share(tmp_path):
    """The recording path (rendered after the run from the recorded configurations) focuses as the env does: in
    every frame half the points lie near where the hands' grasp points were."""
    import mujoco
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.episodes.render_replay import focus_points

    rec = RecorderConfig(cameras=(), point_cloud=True, num_points=128, every=10, point_cloud_near_hands=0.5)
    assert collect("close_drawer", 1, tmp_path / "d", recorder=rec).kept == 1
    store = EpisodeStore(tmp_path / "d")
    assert store.meta()["recorder"]["point_cloud_near_hands"] == 0.5
    [kept] = store.kept()
    arrays = store.load(kept["episode"], ("qpos", "point_cloud"))
    env = HumanoidTaskEnv("close_drawer", config=_env_config(store))
    try:
        env.reset(seed=int(kept["seed"]))
        model = env.unwrapped.sim.model
        data = mujoco.MjData(model)
        near = []
        for qpos, cloud in zip(arrays["qpos"], arrays["point_cloud"]):
            data.qpos[:] = qpos
            mujoco.mj_kinematics(model, data)
            near.append(int(near_mask(cloud, focus_points(model, data), NEAR_HANDS_RADIUS + 1e-6).sum()))
    finally:
        env.close()
    assert min(near) >= 64, near
    res = CliRunner().invoke(app, ["collect", "close_drawer", "-n", "1", "--out", str(tmp_path / "e"),
                                   "--cloud-near-hands", "1.5"])
    assert res.exit_code == 1 and "point_cloud_near_hands must be in [0, 1)" in res.output, res.output
    assert not (tmp_path / "e").exists()


def _env_config(store):
    from humanoidgen.envs.config import TaskEnvConfig

    return TaskEnvConfig.from_recorder(store.meta()["recorder"], cameras=(), point_cloud=False)
