"""Temporal ensembling (ACT, Zhao et al. RSS 2023) around a trained policy: a new prediction at every action, and
the action executed the weighted mean of every prediction made so far for that step (`hgen policy eval
--temporal-ensemble M`). The weights are exp(-M i), i = 0 for the oldest prediction, as ACT weighs them: with a
small M nearly a plain mean, with a large one the oldest prediction alone.

Why: a chunked policy switches, every few actions, to a new sample drawn with new noise, and a diffusion policy's
samples of one scene differ by its miss (close_drawer: 0.02-0.04 rad a joint); the arm then jumps between them at
each switch. Averaging the overlapping predictions smooths those jumps; it costs a prediction per action instead
of one per chunk. Measured on close_drawer (DP3 fast, docs/results/policies.md): no gain, 41.7% either way for a
60-epoch checkpoint and 21.7% against 35.0% for a 20-epoch one; an evaluation option, off by default."""

from __future__ import annotations

import math
from collections import deque

import torch


class TemporalEnsemble:
    """`policy` predicting at every step, its overlapping predictions for the step averaged (weights exp(-m i),
    oldest first). Reads like a policy to the rollout (`cfg` with one executed action a prediction, `obs_keys`,
    `predict_action`, `start_episode`); anything else is the policy's."""

    def __init__(self, policy, m: float) -> None:
        if not (m >= 0 and math.isfinite(m)):
            raise ValueError(f"--temporal-ensemble must be a finite number >= 0, got {m}")
        self.policy, self.m = policy, float(m)
        self.cfg = policy.cfg.model_copy(update={"n_action_steps": 1})
        self._ahead = policy.cfg.horizon - policy.cfg.n_obs_steps + 1  # the predicted actions from now on
        self._chunks: deque[tuple[int, torch.Tensor]] = deque(maxlen=self._ahead)
        self._step = 0

    def __getattr__(self, name: str):  # the policy's normalizer, name, ... (only called for what is not here)
        if name == "policy":
            raise AttributeError(name)
        return getattr(self.policy, name)

    def start_episode(self, obs: dict) -> None:
        self._chunks.clear()
        self._step = 0
        if hasattr(self.policy, "start_episode"):
            self.policy.start_episode(obs)

    @torch.no_grad()
    def predict_action(self, obs: dict[str, torch.Tensor], generator: torch.Generator | None = None
                       ) -> dict[str, torch.Tensor]:
        seq = self.policy.predict_action(obs, generator=generator)["action_pred"]
        start = self.policy.cfg.n_obs_steps - 1
        self._chunks.append((self._step, seq[:, start: start + self._ahead]))
        now = [chunk[:, self._step - first] for first, chunk in self._chunks if self._step - first < chunk.shape[1]]
        w = torch.tensor([math.exp(-self.m * i) for i in range(len(now))], dtype=now[0].dtype, device=now[0].device)
        action = (w[:, None, None] * torch.stack(now)).sum(0) / w.sum()
        self._step += 1
        return {"action": action[:, None], "action_pred": seq}
