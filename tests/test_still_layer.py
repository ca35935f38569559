"""Still layers (`sim.still_layer`): what stays still through a recording is drawn once per still camera, and
each frame draws only what moves over it. The frames must be the renderer's own pixels, and layering must
stand aside wherever a still geom's pixels could depend on what moves."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import copy  # noqa: E402

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from recording_path import path_actions, path_env, recorder_config  # noqa: E402

from humanoidgen.episodes.recorder import EpisodeRecorder  # noqa: E402
from humanoidgen.episodes.render_replay import render_recording  # noqa: E402
from humanoidgen.sim.cameras import CameraRig, pose_data  # noqa: E402
from humanoidgen.sim.still_layer import STILL_GROUP, StillLayer, layered_model, still_parts  # noqa: E402


@pytest.fixture(scope="module")
def recording():
    env = path_env()
    rec = EpisodeRecorder(env, recorder_config(cameras=("head", "front", "left_wrist", "right")))
    for a in path_actions(env):
        env.step(a)
        rec(a)
    return env.model, rec.configurations, rec.config


def test_the_still_world_and_cameras_are_found_and_the_swinging_arms_are_not(recording):
    model, configurations, _ = recording
    still = still_parts(model, configurations)
    assert still.worth_layering
    assert still.cameras >= {"head", "front", "left", "right"}
    assert not {"left_wrist", "right_wrist"} & still.cameras
    names = {model.geom(int(g)).name for g in np.flatnonzero(still.geoms)}
    assert "floor" in names
    hand = model.geom_bodyid == model.body("L_index_proximal").id
    assert hand.any() and not still.geoms[hand].any()
    hidden = model.geom_group == 3
    assert not still.geoms[hidden].any()  # only drawn geoms are layered


def test_layered_frames_are_the_renderers_own_pixels(recording):
    model, configurations, cfg = recording
    args = (model, configurations, cfg.cameras, cfg.width, cfg.height, cfg.depth, cfg.point_cloud_cameras,
            cfg.num_points)
    plain = render_recording(*args, threads=1, still_layers=False)
    layered = render_recording(*args, threads=2, still_layers=True)
    assert set(plain) == set(layered)
    for key in plain:
        assert np.array_equal(plain[key], layered[key]), key
    assert model.geom_group.max() < STILL_GROUP  # the caller's model is left alone (a copy is layered)


def test_a_geom_that_moves_in_one_frame_only_is_not_still(recording):
    model, configurations, _ = recording
    qs = [configurations[0].copy() for _ in range(5)]
    cube = model.body("cube_0")
    cube_geoms = model.geom_bodyid == cube.id
    assert still_parts(model, qs).geoms[cube_geoms].all()
    qs[2][model.jnt_qposadr[cube.jntadr[0]]] += 1e-9  # a nanometre, in one frame
    still = still_parts(model, qs)
    assert not still.geoms[cube_geoms].any()
    assert still.geoms[model.geom("floor").id]


def test_nothing_is_layered_where_a_pixel_could_depend_on_what_moves(recording):
    model, configurations, _ = recording
    assert not still_parts(model, configurations, shadows=True).worth_layering
    see_through = copy.copy(model)
    see_through.geom_rgba[see_through.geom("floor").id, 3] = 0.5
    assert not still_parts(see_through, configurations).worth_layering
    mirror = copy.copy(model)
    mirror.mat_reflectance[mirror.geom_matid[mirror.geom("floor").id]] = 0.3
    assert not still_parts(mirror, configurations).worth_layering
    assert not still_parts(model, configurations[:1]).worth_layering


def test_a_layer_goes_under_nearer_moving_pixels_only():
    layer = StillLayer(rgb=np.full((1, 3, 3), 7, np.uint8), zbuf=np.array([[0.5, 0.5, 0.5]], np.float32),
                       zero_far=True)
    rgb = np.array([[[1, 1, 1], [2, 2, 2], [3, 3, 3]]], np.uint8)
    zbuf = np.array([[0.9, 0.5, 0.0]], np.float32)  # nearer, a tie, nothing drawn (far plane)
    layer.under(rgb, zbuf)
    assert rgb[0, :, 0].tolist() == [1, 7, 7]
    assert zbuf.tolist() == [[pytest.approx(0.9), 0.5, 0.5]]
    standard = StillLayer(rgb=layer.rgb, zbuf=layer.zbuf, zero_far=False)  # 0 at the near plane
    rgb2, z2 = np.zeros((1, 3, 3), np.uint8), np.array([[0.1, 0.5, 1.0]], np.float32)
    standard.under(rgb2, z2)
    assert rgb2[0, :, 0].tolist() == [0, 7, 7]


def test_a_layer_is_for_colour_and_depth_only(recording):
    model, configurations, _ = recording
    rig = CameraRig(layered_model(model, still_parts(model, configurations)), 64, 48, extra_groups=(STILL_GROUP,))
    try:
        data = mujoco.MjData(rig.model)
        pose_data(rig.model, data, configurations[0])
        layer = StillLayer(*rig.draw_raw(data, "front", (STILL_GROUP,)), rig.zero_far)
        with pytest.raises(ValueError, match="colour and depth only"):
            rig.render(data, "front", over=layer)
        frame = rig.render(data, "front", segmentation=False, groups=(0, 1, 2), over=layer)
        whole = rig.render(data, "front", segmentation=False)
        assert np.array_equal(frame.rgb, whole.rgb) and np.array_equal(frame.depth, whole.depth)
    finally:
        rig.close()
