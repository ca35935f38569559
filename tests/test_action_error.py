"""bench/action_error.py: the teacher-forced error is the largest miss over the executed actions, per joint, and
the summary keeps only the joints the demonstrations move, beside their span."""

from __future__ import annotations

import numpy as np
import pytest

from bench_scripts import load_bench

torch = pytest.importorskip("torch")


class _Off:
    """A stand-in policy that predicts the recorded actions plus a known offset on joint 1."""

    obs_keys = ("state",)

    def __init__(self, actions: np.ndarray, offset: float) -> None:
        from types import SimpleNamespace

        self.cfg = SimpleNamespace(n_obs_steps=2, n_action_steps=3)
        self.actions, self.offset = actions, offset

    def predict_action(self, obs, generator=None):
        t = int(obs["state"][0, -1, 0])  # the state carries its frame number
        pred = self.actions[t: t + 3].copy()
        pred[:, 1] += self.offset * np.arange(1, 4)  # a miss growing over the executed actions
        return {"action": torch.as_tensor(pred[None])}


def test_the_error_is_the_largest_miss_per_joint_and_only_moving_joints_are_summarized():
    bench = load_bench("action_error")
    ends = np.array([10, 25])
    actions = np.zeros((25, 4))
    actions[:, 1] = np.linspace(0, 2.0, 25)  # joint 1 moves 2 rad, joint 2 a little, joints 0 and 3 not at all
    actions[:, 2] = np.linspace(0, 0.5, 25)
    state = np.arange(25, dtype=float)[:, None].repeat(4, axis=1)
    frames = bench.sample_frames(ends, 2, 3, 40)
    starts = [0, 10]
    for t in frames:  # every frame has its observations and executed actions inside one episode
        e = int(t >= 10)
        assert starts[e] + 1 <= t <= ends[e] - 3
    errors = bench.teacher_forced(_Off(actions, 0.01), {"state": state, "action": actions}, frames)
    np.testing.assert_allclose(errors[:, 1], 0.03)
    np.testing.assert_allclose(errors[:, [0, 2, 3]], 0.0, atol=1e-12)
    s = bench.summary(errors, actions)
    assert s["joints"] == [1, 2] and s["span_rad"] == [2.0, 0.5]
    assert s["mean_error_rad"] == [0.03, 0.0] and s["error_per_span"] == [0.015, 0.0]


class _Hands:
    """A stand-in for HandFrames: the left hand sits at joints 0-2, the right hand never moves."""

    def positions(self, actions):
        out = np.zeros((len(actions), 2, 3))
        out[:, 0] = np.asarray(actions)[:, :3]
        return out


def test_the_hands_miss_is_measured_where_they_land_at_the_predicted_targets():
    bench = load_bench("action_error")
    actions = np.zeros((25, 4))
    actions[:, 1] = np.linspace(0, 2.0, 25)
    state = np.arange(25, dtype=float)[:, None].repeat(4, axis=1)
    frames = bench.sample_frames(np.array([25]), 2, 3, 20)
    got = bench.hand_misses(_Off(actions, 0.01), {"state": state, "action": actions}, frames, _Hands())
    assert set(got) == {"left"}  # the right hand never moves
    assert got["left"]["median_m"] == pytest.approx(0.03)  # joint 1's miss, the largest of the three executed


def test_hand_frames_are_the_simulations_own_at_those_joints():
    import mujoco

    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    _, sim = build_scene(load_task("close_drawer"), 0, settle_s=0.0)
    bench = load_bench("action_error")
    rng = np.random.default_rng(0)
    actions = sim.joint_positions()[None].repeat(4, axis=0)
    actions[:, :14] += rng.uniform(-0.3, 0.3, (4, 14))
    got = bench.HandFrames(sim.model).positions(actions)
    for a, p in zip(actions, got):
        sim.set_joint_positions(a)
        mujoco.mj_kinematics(sim.model, sim.data)
        np.testing.assert_allclose(p, [sim.hand_pose(s)[0] for s in ("left", "right")], atol=1e-9)
