"""Temporal ensembling (policies/ensemble.py): a prediction at every step, and the action executed the weighted
mean (exp(-m i), oldest first) of every prediction covering the step; a new episode forgets the old ones."""

import math
from types import SimpleNamespace

import pytest

torch = pytest.importorskip("torch")

from humanoidgen.policies.config import PolicyConfig  # noqa: E402
from humanoidgen.policies.ensemble import TemporalEnsemble  # noqa: E402


class _Counting:
    """A stand-in policy: its j-th prediction is the value j at every step of its horizon (2 observation steps,
    horizon 4: 3 actions from now on)."""

    def __init__(self) -> None:
        self.cfg = PolicyConfig(horizon=4, n_obs_steps=2, n_action_steps=2, unet={"down_dims": [16]},
                                state_dim=1, action_dim=1)
        self.obs_keys = ("state",)
        self.normalizer = SimpleNamespace(keys=("action",))
        self.calls = 0

    def predict_action(self, obs, generator=None):
        seq = torch.full((1, 4, 1), float(self.calls))
        self.calls += 1
        return {"action_pred": seq, "action": seq[:, 1:3]}


def _run(m: float, steps: int) -> list[float]:
    ens = TemporalEnsemble(_Counting(), m)
    ens.start_episode({})
    return [float(ens.predict_action({})["action"][0, 0, 0]) for _ in range(steps)]


def test_each_step_executes_the_weighted_mean_of_the_predictions_covering_it():
    # Step k is covered by the predictions made at k-2, k-1 and k (3 actions ahead each).
    assert _run(0.0, 5) == pytest.approx([0.0, 0.5, 1.0, 2.0, 3.0])
    w = math.exp(-1.0)  # the second oldest's weight at m = 1
    assert _run(1.0, 2)[1] == pytest.approx((0 * 1.0 + 1 * w) / (1.0 + w))  # the oldest weighs most
    assert _run(50.0, 5) == pytest.approx([0.0, 0.0, 0.0, 1.0, 2.0], abs=1e-6)  # the oldest alone


def test_the_wrapper_reads_like_a_policy_executing_one_action_and_forgets_the_last_episode():
    policy = _Counting()
    ens = TemporalEnsemble(policy, 0.0)
    assert ens.cfg.n_action_steps == 1 and ens.cfg.horizon == 4 and policy.cfg.n_action_steps == 2
    assert ens.obs_keys == ("state",) and ens.normalizer is policy.normalizer  # the rest is the policy's
    assert not hasattr(ens, "observation_batch")
    ens.start_episode({})
    for _ in range(3):
        ens.predict_action({})
    ens.start_episode({})
    assert float(ens.predict_action({})["action"][0, 0, 0]) == 3.0  # the fourth prediction alone
    with pytest.raises(ValueError, match="finite number >= 0"):
        TemporalEnsemble(policy, float("nan"))
