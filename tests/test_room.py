"""Rooms: the O -> O' transform (round trips), reproducible and distinct rooms, the keep-out box, and a room
scene whose physics cost stays that of the table."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from humanoidgen.scenes.frames import (
    apply_point, apply_pose, apply_vector, compose, frame, inverse, o_to_o_prime, table_frame,
)
from humanoidgen.scenes.room import (
    KEEP_OUT, SURFACE_HEIGHT_RANGE, Room, footprint, generate_room, keep_out_in_room, room_seed_for,
)
from humanoidgen.sim.geometry import quat_to_mat


def test_transform_maps_o_onto_o_prime_and_round_trips():
    T = o_to_o_prime(frame(np.array([2.0, 3.0, 0.95]), math.pi / 2))
    # O's origin and axes land on O''s.
    assert np.allclose(apply_point(T, table_frame().t), [2.0, 3.0, 0.95])
    assert np.allclose(apply_vector(T, [1, 0, 0]), [0, 1, 0])
    assert np.allclose(apply_vector(T, [0, 0, 1]), [0, 0, 1])
    rng = np.random.default_rng(0)
    p, v = rng.normal(size=(5, 3)), rng.normal(size=(5, 3))
    back = inverse(T)
    assert np.allclose(apply_point(back, apply_point(T, p)), p)
    assert np.allclose(apply_vector(back, apply_vector(T, v)), v)
    # Points and axes stay consistent: a point plus an axis maps to the mapped point plus the mapped axis.
    assert np.allclose(apply_point(T, p + v), apply_point(T, p) + apply_vector(T, v))
    q = np.array([0.9, 0.1, -0.3, 0.2])
    pos2, q2 = apply_pose(T, p[0], q)
    pos3, q3 = apply_pose(back, pos2, q2)
    assert np.allclose(pos3, p[0]) and np.allclose(quat_to_mat(q3), quat_to_mat(q))
    # A key point given in an object's pose maps like the pose: R' (k) + t' = T (R k + t).
    k = np.array([0.05, -0.02, 0.1])
    assert np.allclose(quat_to_mat(q2) @ k + pos2, apply_point(T, quat_to_mat(q) @ k + p[0]))
    assert np.allclose(compose(T, back).R, np.eye(3)) and np.allclose(compose(T, back).t, 0)


def test_same_seed_same_room_and_serialization_round_trip():
    a, b = generate_room(17), generate_room(17)
    assert a == b
    assert Room.from_dict(json.loads(json.dumps(a.to_dict()))) == a
    assert generate_room(18) != a


def test_at_least_120_distinct_rooms_all_clear_of_the_workspace():
    keys = set()
    for seed in range(120):
        room = generate_room(seed)
        keys.add(json.dumps(room.to_dict(), sort_keys=True, default=str))
        assert SURFACE_HEIGHT_RANGE[0] <= room.surface_height <= SURFACE_HEIGHT_RANGE[1]
        keep = keep_out_in_room(room.transform)
        sx, sy, _ = room.size
        assert 0 < keep[0] and keep[1] < sx and 0 < keep[2] and keep[3] < sy, f"room {seed}: workspace outside"
        for p in room.parts:
            if p.kind == "wall":
                continue
            f = footprint(p)
            assert not (f[0] < keep[1] and keep[0] < f[1] and f[2] < keep[3] and keep[2] < f[3]), \
                f"room {seed}: {p.kind} in the keep-out box"
    assert len(keys) == 120


def test_room_seed_option():
    assert room_seed_for(None, 3) is None
    assert room_seed_for("12", 3) == 12 and room_seed_for(12, 3) == 12
    assert room_seed_for("random", 3) == room_seed_for("random", 3) != room_seed_for("random", 4)
    with pytest.raises(ValueError, match="--room"):
        room_seed_for("kitchen", 0)


def test_keep_out_box_holds_table_robot_and_world_cameras():
    from humanoidgen.sim.cameras import CAMERAS
    from humanoidgen.sim.layout import ROBOT_BASE_POS, TABLE_X, TABLE_Y

    x0, x1, y0, y1 = KEEP_OUT
    pts = [(TABLE_X[0], TABLE_Y[0]), (TABLE_X[1], TABLE_Y[1]), ROBOT_BASE_POS[:2]]
    pts += [c.eye[:2] for c in CAMERAS if c.body is None]
    for x, y in pts:
        assert x0 < x < x1 and y0 < y < y1


def test_room_scene_is_static_visual_and_moves_the_robot_with_the_floor():
    from humanoidgen.scenes.dressing import SceneDressing
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder

    dressing = SceneDressing.from_seeds(room_seed=5)
    room = dressing.room
    builder = SceneBuilder(surface_height=dressing.surface_height, dressing=dressing)
    builder.add_cube()
    scene = builder.build()
    m = scene.model
    added = [g for g in range(m.ngeom) if (m.geom(g).name or "").startswith("room_")]
    assert len(added) == len(room.parts) + 1
    assert all(m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0 and m.geom_bodyid[g] == 0 for g in added)
    env = HumanoidEnv(scene)
    pelvis_z = env.data.xpos[m.body("pelvis").id][2]
    floor_z = m.geom("floor").pos[2]
    assert pelvis_z - floor_z == pytest.approx(1.03, abs=1e-9)  # the feet stay on the floor
    assert floor_z == pytest.approx(-room.surface_height)
    # In the room's own frame the work surface sits at O' and at the room's surface height.
    T = room.transform
    assert np.allclose(apply_point(T, table_frame().t), room.o_prime)


def test_hgen_render_room(tmp_path):
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app

    out = tmp_path / "room.png"
    res = CliRunner().invoke(app, ["render", "--room", "4", "--visuals", "2", "--width", "64", "--height", "48",
                                   "--settle", "0", "--out", str(out)])
    assert res.exit_code == 0, res.output
    assert out.exists() and "room 4" in res.output


def test_collect_records_the_dressing(monkeypatch):
    from humanoidgen.episodes import collect
    from humanoidgen.episodes.result import EpisodeResult
    from humanoidgen.episodes.task_episode import EpisodeRequest
    from humanoidgen.scenes.dressing import episode_dressing

    seen = []

    def fake_run(req, **kwargs):  # collect asks for the arrays unrendered (render=False)
        seen.append(req.dressing)
        return EpisodeResult(req.task, req.seed, True, [], [], 0.0, 0.0, 0.0, {}, []), None

    monkeypatch.setattr(collect, "run_task_episode", fake_run)
    d = episode_dressing("random", True, 8)
    record, _ = collect.attempt(EpisodeRequest("blocks_stack_easy", 8, dressing=d))
    assert record["dressing"] == d == seen[0]
