"""Recording: physics first, images rendered afterwards from the recorded configurations, depth in
millimetres, lighter robot meshes in recorded images. What was recorded before these changes is in
tests/data/recording_reference.npz (see tests/recording_path.py); tolerances:

* state and actions: bit-identical;
* images at the same level of detail (full): identical;
* depth: within 1 mm (stored in whole millimetres: within 0.5 mm), background (nothing within 65.5 m) -> inf;
* point clouds: within 1e-6 m (float32 rounding of points computed per axis instead of through BLAS).
"""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import io  # noqa: E402
import zipfile  # noqa: E402
from pathlib import Path  # noqa: E402

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
import zstandard  # noqa: E402
from recording_path import REFERENCE_FRAMES, path_actions, path_env, recorder_config  # noqa: E402

from humanoidgen.episodes.dataset import EpisodeStore, read_episode, write_episode  # noqa: E402
from humanoidgen.episodes.depth_units import decode_depth, encode_depth  # noqa: E402
from humanoidgen.episodes.recorder import EpisodeRecorder, matching_render_model  # noqa: E402
from humanoidgen.sim.meshes import DEFAULT_MAX_FACES, cluster, recording_faces, visual_detail  # noqa: E402

REFERENCE = Path(__file__).parent / "data" / "recording_reference.npz"
STATE = ("action", "joint_pos", "qpos", "time", "ee_pose", "object_pose")


def record(**config) -> tuple[EpisodeRecorder, object]:
    env = path_env()
    rec = EpisodeRecorder(env, recorder_config(**config))
    for a in path_actions(env):
        env.step(a)
        rec(a)
    return rec, env


@pytest.fixture(scope="module")
def reference() -> dict[str, np.ndarray]:
    with np.load(REFERENCE) as z:
        return {k.replace("__", "/"): z[k] for k in z.files}


@pytest.fixture(scope="module")
def full_detail():
    rec, _ = record(visual_faces=DEFAULT_MAX_FACES)
    return rec.arrays()


def test_state_is_bit_identical_to_the_reference(full_detail, reference):
    for key in STATE:
        assert full_detail[key].dtype == reference[key].dtype
        assert np.array_equal(full_detail[key], reference[key]), key


def test_full_detail_images_replayed_from_the_physics_equal_those_rendered_during_it(full_detail, reference):
    frames = list(REFERENCE_FRAMES)
    for cam in ("head", "front", "left_wrist"):
        assert np.array_equal(full_detail[f"rgb/{cam}"][frames], reference[f"rgb/{cam}"]), cam
        stored = full_detail[f"depth/{cam}"]
        assert stored.dtype == np.uint16
        depth, ref = decode_depth(stored[frames]), reference[f"depth/{cam}"]
        seen = ref < 65.534
        assert np.abs(depth[seen] - ref[seen]).max() <= 0.0005 + 1e-6, cam
        assert np.isinf(depth[~seen]).all()
    assert np.abs(full_detail["point_cloud"][frames] - reference["point_cloud"]).max() < 1e-6


def test_recording_detail_changes_pixels_only_a_little(reference):
    rec, env = record()
    faces = rec.config.faces
    assert faces == recording_faces(64, 48) < DEFAULT_MAX_FACES
    with visual_detail(faces):
        from humanoidgen.sim.scene import SceneBuilder

        builder = SceneBuilder()
        builder.add_cube()
        model = matching_render_model(env.model, builder.build().model)
    arrays = rec.arrays(model=model)
    for key in STATE:
        assert np.array_equal(arrays[key], reference[key])
    frames = list(REFERENCE_FRAMES)
    diff = np.concatenate([np.abs(arrays[f"rgb/{c}"][frames].astype(int) - reference[f"rgb/{c}"]).ravel()
                           for c in ("head", "front", "left_wrist")])
    assert 0 < diff.mean() < 6  # measured: about 2 levels at 320x240 (bench/results/recording_detail.json)
    assert (diff > 32).mean() < 0.05


def test_images_are_rendered_only_when_asked():
    rec, _ = record(visual_faces=DEFAULT_MAX_FACES)
    arrays = rec.arrays(images=False)
    assert set(arrays) == set(STATE)


def test_visual_detail_leaves_the_physics_alone():
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder

    def run(faces):
        with visual_detail(faces):
            builder = SceneBuilder()
            builder.add_cube()
            env = HumanoidEnv(builder.build())
        for a in path_actions(env)[:20]:
            env.step(a)
        return env

    full, light = run(DEFAULT_MAX_FACES), run(200)
    assert np.array_equal(full.model.body_mass, light.model.body_mass)
    assert np.array_equal(full.model.body_inertia, light.model.body_inertia)
    assert np.array_equal(full.data.qpos, light.data.qpos)
    visual = [g for g in range(light.model.ngeom) if light.model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH
              and light.model.geom_group[g] == 1]
    assert all(light.model.mesh_facenum[light.model.geom_dataid[g]] <= 200 for g in visual)


def test_clustering_holds_the_face_budget():
    rng = np.random.default_rng(0)
    # Many small separate pieces: what quadric decimation cannot reduce.
    base = rng.random((400, 3))
    verts = np.concatenate([base + rng.normal(0, 1e-3, (400, 3)) for _ in range(3)])
    faces = np.stack([np.arange(400), np.arange(400) + 400, np.arange(400) + 800], axis=1).astype(np.int32)
    v, f = cluster(verts, faces, 100)
    assert 0 < len(f) <= 100 and f.max() < len(v)


