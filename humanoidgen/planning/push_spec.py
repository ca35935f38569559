"""What the planner needs to know of a fingertip push on an articulated part (a lid, a laptop screen, a drawer
front): the shape planning asks of it. Task data provides it (`tasks.targets.PushSpec`, validated from a task's
YAML); planning owns the shape and never imports the tasks that fill it, so data flows one way."""

from __future__ import annotations

from typing import Literal, Protocol


class FingertipPush(Protocol):
    point: str  # a key point on the moving part
    to: float  # the openness the push brings the part to
    face: Literal["inner", "outer"]  # under the part (lifting it) or on its outer face (pressing it shut)
    axes: tuple[str, str]  # (in along the part, into the part from its outer face)
    depth: float  # fingertip centre from the point, along axes[1] (m)
    aim: str | tuple[float, float, float]  # the fingertip points this way: an object axis or a world direction
    aim_cone_deg: float
    palm_across: str | None  # an object axis the palm stays across (70-110 deg)
    step: float  # openness per stage
    standoff: float  # the pre-push pose: metres off the contact point

    def inset_at(self, openness: float) -> float:
        """The contact's inset (m along axes[0]) with the part at `openness`."""


class TaskTargets(Protocol):
    """A task's named target poses and pushes, as planning asks them (`tasks.targets.SceneTargets` provides them):
    handed to the planner API as `targets=` by whoever built the task's scene."""

    def find(self, type_name: str, obj_id: int, name: str, side: str): ...

    def push(self, type_name: str, obj_id: int): ...

    def names(self, type_name: str, obj_id: int, side: str) -> list[str]: ...
