"""A predicate over an episode's course on how fast a part moved: a lid or screen brought down, not slammed. Like
held_move.py's, it needs a watch (tasks/watch.py) that saw every control step."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from typing import ClassVar, Literal

from pydantic import Field

from humanoidgen.objects.describe import openness as _openness
from humanoidgen.tasks.predicate_base import ObjRef, PredicateResult, Ref, _obj, _part_name, _Strict


@dataclass
class SpeedMemory:
    """The part's openness at the last control steps (`trail`: (time, openness), as long as the window) and the
    fastest it has moved over a window so far (`fastest`, openness per second)."""

    trail: deque = field(default_factory=deque)
    fastest: float = 0.0

    def copy(self) -> SpeedMemory:
        return SpeedMemory(deque(self.trail), self.fastest)


class MovedGently(_Strict):
    """The part never moved faster than `max_speed` (openness per second, either way), measured over every window
    of `window_s` of the episode. The paper, of a policy that closed the box lid by flailing: "the arm tends to
    make rapid and random movements, occasionally closing the box lid by chance ... this behavior is unstable and
    unsafe". Its stiff-hinged lids move only while something pushes them, so a hand that presses one down is as
    fast as its arm: close_box_easy's reference plan brings the lid down at most 1.05 of its range a second (50
    seeds); random joint targets that shut it, or close_laptop_easy's screen, slam it at 1.3-4.4 (30 scenes
    each). Judged over the episode by a watch; on a state alone it has seen nothing and does not hold."""

    history: ClassVar[bool] = True
    type: Literal["moved_gently"] = "moved_gently"
    obj: Ref
    part: str | None = None  # a part with a joint of its own; None: the object's openness
    max_speed: float = Field(gt=0)
    window_s: float = Field(default=0.1, gt=0)

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def start(self) -> SpeedMemory:
        return SpeedMemory()

    def observe(self, env, memory: SpeedMemory) -> None:
        o = _openness(env.model, env.data, _obj(env, self.obj), self.part)
        if o is None:
            return
        t = float(env.data.time)
        memory.trail.append((t, o))
        # keep the oldest sample at least a window back, so every window is measured across its whole length
        while len(memory.trail) > 2 and t - memory.trail[1][0] >= self.window_s:
            memory.trail.popleft()
        t0, o0 = memory.trail[0]
        if t - t0 >= self.window_s:
            memory.fastest = max(memory.fastest, abs(o - o0) / (t - t0))

    def evaluate(self, env, memory: SpeedMemory | None = None) -> PredicateResult:
        what = _part_name(self.obj, self.part)
        if memory is None:
            return PredicateResult(ok=False, detail=f"{what} moved gently: judged over an episode, and none was "
                                                    f"watched here")
        ok = memory.fastest <= self.max_speed
        return PredicateResult(ok=ok, detail=f"{what} moved at most {memory.fastest:.2f} of its range a second "
                                             f"({'within' if ok else 'over'} {self.max_speed:.2f})")
