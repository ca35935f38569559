"""What a move leaves to do after it when a held part could not be taken all the way (`Pose.regrip`): let go of
the part where it is and get it on to the openness asked, pushed on or gripped again (`recoveries/grip_again`).
Typed data the goal search and the part-following stage write and the recovery reads."""

from __future__ import annotations

from humanoidgen.planning.part_joint import PartFollow

from dataclasses import dataclass

STOP_SHORT_OF_SHUT = 0.2  # a hinged part to be shut is let go here by a hand holding it by its edge (part_grip)
SHUT = 0.05  # openness: a part asked this near its closed end is to be shut (tasks check shut parts to 0.05)


@dataclass
class RegripRequest:
    """Let go of the part `follow` moves where it is (at openness `reached`), then get it to `openness` (pushed
    on, or gripped again with `verb`). `optional`: where that fails the part stays, with an event, instead of the
    move failing. `why`: the event's reason for letting go (default: the arm's reach ends there)."""

    obj: tuple  # (type_name, obj_id)
    openness: float
    verb: str | None
    reached: float
    optional: bool
    follow: PartFollow
    why: str | None = None


def request(follow: PartFollow, wanted: float, verb: str | None, reached: float, optional: bool,
            why: str | None = None) -> RegripRequest:
    return RegripRequest(follow.obj, wanted, verb, reached, optional, follow, why or None)
