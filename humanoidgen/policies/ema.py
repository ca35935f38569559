"""Exponential moving average of the weights, DP's schedule (decay 1 - (1 + step)^-0.75, capped at 0.9999),
by diffusers' EMAModel. The EMA copy is what is evaluated and saved for inference."""

from __future__ import annotations

import copy

from diffusers.training_utils import EMAModel
from torch import nn

from humanoidgen.policies.config import TrainConfig


class EmaWeights:
    def __init__(self, model: nn.Module, cfg: TrainConfig) -> None:
        self.model = copy.deepcopy(model).eval().requires_grad_(False)
        self._ema = EMAModel(self.model.parameters(), decay=cfg.ema_max_decay, min_decay=0.0, use_ema_warmup=True,
                             inv_gamma=1.0, power=cfg.ema_power)

    def update(self, model: nn.Module) -> None:
        self._ema.step(model.parameters())
        self._ema.copy_to(self.model.parameters())
        # Buffers (the normalizer's statistics) are not averaged: they are fitted once, copy them as they are.
        for mine, theirs in zip(self.model.buffers(), model.buffers()):
            mine.copy_(theirs)

    def state_dict(self) -> dict:
        return self._ema.state_dict()

    def load_state_dict(self, state: dict) -> None:
        self._ema.load_state_dict(state)
        self._ema.copy_to(self.model.parameters())
