"""The random-action baseline: a joint target drawn uniformly, per joint, within an action range (the
demonstrations' when known, else the joint limits), held for `hold` actions, then the next. As gymnasium's
`action_space.sample()` (the usual random agent of RL and manipulation benchmarks) but held, so that it moves
the arms as far as a policy could. The draws come from the episode's torch generator, which evaluation seeds
with the episode's number: the same scenes give the same actions."""

from __future__ import annotations

import torch

from humanoidgen.policies.baselines import RANDOM_HOLD_ACTIONS, ActionRange, BaselineConfig


class RandomPolicy:
    name = "random"
    obs_keys = ("state",)

    def __init__(self, action_range: ActionRange, hold: int = RANDOM_HOLD_ACTIONS) -> None:
        if hold < 1:
            raise ValueError(f"hold must be >= 1 action, got {hold}")
        self.cfg = BaselineConfig(n_action_steps=hold)
        self.action_range = action_range
        self._low = torch.tensor(action_range.low, dtype=torch.float32)
        self._span = torch.tensor(action_range.high, dtype=torch.float32) - self._low

    @torch.no_grad()
    def predict_action(self, obs: dict[str, torch.Tensor], generator: torch.Generator | None = None
                       ) -> dict[str, torch.Tensor]:
        u = torch.rand(self._low.shape, generator=generator)
        target = self._low + u * self._span
        action = target.expand(self.cfg.n_action_steps, -1)[None]
        return {"action": action.to(obs["state"].device)}
