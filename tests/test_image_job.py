"""Images of kept attempts rendered by the caller, not the plan worker (`episodes.image_job`), and written
frame by frame (`EpisodeStore` with a pending ImageJob): the same arrays as rendering them all at once."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from recording_path import path_actions, path_env, recorder_config  # noqa: E402

from humanoidgen.episodes.dataset import EpisodeStore  # noqa: E402
from humanoidgen.episodes.depth_units import encode_depth  # noqa: E402
from humanoidgen.episodes.image_job import PENDING_IMAGES, ImageJob  # noqa: E402
from humanoidgen.episodes.npy_zstd import NpyZstdStream  # noqa: E402
from humanoidgen.episodes.recorder import EpisodeRecorder, RecorderConfig  # noqa: E402
from humanoidgen.episodes.render_replay import iter_frames, render_recording  # noqa: E402
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode  # noqa: E402

SMALL = RecorderConfig(every=10, cameras=("head", "left_wrist"), width=64, height=48, point_cloud=True,
                       num_points=64)


def test_a_kept_attempt_comes_back_unrendered_and_its_file_holds_what_rendering_at_once_gives(tmp_path):
    result, arrays = run_task_episode(EpisodeRequest("block_stack_single", seed=0, recorder=SMALL), render=False)
    assert result.success
    job = arrays[PENDING_IMAGES]
    assert isinstance(job, ImageJob) and not any(k.startswith(("rgb/", "depth/", "point")) for k in arrays)
    assert job.frames == len(arrays["action"])
    at_once = job.render_arrays()
    store = EpisodeStore(tmp_path / "ds")
    store.create({"task": "block_stack_single"})
    store.add({"seed": 0, "success": True}, arrays)
    loaded = store.load(0)
    for key, value in at_once.items():
        stored = encode_depth(loaded[key]) if key.startswith("depth/") else loaded[key]
        assert np.array_equal(stored, value), key
    _, rendered = run_task_episode(EpisodeRequest("block_stack_single", seed=0, recorder=SMALL))
    for key, value in at_once.items():
        assert np.array_equal(rendered[key], value), key


def test_frames_are_the_same_whatever_the_chunks_and_threads():
    env = path_env()
    rec = EpisodeRecorder(env, recorder_config())
    for a in path_actions(env):
        env.step(a)
        rec(a)
    cfg = rec.config
    args = (env.model, rec.configurations, cfg.cameras, cfg.width, cfg.height, cfg.depth, cfg.point_cloud_cameras,
            cfg.num_points)
    whole = render_recording(*args, threads=1)
    for threads, chunk in ((1, 1), (2, 2), (3, 5)):
        frames = list(iter_frames(*args, threads=threads, chunk=chunk))
        assert [t for t, _ in frames] == list(range(len(rec.configurations)))
        for t, frame in frames:
            for key, value in frame.items():
                assert np.array_equal(value, whole[key][t]), (threads, chunk, key, t)


def test_the_workers_numbers_are_checked():
    q = np.zeros((3, 52))
    stat = np.array([1.0, 0.0, 0.0, 0.5])
    ImageJob("block_stack_single", 0, None, SMALL, q, stat)
    bad = q.copy()
    bad[1, 4] = np.nan
    for configurations, model_stat in ((bad, stat), (q[:0], stat), (q.astype(np.float32), stat),
                                       (q, np.array([0.0, 0, 0, 0])), (q, stat[:3])):
        with pytest.raises(ValueError):
            ImageJob("block_stack_single", 0, None, SMALL, configurations, model_stat)


def test_a_stack_takes_exactly_its_frames():
    stream = NpyZstdStream((2, 4, 5), np.uint16)
    with pytest.raises(ValueError):
        stream.write(np.zeros((4, 5), np.uint8))
    stream.write(np.zeros((4, 5), np.uint16))
    with pytest.raises(ValueError):
        stream.finish()
    stream.write(np.ones((4, 5), np.uint16))
    with pytest.raises(ValueError):
        stream.write(np.ones((4, 5), np.uint16))
    assert stream.finish()


def test_warm_up_fills_the_caches_and_never_raises():
    """collect warms the rendering process while the first attempt plans: the compiled point-cloud code is
    loaded for the depth type rendering gives (float32), and a task it cannot build costs nothing but time."""
    from humanoidgen.episodes.image_job import warm_up
    from humanoidgen.sim.pointcloud import _crop_pixels
    from humanoidgen.sim.still_layer import _under

    warm_up("no_such_task", SMALL)  # no exception
    warm_up("block_stack_single", SMALL)
    assert any(str(sig[0]).startswith("array(float32") for sig in _crop_pixels.signatures)
    assert any(str(sig[0]).startswith("array(uint8, 3d") for sig in _under.signatures)
