"""What an episode reports: its steps (which call failed and why), the task's checks, timings, final object
poses and the planner's events. Plain data: the parent that runs episodes imports this, not the planner."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field


@dataclass
class StepResult:
    index: int
    title: str
    ok: bool
    error: str = ""  # "<call>: <reason>" or "<ExceptionType>: <message> (line n)"
    seconds: float = 0.0
    sim_seconds: float = 0.0
    events: list[str] = field(default_factory=list)


@dataclass
class EpisodeResult:
    task: str
    seed: int | None
    success: bool
    checks: list[dict]  # each success predicate: {"ok": bool, "detail": str}
    steps: list[StepResult]
    wall_seconds: float
    sim_seconds: float
    plan_seconds: float
    objects: dict[str, dict]  # final pose (and openness) of every object
    events: list[str]

    @property
    def failed_step(self) -> StepResult | None:
        return next((s for s in self.steps if not s.ok), None)

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> EpisodeResult:
        return cls(**{**d, "steps": [StepResult(**s) for s in d["steps"]]})
