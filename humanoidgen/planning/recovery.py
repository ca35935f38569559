"""The one protocol every recovery follows, and the typed requests stages hand to them.

A stage runs the normal path; where it cannot, it raises a typed failure (`PlanningError`, `MotionError`) and
asks the context's pipeline for a recovery (`ctx.recover(stage, request, failure)`); some recoveries instead
adapt a stage's request before it runs (`ctx.adapt(stage, request)`). Each recovery is one file under
`recoveries/`, registered in order in `pipeline.py`, the only module that imports them. A recovery imports
stages and geometry below it, never the planner API or another recovery.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any, ClassVar, Literal

import numpy as np

from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.poses import Pose
from humanoidgen.sim.layout import Side

Stage = Literal["goal", "transit", "move", "release"]
Trigger = Literal["failure", "before", "after"]


@dataclass
class GoalRequest:
    """Constraints to solve for one hand's goal (`gen`: what generated them, None for the plan's own)."""

    side: Side
    constraints: list
    gen: Any = None


@dataclass
class GoalFound:
    """A goal the search found for one hand (`result`), from the arm at `q_now`; an "after" recovery may replace
    `result` with a better one for the same constraints."""

    side: Side
    constraints: list
    q_now: np.ndarray
    result: Any


@dataclass
class LegRequest:
    """One arm's plain move from `q0` to `target` (no approach axis, no part to follow)."""

    side: Side
    q0: np.ndarray
    target: Pose
    path_constraints: list = field(default_factory=list)


@dataclass
class ReleaseRequest:
    """A hand about to let go of what it holds; `releasing`: every hand the call opens."""

    side: Side
    held: Any
    releasing: tuple[Side, ...]


@dataclass
class AfterMove:
    """A hand's move has run; `target`: the pose it went to (its `regrip` says what is left to do)."""

    side: Side
    target: Pose
    verbs: Any  # the planner API: a recovery that takes the part again calls the plan's own verbs


class Recovery(ABC):
    """One recovery: which stage it serves and when (`trigger`), what it answers and tries, which event it
    leaves. `applies` decides from the request (and the failure); `attempt` returns the stage's result or
    raises (for a failure: the original one where it found nothing better)."""

    stage: ClassVar[Stage]
    trigger: ClassVar[Trigger]
    answers: ClassVar[str]
    tries: ClassVar[str]
    event: ClassVar[str]

    @abstractmethod
    def applies(self, ctx: PlanningContext, request: Any, failure: Exception | None) -> bool: ...

    @abstractmethod
    def attempt(self, ctx: PlanningContext, request: Any, failure: Exception | None) -> Any: ...
