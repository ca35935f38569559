"""Predicates over an episode's course: a part brought to an openness by the hand holding it (close_drawer as the
paper words it) or carried there by the hand on it (open_box_easy's lid flipped up). The state predicates are in
predicates.py; these need a watch (tasks/watch.py)."""

from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import Field

from humanoidgen.objects.describe import openness as _openness
from humanoidgen.planning.hand_ops import finger_contacts, is_held
from humanoidgen.tasks.predicate_base import ObjRef, PredicateResult, Ref, _name, _obj, _Strict


class HoldMemory:
    """What a `moved_while_held` predicate has seen of an episode so far (tasks/watch.py keeps one per episode)."""

    __slots__ = ("start", "done", "travelled")

    def __init__(self) -> None:
        self.start: float | None = None  # the openness when the current hold began (None: not held)
        self.done = False  # the part reached the value within one hold that moved it `travel` or more
        self.travelled = 0.0  # the most one hold has moved it so far (for the detail)

    def copy(self) -> HoldMemory:
        c = HoldMemory()
        c.start, c.done, c.travelled = self.start, self.done, self.travelled
        return c


class MovedWhileHeld(_Strict):
    """The `side` hand brought the part to `value` holding it: within one hold (thumb against a finger or the
    palm, never letting go) the openness went at least `travel` toward the value and reached it (at most, or at
    least, `value`, as `toward` says). A process, not an end state: the paper's close_drawer, "with the left hand
    attached to the drawer handle, the left hand pushes the drawer back to an openness of 0". Judged over the
    episode (the trusted replay and the gym environment watch every control step); judged on a state
    alone, it has seen nothing and does not hold."""

    type: Literal["moved_while_held"] = "moved_while_held"
    history: ClassVar[bool] = True
    obj: Ref
    side: Literal["left", "right"]
    toward: Literal["closed", "open"]
    value: float = Field(ge=0, le=1)
    travel: float = Field(gt=0, le=1)

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def start(self) -> HoldMemory:
        return HoldMemory()

    def observe(self, env, memory: HoldMemory) -> None:
        obj = _obj(env, self.obj)
        o = _openness(env.model, env.data, obj, None)
        if o is None or memory.done:
            return
        if not is_held(finger_contacts(env.model, env.data, self.side, obj.body)):
            memory.start = None
            return
        if memory.start is None:
            memory.start = o
        moved = memory.start - o if self.toward == "closed" else o - memory.start
        memory.travelled = max(memory.travelled, moved)
        reached = o <= self.value if self.toward == "closed" else o >= self.value
        memory.done = reached and moved >= self.travel

    def evaluate(self, env, memory: HoldMemory | None = None) -> PredicateResult:
        what = f"{_name(self.obj)} {self.toward} to {self.value:.2f} by the {self.side} hand holding it"
        if memory is None:
            return PredicateResult(ok=False, detail=f"{what}: judged over an episode, and none was watched here")
        if memory.done:
            return PredicateResult(ok=True, detail=f"{what} (one hold moved it {memory.travelled:.2f})")
        return PredicateResult(ok=False, detail=f"{what}: not done (the longest hold moved it {memory.travelled:.2f};"
                                                f" at least {self.travel:.2f} wanted)")


class TouchMemory:
    """What a `moved_while_touched` predicate has seen so far."""

    __slots__ = ("last", "moved", "done")

    def __init__(self) -> None:
        self.last: float | None = None  # the openness at the last control step seen
        self.moved = 0.0  # the part's net way toward the value made under the hand (see MovedWhileTouched)
        self.done = False

    def copy(self) -> TouchMemory:
        c = TouchMemory()
        c.last, c.moved, c.done = self.last, self.moved, self.done
        return c


class MovedWhileTouched(_Strict):
    """The `side` hand carried the part to `value`: the part's net way toward the value made under the hand is at
    least `travel` when it is at the value (at least, or at most, `value`, as `toward` says). From one control step
    to the next, a move with the hand (any finger or the palm) on it counts either way, and a move back without the
    hand counts against it too; a move on without the hand does not count. A lid lifted on a fingertip in stages
    counts; one flicked up by a hand swinging past it does not (the lid flies on after the hand has gone), nor does
    one jiggled up and down under it. A process, as the paper's open_box_easy: "the right hand moves to be under
    the box lid. Then the right hand moves to flip the box lid up". Judged over the episode by a watch, like
    `moved_while_held`."""

    type: Literal["moved_while_touched"] = "moved_while_touched"
    history: ClassVar[bool] = True
    obj: Ref
    side: Literal["left", "right"]
    toward: Literal["closed", "open"]
    value: float = Field(ge=0, le=1)
    travel: float = Field(gt=0, le=1)

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def start(self) -> TouchMemory:
        return TouchMemory()

    def observe(self, env, memory: TouchMemory) -> None:
        obj = _obj(env, self.obj)
        o = _openness(env.model, env.data, obj, None)
        if o is None or memory.done:
            return
        on = bool(finger_contacts(env.model, env.data, self.side, obj.body))
        if memory.last is not None:
            step = memory.last - o if self.toward == "closed" else o - memory.last
            if on or step < 0.0:
                memory.moved += step
        memory.last = o
        if not on:
            return
        reached = o <= self.value if self.toward == "closed" else o >= self.value
        memory.done = reached and memory.moved >= self.travel

    def evaluate(self, env, memory: TouchMemory | None = None) -> PredicateResult:
        what = f"{_name(self.obj)} {'shut' if self.toward == 'closed' else 'opened'} to {self.value:.2f} by the " \
               f"{self.side} hand on it"
        if memory is None:
            return PredicateResult(ok=False, detail=f"{what}: judged over an episode, and none was watched here")
        if memory.done:
            return PredicateResult(ok=True, detail=f"{what} (it carried it {memory.moved:.2f})")
        return PredicateResult(ok=False, detail=f"{what}: not done (the hand on it carried it {memory.moved:.2f} net;"
                                                f" at least {self.travel:.2f} wanted, the value reached then)")