def test_depth_in_millimetres_round_trips_within_half_a_millimetre():
    depth = np.array([[0.2, 1.23456, 65.5], [np.inf, np.nan, 97.8]], np.float32)
    mm = encode_depth(depth)
    assert mm.dtype == np.uint16 and mm.tolist() == [[200, 1235, 65500], [0, 0, 0]]
    back = decode_depth(mm)
    assert back.dtype == np.float32
    assert np.abs(back[0] - depth[0]).max() <= 0.0005 + 1e-6
    assert np.isinf(back[1]).all()


def test_episode_files_are_zips_of_npy_members_and_load_in_metres(tmp_path):
    rng = np.random.default_rng(0)
    arrays = {"action": rng.random((5, 26)).astype(np.float32),
              "rgb/head": rng.integers(0, 255, (5, 6, 8, 3), dtype=np.uint8),
              "depth/head": encode_depth(rng.random((5, 6, 8)) + 0.3)}
    path = tmp_path / "e.npz"
    with open(path, "wb") as f:
        write_episode(f, arrays)
    with np.load(path) as z:  # any reader: state as plain .npy members
        assert np.array_equal(z["action"], arrays["action"])
    with zipfile.ZipFile(path) as zf:  # image stacks: whole .npy files, zstd-compressed
        for key in ("rgb/head", "depth/head"):
            raw = zstandard.ZstdDecompressor().decompress(zf.read(key.replace("/", "__") + ".npy.zst"))
            assert np.array_equal(np.load(io.BytesIO(raw)), arrays[key])
    assert {k: v.dtype for k, v in read_episode(path).items()} == {k: v.dtype for k, v in arrays.items()}
    store = EpisodeStore(tmp_path / "ds")
    store.create({"task": "t"})
    store.add({"seed": 0, "success": True}, arrays)
    loaded = store.load(0)
    assert loaded["depth/head"].dtype == np.float32
    assert np.array_equal(loaded["depth/head"], decode_depth(arrays["depth/head"]))
    assert np.array_equal(loaded["rgb/head"], arrays["rgb/head"])
    assert store.corrupt() == {}


def test_files_of_format_2_still_load(tmp_path):
    """Before format 3, stacks were deflated .npy members in Fortran order (a plain npz)."""
    rng = np.random.default_rng(1)
    rgb = np.asfortranarray(rng.integers(0, 255, (4, 6, 8, 3), dtype=np.uint8))
    depth = np.asfortranarray(encode_depth(rng.random((4, 6, 8)) + 0.3))
    store = EpisodeStore(tmp_path / "ds")
    store.create({"task": "t"})
    store.add({"seed": 0, "success": True}, {"action": np.zeros((4, 26), np.float32)})
    np.savez_compressed(store.episode_path(0), action=np.zeros((4, 26), np.float32), rgb__head=rgb,
                        depth__head=depth)
    loaded = store.load(0)
    assert np.array_equal(loaded["rgb/head"], rgb)
    assert np.array_equal(loaded["depth/head"], decode_depth(depth))
    assert store.corrupt() == {}


def test_a_damaged_image_stack_is_found(tmp_path):
    arrays = {"action": np.zeros((3, 26), np.float32),
              "rgb/head": np.random.default_rng(2).integers(0, 255, (3, 6, 8, 3), dtype=np.uint8)}
    store = EpisodeStore(tmp_path / "ds")
    store.create({"task": "t"})
    store.add({"seed": 0, "success": True}, arrays)
    path = store.episode_path(0)
    with zipfile.ZipFile(path) as zf:
        info = zf.getinfo("rgb__head.npy.zst")
    data = bytearray(path.read_bytes())
    # A flipped byte inside the stored member: zip's CRC and zstd's own checksum both catch it.
    data[info.header_offset + 30 + len(info.filename) + info.compress_size // 2] ^= 0xFF
    path.write_bytes(bytes(data))
    assert 0 in store.corrupt()


def test_rendering_threads_do_not_change_the_recording(full_detail):
    from humanoidgen.episodes.render_replay import render_recording

    rec, env = record(visual_faces=DEFAULT_MAX_FACES)
    cfg = rec.config
    one = render_recording(env.model, rec.configurations, cfg.cameras, cfg.width, cfg.height, cfg.depth,
                           cfg.point_cloud_cameras, cfg.num_points, threads=1, cloud_floor=cfg.point_cloud_floor)
    three = render_recording(env.model, rec.configurations, cfg.cameras, cfg.width, cfg.height, cfg.depth,
                             cfg.point_cloud_cameras, cfg.num_points, threads=3,
                             cloud_floor=cfg.point_cloud_floor)
    for key in one:
        assert np.array_equal(one[key], three[key]), key
        assert np.array_equal(one[key], full_detail[key]), key


def test_the_cloud_floor_is_checked_and_recorded_in_meta():
    """The recorder's cloud floor is a validated setting (a typo of 5 for 0.005 would crop every object away)
    that meta.json keeps (`asdict`), so an env built from a dataset observes what it recorded."""
    from dataclasses import asdict

    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.sim.pointcloud import CLOUD_FLOOR

    assert asdict(RecorderConfig())["point_cloud_floor"] == CLOUD_FLOOR
    with pytest.raises(ValueError, match="point_cloud_floor"):
        RecorderConfig(point_cloud_floor=5.0)
