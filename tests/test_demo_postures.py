"""bench/demo_postures.py: the arm postures where the hand closes, grouped into families, on synthetic episodes
whose families are known (two for the left arm; the right hand never closes and gets no row)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from humanoidgen.episodes.dataset import EpisodeStore
from humanoidgen.robots import default_robot
from bench_scripts import load_bench


def _bench():
    return load_bench("demo_postures")


def _store(root: Path, postures: list[np.ndarray]) -> EpisodeStore:
    robot = default_robot()
    names = list(robot.action_joints)
    store = EpisodeStore(root)
    store.create({"task": "synthetic_grip", "robot": robot.name, "control_hz": 50.0, "action_names": names})
    left_arm = [names.index(j) for j in robot.arm_joints["left"]]
    left_hand = [names.index(j) for j in robot.hand_joints["left"]]
    for i, q in enumerate(postures):
        t = 30
        action = np.zeros((t, len(names)), np.float32)
        # The arm travels to q over 20 actions, the hand closes at action 20 and the arm moves on (a push).
        action[:, left_arm] = np.linspace(0, 1, t)[:, None].clip(0, 20 / 29) * 29 / 20 * q
        action[20:, left_arm] += np.linspace(0, 0.3, t - 20)[:, None]
        action[20:, left_hand] = 1.2
        store.add({"seed": i, "success": True}, {"action": action})
    store.add({"seed": 99, "success": False, "error": "failed"}, None)  # not kept: not counted
    return store


def test_closing_index_finds_the_first_closed_action_after_the_opening():
    bench = _bench()
    hand = np.zeros((12, 6))
    hand[:3] = 0.6  # starts half closed, opens (pre-grasp), then closes at 7
    hand[7:] = 1.3
    assert bench.closing_index(hand) == 7
    assert bench.closing_index(np.full((12, 6), 0.4)) is None  # never moves: no grip in this episode


def test_families_counts_the_postures_apart(tmp_path):
    bench = _bench()
    a = np.array([-1.5, 0.5, -1.8, 0.8, 2.7, 0.0, 1.2])
    b = np.array([-1.7, -0.2, 2.4, 1.0, 0.4, -0.3, 1.2])  # the shoulder and forearm turned the other way
    rng = np.random.default_rng(0)
    postures = [a + rng.uniform(-0.1, 0.1, 7) for _ in range(5)] + [b + rng.uniform(-0.1, 0.1, 7) for _ in range(3)]
    _store(tmp_path / "demos", postures)
    out = tmp_path / "results"
    assert bench.main([str(tmp_path / "demos"), "--name", "t", "--results", str(out)]) == 0
    (row,) = json.loads((out / "demo_postures_t.json").read_text())["rows"]  # the right hand never closes
    assert (row["side"], row["episodes"], row["closing"]) == ("left", 8, 8)
    assert row["families"] == 2 and row["family_sizes"] == [5, 3] and row["largest_share"] == 5 / 8
    assert row["spread_rad"][2] > 4.0  # the shoulder's yaw differs by 4.2 rad between the two
    assert max(row["largest_family_spread_rad"]) < 0.2  # each family is tight
    assert (out / "demo_postures_t.png").stat().st_size > 0
    # A tolerance wider than the gap between them makes one family.
    assert bench.main([str(tmp_path / "demos"), "--name", "w", "--tol", "5", "--results", str(out)]) == 0
    assert json.loads((out / "demo_postures_w.json").read_text())["rows"][0]["families"] == 1


def test_a_folder_that_is_not_episodes_is_one_line_and_exit_2(tmp_path, capsys):
    assert _bench().main([str(tmp_path), "--results", str(tmp_path / "r")]) == 2
    assert "not an episode folder" in capsys.readouterr().err


def test_grips_at_a_joint_limit_are_counted(tmp_path):
    """Three of five grips with the wrist's yaw at the end of its range (as close_drawer's are): share 0.6, all
    on that joint; the robot's ranges are read from its compiled model."""
    bench = _bench()
    robot = default_robot()
    ranges = bench.joint_ranges(robot)
    yaw = robot.arm_joints["left"][6]
    lo, hi = ranges[yaw]
    assert lo < 0 < hi
    free = np.array([-1.5, 0.3, 0.2, 0.8, 0.5, 0.0, 0.3])
    postures = [free.copy() for _ in range(5)]
    for q in postures[:3]:
        q[6] = hi - 0.005
    _store(tmp_path / "demos", postures)
    out = tmp_path / "results"
    assert bench.main([str(tmp_path / "demos"), "--name", "t", "--results", str(out)]) == 0
    (row,) = json.loads((out / "demo_postures_t.json").read_text())["rows"]
    assert row["at_limit_share"] == 0.6
    assert row["at_limit_by_joint"] == [0, 0, 0, 0, 0, 0, 3]
