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
