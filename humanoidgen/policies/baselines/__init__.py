"""Baseline policies that need no training, measured on the same scenes as a trained policy so that its score
can be told from chance: `random` (uniform joint targets, each held for a few actions) and `noop` (hold the
start posture). They follow the trained policies' protocol as `policies.rollout` drives it: `name`,
`obs_keys`, `cfg.n_obs_steps`, `predict_action(obs, generator) -> {"action": (1, k, action_dim)}`, plus the
optional `start_episode(obs)` that rollout calls with each episode's first observation."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# Actions a random target is held for: 0.4 s at the recordings' 10 Hz, the executed chunk of the CPU `fast`
# recipe, so the arm travels towards each target instead of trembling around its start (one new target per
# 0.1 s action mostly cancels out under the joints' PD control).
RANDOM_HOLD_ACTIONS = 4


@dataclass(frozen=True)
class BaselineConfig:
    """The part of a policy config rollout reads."""

    n_action_steps: int = 1
    n_obs_steps: int = 1


@dataclass(frozen=True)
class ActionRange:
    """Per-joint bounds random targets are drawn in, and where they came from (named in reports)."""

    low: tuple[float, ...]
    high: tuple[float, ...]
    source: str  # "joint limits", "demonstrations (runs/x)", ...

    def __post_init__(self) -> None:
        if len(self.low) != len(self.high):
            raise ValueError(f"action range bounds differ in length: {len(self.low)} vs {len(self.high)}")
        if any(lo > hi for lo, hi in zip(self.low, self.high)):
            raise ValueError("action range: a low bound above its high bound")

    @classmethod
    def of(cls, low, high, source: str) -> ActionRange:
        return cls(tuple(float(x) for x in np.asarray(low).ravel()), tuple(float(x) for x in np.asarray(high).ravel()),
                   source)

    def to_dict(self) -> dict:
        return {"source": self.source, "low": list(self.low), "high": list(self.high)}
