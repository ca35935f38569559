"""The planner's one failure type: every stage and recovery raises it, and the plan worker sends its `call` and
`reason` back to the plan's author (an LLM's feedback). Its own module so that any planning module can import
it at the top, below everything that raises it."""

from __future__ import annotations


class PlanningError(RuntimeError):
    """A planner call that could not do its job; `call` and `reason` go back to the plan's author."""

    def __init__(self, call: str, reason: str) -> None:
        super().__init__(f"{call}: {reason}")
        self.call = call
        self.reason = reason
