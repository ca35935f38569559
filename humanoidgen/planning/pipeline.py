"""The planning pipeline's registry: every recovery, in the order it is tried, and the budgets they draw on.

Stages (goal, transit, move, release) run the normal path and hand their typed requests here: before they run
(`before`: a recovery may adapt or take over the request), after (`after`: what a move left to do), and when
they fail (`recover`: the first recovery that applies answers the failure; none, and the failure stands). This
is the only module that imports the recoveries; a new one is one file under `recoveries/`, one line in
`RECOVERIES` and one test. `design_table()` is what the docs' planning design page shows.

Rule: stages know the pipeline only through the context (`ctx.recover`, `ctx.before`, `ctx.after`); recoveries
import stages and geometry, never the planner API, the pipeline or each other.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.recovery import Recovery
from humanoidgen.planning.recoveries.ajar_before_grip import AjarBeforeGrip
from humanoidgen.planning.recoveries.carry_into import CarryInto
from humanoidgen.planning.recoveries.grip_again import GripAgain
from humanoidgen.planning.recoveries.hand_over import HandOverTrial
from humanoidgen.planning.recoveries.near_posture import NearPosture
from humanoidgen.planning.recoveries.part_release import PartRelease
from humanoidgen.planning.recoveries.pinch_instead import PinchInstead
from humanoidgen.planning.recoveries.rise_first import RiseFirst

# In the order they are tried within their stage and trigger.
RECOVERIES: tuple[Recovery, ...] = (
    AjarBeforeGrip(),
    PinchInstead(),
    NearPosture(),
    CarryInto(),
    RiseFirst(),
    GripAgain(),
    HandOverTrial(),
    PartRelease(),
)


@dataclass(frozen=True)
class Budgets:
    """What recoveries may spend per plan call (seconds of search are the stages' own constants)."""

    regrips: int = 2  # times a held part may be let go and gripped again on one move (recoveries/grip_again)


BUDGETS = Budgets()


class Pipeline:
    """Runs a stage's recoveries for a context (`PlanningContext.pipeline`)."""

    def __init__(self, recoveries: tuple[Recovery, ...] = RECOVERIES) -> None:
        self.recoveries = recoveries

    def _for(self, stage: str, trigger: str) -> list[Recovery]:
        return [r for r in self.recoveries if r.stage == stage and r.trigger == trigger]

    def recover(self, ctx: PlanningContext, stage: str, request: Any, failure: Exception) -> Any:
        for recovery in self._for(stage, "failure"):
            if recovery.applies(ctx, request, failure):
                return recovery.attempt(ctx, request, failure)
        raise failure

    def before(self, ctx: PlanningContext, stage: str, request: Any) -> bool:
        """True where a recovery took the request over (the stage's usual way is not to run)."""
        for recovery in self._for(stage, "before"):
            if recovery.applies(ctx, request, None) and recovery.attempt(ctx, request, None):
                return True
        return False

    def after(self, ctx: PlanningContext, stage: str, request: Any) -> None:
        for recovery in self._for(stage, "after"):
            if recovery.applies(ctx, request, None):
                recovery.attempt(ctx, request, None)


def design_table(recoveries: tuple[Recovery, ...] = RECOVERIES) -> list[dict[str, str]]:
    """One row per recovery, in order: its stage, trigger, file, what it answers, tries and leaves as an event."""
    return [{"stage": r.stage, "trigger": r.trigger, "recovery": type(r).__name__,
             "file": f"planning/recoveries/{type(r).__module__.rsplit('.', 1)[-1]}.py",
             "answers": r.answers, "tries": r.tries, "event": r.event} for r in recoveries]
