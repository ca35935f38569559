"""The gymnasium task environment: the env checker, reset(seed) giving collection's scene, and the recorded
actions of real episodes redoing the task when replayed through the environment."""

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium")

import humanoidgen.envs as envs  # noqa: E402
from humanoidgen.envs import EVAL_SEED_BASE, HumanoidTaskEnv, TaskEnvConfig  # noqa: E402
from humanoidgen.episodes.recorder import RecorderConfig  # noqa: E402
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode  # noqa: E402
from humanoidgen.sim.pointcloud import CLOUD_FLOOR, TABLE_CLOUD_FLOOR  # noqa: E402

EVERY = 5
NO_CAMERAS = TaskEnvConfig(every=EVERY, cameras=(), point_cloud=False)
# Small pictures: what matters is that the env draws what the recording drew, not the size.
SMALL = dict(every=EVERY, cameras=("head",), width=64, height=48, depth=True, point_cloud=True, num_points=256)


@pytest.fixture(scope="module")
def recorded() -> dict[tuple[str, int], dict]:
    """Reference-plan episodes recorded as `hgen collect` records them (10 Hz, no cameras: fast)."""
    out = {}
    for task, seed in (("close_drawer", 0), ("close_drawer", 1), ("block_stack_single", 0)):
        result, arrays = run_task_episode(EpisodeRequest(task, seed, recorder=RecorderConfig(every=EVERY)))
        assert result.success, (task, seed, result.failed_step)
        out[task, seed] = arrays
    result, arrays = run_task_episode(EpisodeRequest("close_drawer", 2, recorder=RecorderConfig(**SMALL)))
    assert result.success, result.failed_step
    out["pictures"] = arrays
    return out


def test_registered_and_passes_the_env_checker():
    from gymnasium.utils.env_checker import check_env

    assert envs.env_id("close_drawer") in gym.registry
    env = gym.make("humanoidgen/close_drawer-v0", cameras=("head",), width=64, height=48, num_points=256,
                   render_mode="rgb_array")
    try:
        check_env(env.unwrapped, skip_render_check=False)
        obs, info = env.reset(seed=3)
        assert obs["rgb/head"].shape == (48, 64, 3) and obs["point_cloud"].shape == (256, 3)
        assert obs["joint_pos"].shape == (26,) and obs["ee_pose"].shape == (14,)
        assert info["success"] is False and info["checks"][0]["predicate"] == "openness_at_most"
        assert env.render().shape == (480, 640, 3)
    finally:
        env.close()


def test_unseeded_reset_draws_evaluation_seeds():
    env = HumanoidTaskEnv("close_drawer", config=NO_CAMERAS)
    _, info = env.reset()
    assert info["seed"] >= EVAL_SEED_BASE
    env.close()


def test_reset_builds_the_collected_scene(recorded):
    """After one control step of the first recorded action, the whole simulator state is the recorded one."""
    env = HumanoidTaskEnv("close_drawer", config=NO_CAMERAS)
    for seed in (0, 1):
        arrays = recorded["close_drawer", seed]
        env.reset(seed=seed)
        env.sim.step(arrays["action"][0])
        np.testing.assert_allclose(env.sim.data.qpos, arrays["qpos"][0], atol=1e-6)
    other = recorded["close_drawer", 0]["qpos"][0]
    env.reset(seed=1)
    env.sim.step(recorded["close_drawer", 1]["action"][0])
    assert np.abs(env.sim.data.qpos - other).max() > 1e-3  # a different seed is a different scene
    env.close()


def test_observations_are_what_the_recording_holds(recorded):
    """rgb, depth and the point cloud of the first recorded frame, observed again in the env."""
    arrays = recorded["pictures"]
    env = HumanoidTaskEnv("close_drawer", config=TaskEnvConfig(**SMALL))
    env.reset(seed=2)
    env.sim.step(arrays["action"][0])  # the recorder's first frame follows one control step
    obs = env._observer()
    np.testing.assert_array_equal(obs["rgb/head"], arrays["rgb/head"][0])
    np.testing.assert_allclose(obs["point_cloud"], arrays["point_cloud"][0], atol=1e-6)
    stored = arrays["depth/head"][0]
    stored = stored.astype(np.float32) / 1000 if stored.dtype == np.uint16 else stored
    seen = np.isfinite(obs["depth/head"]) & (stored > 0) & np.isfinite(stored)
    np.testing.assert_allclose(obs["depth/head"][seen], stored[seen], atol=1e-6)
    np.testing.assert_allclose(obs["joint_pos"], arrays["joint_pos"][0], atol=1e-6)
    env.close()


def test_clouds_leave_the_table_out_unless_recorded_with_it(recorded):
    """The recorded cloud (and the env's) has no point on the table's surface: all above CLOUD_FLOOR; an env
    configured as recordings before the floor (TABLE_CLOUD_FLOOR) sees the table: most of its points at z = 0."""
    cloud = recorded["pictures"]["point_cloud"]
    assert cloud[..., 2].min() > CLOUD_FLOOR
    env = HumanoidTaskEnv("close_drawer", config=TaskEnvConfig(**SMALL, point_cloud_floor=TABLE_CLOUD_FLOOR))
    env.reset(seed=2)
    env.sim.step(recorded["pictures"]["action"][0])
    with_table = env._observer()["point_cloud"]
    env.close()
    assert (np.abs(with_table[:, 2]) < 1e-3).mean() > 0.3


@pytest.mark.parametrize("key", [("close_drawer", 0), ("close_drawer", 1), ("block_stack_single", 0)])
def test_replaying_recorded_actions_redoes_the_task(recorded, key):
    arrays = recorded[key]
    env = HumanoidTaskEnv(key[0], config=NO_CAMERAS)
    _, info = env.reset(seed=key[1])
    assert not info["success"]
    for action in arrays["action"]:
        _, reward, terminated, truncated, info = env.step(action)
        if terminated or truncated:
            break
    assert info["success"] and terminated and reward == 1.0, info["checks"]
    env.close()


def test_truncates_at_the_step_limit():
    env = HumanoidTaskEnv("close_drawer", config=TaskEnvConfig(every=EVERY, cameras=(), point_cloud=False,
                                                               max_steps=3))
    obs, _ = env.reset(seed=0)
    flags = [env.step(obs["joint_pos"])[3] for _ in range(3)]
    assert flags == [False, False, True]
    env.close()


def test_config_from_recorder_and_bad_values():
    cfg = TaskEnvConfig.from_recorder({"every": 5, "cameras": ["head", "front"], "width": 320, "height": 240,
                                       "depth": True, "point_cloud": True, "num_points": 1024,
                                       "point_cloud_cameras": ["head", "front", "left", "right"], "new": 1})
    assert cfg.cameras == ("head", "front") and cfg.action_hz == 10.0 and cfg.extra == {"new": 1}
    # Recorded before the cloud's floor was a setting: observed as recorded, with the table.
    assert cfg.point_cloud_floor == TABLE_CLOUD_FLOOR
    assert TaskEnvConfig.from_recorder({"every": 5, "point_cloud_floor": 0.02}).point_cloud_floor == 0.02
    with pytest.raises(ValueError, match="unknown camera"):
        TaskEnvConfig(cameras=("nose",))
    with pytest.raises(ValueError, match="every"):
        TaskEnvConfig(every=0)
