"""An evaluation's outcomes and their summary as the paper reports it: the success rate of each (checkpoint,
seed), then their mean and standard deviation; with the baselines measured on the same scenes beside it."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from humanoidgen.policies.rollout import EpisodeOutcome


def wilson_interval(passed: int, total: int, z: float = 1.96) -> tuple[float, float]:
    """The Wilson score interval of a success rate, passed of total episodes (95% at z = 1.96): with few
    episodes it stays inside [0, 1] and is not zero-width at 0 or total passes, as the normal one is."""
    if total <= 0:
        return 0.0, 1.0
    p = passed / total
    centre = (p + z * z / (2 * total)) / (1 + z * z / total)
    half = z * np.sqrt(p * (1 - p) / total + z * z / (4 * total * total)) / (1 + z * z / total)
    return float(max(0.0, centre - half)), float(min(1.0, centre + half))


@dataclass
class EvalReport:
    task: str
    policy: str
    checkpoints: list[str]
    seeds: list[int]
    episodes: int
    outcomes: list[EpisodeOutcome] = field(default_factory=list)
    info: dict = field(default_factory=dict)  # what else defines the run (a baseline's action range and hold)
    baselines: dict[str, EvalReport] = field(default_factory=dict)  # by name, on the same scenes
    scenes: str = "clean"  # or "randomized": each scene dressed from its seed (`TaskEnvConfig.randomize`)

    def rates(self) -> dict[tuple[str, int], float]:
        """Success rate of each (checkpoint, seed)."""
        out: dict[tuple[str, int], list[bool]] = {}
        for o in self.outcomes:
            out.setdefault((o.checkpoint, o.seed), []).append(o.success)
        return {k: float(np.mean(v)) for k, v in out.items()}

    @property
    def success_mean(self) -> float:
        return float(np.mean(list(self.rates().values()))) if self.outcomes else 0.0

    @property
    def success_std(self) -> float:
        return float(np.std(list(self.rates().values()))) if self.outcomes else 0.0

    def interval(self) -> tuple[float, float]:
        """The 95% Wilson interval of the success rate over all episodes pooled (`wilson_interval`)."""
        return wilson_interval(sum(o.success for o in self.outcomes), len(self.outcomes))

    def summary(self) -> str:
        """'dp3 on close_drawer: success 68.3% +- 6.2 over 3 (checkpoint, seed) pairs'."""
        where = " (randomized scenes)" if self.scenes == "randomized" else ""
        return (f"{self.policy} on {self.task}{where}: success {100 * self.success_mean:.1f}% +- "
                f"{100 * self.success_std:.1f} over {len(self.rates())} (checkpoint, seed) pairs")

    def baseline_line(self) -> str:
        """The baselines beside the score, one line ('' without them)."""
        if not self.baselines:
            return ""
        parts = [f"{name} {100 * b.success_mean:.1f}% +- {100 * b.success_std:.1f}" for name, b in self.baselines.items()]
        return f"baselines on the same {len(self.outcomes_per_checkpoint())} scenes: " + ", ".join(parts)

    def outcomes_per_checkpoint(self) -> list[EpisodeOutcome]:
        first = self.outcomes[0].checkpoint if self.outcomes else None
        return [o for o in self.outcomes if o.checkpoint == first]

    def to_dict(self) -> dict:
        out = {"task": self.task, "policy": self.policy, "scenes": self.scenes, "checkpoints": self.checkpoints,
               "seeds": self.seeds,
               "episodes": self.episodes, "success_mean": self.success_mean, "success_std": self.success_std,
               "rates": [{"checkpoint": c, "seed": s, "success": r} for (c, s), r in self.rates().items()],
               "outcomes": [asdict(o) for o in self.outcomes]}
        if self.info:
            out["info"] = self.info
        if self.baselines:
            out["baselines"] = {name: b.to_dict() for name, b in self.baselines.items()}
        return out
