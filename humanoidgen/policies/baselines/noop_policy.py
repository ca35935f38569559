"""The no-op baseline: every action is the joint positions the episode started in, so the robot holds its
start posture and the scene is left to itself (a task whose success holds in the initial state, or comes by
itself, passes it)."""

from __future__ import annotations

import numpy as np
import torch

from humanoidgen.policies.baselines import BaselineConfig


class NoopPolicy:
    name = "noop"
    obs_keys = ("state",)

    def __init__(self, chunk: int = 10) -> None:
        self.cfg = BaselineConfig(n_action_steps=chunk)  # any chunk: every action is the same
        self._start: torch.Tensor | None = None

    def start_episode(self, obs: dict[str, np.ndarray]) -> None:
        self._start = torch.as_tensor(np.asarray(obs["joint_pos"], dtype=np.float32))

    @torch.no_grad()
    def predict_action(self, obs: dict[str, torch.Tensor], generator: torch.Generator | None = None
                       ) -> dict[str, torch.Tensor]:
        if self._start is None:
            raise RuntimeError("noop: call start_episode(first observation) at each episode's start")
        return {"action": self._start.expand(self.cfg.n_action_steps, -1)[None].to(obs["state"].device)}
