"""Predicates over an episode's course: a part brought to an openness by the hand holding it (close_drawer as the
paper words it) or carried there by the hand on it (open_box_easy's lid flipped up). The state predicates are in
predicates.py; these need a watch (tasks/watch.py)."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar, Literal

from pydantic import Field

from humanoidgen.objects.describe import openness as _openness
from humanoidgen.planning.hand_ops import finger_contacts, is_held
from humanoidgen.tasks.predicate_base import ObjRef, PredicateResult, Ref, _obj, _part_name, _Strict


@dataclass
class ProcessMemory:
    """What a predicate over the episode's course has seen so far (tasks/watch.py keeps one per predicate and
    episode): `anchor`, the openness it measures from (moved_while_held: where the current hold began, None when
    not held; moved_while_touched: at the last control step); `moved`, how far it counts the part as moved
    (the longest hold's way; the net way under the hand); `done`, the predicate met (kept once met); `squeezed`,
    the simulation time the hand last squeezed the part (moved_while_held's grip, which survives short gaps)."""

    anchor: float | None = None
    moved: float = 0.0
    done: bool = False
    squeezed: float = 0.0

    def copy(self) -> ProcessMemory:
        return replace(self)


class _MovedByHand(_Strict):
    """What both predicates share: the part, the hand, the way and the value it must reach, and how far the hand
    must have moved it."""

    history: ClassVar[bool] = True
    obj: Ref
    part: str | None = None  # a part with a joint of its own (a safe's knob); None: the object's openness
    side: Literal["left", "right"]
    toward: Literal["closed", "open"]
    value: float = Field(ge=0, le=1)
    travel: float = Field(gt=0, le=1)

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def start(self) -> ProcessMemory:
        return ProcessMemory()

    def _progress(self, before: float, after: float) -> float:
        """How far the part went toward the value from `before` to `after` (negative: back)."""
        return before - after if self.toward == "closed" else after - before

    def _reached(self, o: float) -> bool:
        return o <= self.value if self.toward == "closed" else o >= self.value

    def _now(self, env, memory: ProcessMemory) -> tuple[float, set[str]] | None:
        """The part's openness and the hand's fingers on it, or None when there is nothing left to watch."""
        obj = _obj(env, self.obj)
        o = _openness(env.model, env.data, obj, self.part)
        if o is None or memory.done:
            return None
        return o, finger_contacts(env.model, env.data, self.side, obj.body)

    def _unwatched(self, what: str) -> PredicateResult:
        return PredicateResult(ok=False, detail=f"{what}: judged over an episode, and none was watched here")


class MovedWhileHeld(_MovedByHand):
    """The `side` hand brought the part to `value` holding it: within one hold (thumb against a finger or the
    palm, never letting go) the openness went at least `travel` toward the value and reached it (at most, or at
    least, `value`, as `toward` says). A process, not an end state: the paper's close_drawer, "with the left hand
    attached to the drawer handle, the left hand pushes the drawer back to an openness of 0". Judged over the
    episode (the trusted replay and the gym environment watch every control step); judged on a state
    alone, it has seen nothing and does not hold.

    A hold lasts through gaps in the squeeze of up to `grip_gap_s` while the hand stays on the part: a closed
    hand pushing a handle loses and regains the thumb's contact for a few control steps at a time, the other
    fingers still on it (a DP3 policy's fist around the drawer handle, 0.02-0.22 s gaps while it pushed the drawer
    0.6 of the way), while letting go and gripping again takes the hand longer than half a second (opening and
    closing the Inspire hand takes about 1 s). A hand off the part ends the hold at once: with gaps off the part
    allowed too, random joint targets closing the hand near the box lid passed close_box_hard in 3 of 20 scenes."""

    type: Literal["moved_while_held"] = "moved_while_held"
    grip_gap_s: float = Field(default=0.5, ge=0)

    def observe(self, env, memory: ProcessMemory) -> None:
        now = self._now(env, memory)
        if now is None:
            return
        o, touched = now
        t = float(env.data.time)
        if not is_held(touched):
            if memory.anchor is not None and (not touched or t - memory.squeezed > self.grip_gap_s):
                memory.anchor = None
            return
        memory.squeezed = t
        if memory.anchor is None:
            memory.anchor = o
        moved = self._progress(memory.anchor, o)
        memory.moved = max(memory.moved, moved)
        memory.done = self._reached(o) and moved >= self.travel

    def evaluate(self, env, memory: ProcessMemory | None = None) -> PredicateResult:
        part = _part_name(self.obj, self.part)
        what = f"{part} {self.toward} to {self.value:.2f} by the {self.side} hand holding it"
        if memory is None:
            return self._unwatched(what)
        if memory.done:
            return PredicateResult(ok=True, detail=f"{what} (one hold moved it {memory.moved:.2f})")
        return PredicateResult(ok=False, detail=f"{what}: not done (the longest hold moved it {memory.moved:.2f};"
                                                f" at least {self.travel:.2f} wanted)")


class MovedWhileTouched(_MovedByHand):
    """The `side` hand carried the part to `value`: the part's net way toward the value made under the hand is at
    least `travel` when it is at the value (at least, or at most, `value`, as `toward` says). From one control step
    to the next, a move with the hand (any finger or the palm) on it counts either way, and a move back without the
    hand counts against it too; a move on without the hand does not count. A lid lifted on a fingertip in stages
    counts; one flicked up by a hand swinging past it does not (the lid flies on after the hand has gone), nor does
    one jiggled up and down under it. A process, as the paper's open_box_easy: "the right hand moves to be under
    the box lid. Then the right hand moves to flip the box lid up". Judged over the episode by a watch, like
    `moved_while_held`."""

    type: Literal["moved_while_touched"] = "moved_while_touched"

    def observe(self, env, memory: ProcessMemory) -> None:
        now = self._now(env, memory)
        if now is None:
            return
        o, touched = now
        on = bool(touched)
        if memory.anchor is not None:
            step = self._progress(memory.anchor, o)
            if on or step < 0.0:
                memory.moved += step
        memory.anchor = o
        if on:
            memory.done = self._reached(o) and memory.moved >= self.travel

    def evaluate(self, env, memory: ProcessMemory | None = None) -> PredicateResult:
        part = _part_name(self.obj, self.part)
        way = "shut" if self.toward == "closed" else "opened"
        what = f"{part} {way} to {self.value:.2f} by the {self.side} hand on it"
        if memory is None:
            return self._unwatched(what)
        if memory.done:
            return PredicateResult(ok=True, detail=f"{what} (it carried it {memory.moved:.2f})")
        return PredicateResult(ok=False, detail=f"{what}: not done (the hand on it carried it {memory.moved:.2f} net;"
                                                f" at least {self.travel:.2f} wanted, the value reached then)")
