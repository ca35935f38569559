"""What an object family provides: its models (`type_id`s), how to build one into a scene, its annotations."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import mujoco

from humanoidgen.objects.schema import ObjectAnnotations


@dataclass(frozen=True)
class ObjectModel:
    """One model of a family: `type_id` selects it; `params` are its dimensions (metres), colour, mass, ... as
    its model file gives them (objects/families/; the family's defaults fill in the rest when it is built)."""

    family: str
    type_id: int
    description: str
    params: dict = field(default_factory=dict)


class ObjectFamily(Protocol):
    """A family of objects (cube, cup, drawer, ...).

    `build` fills `body` (already placed at the object's pose, named "<family>_<obj_id>") with geoms and, for
    articulated objects, child bodies named "<body>_<part>" and joints named "<body>_<joint>". The object's
    frame has its origin at the centre of its bounding box, z up when upright. Rigid families get a free joint
    from the scene; articulated families are fixed to the table (`articulated = True`), and so are families
    that say `static = True` (barriers; an attribute a family may leave out).
    """

    name: str
    articulated: bool

    def models(self) -> list[ObjectModel]: ...

    def build(self, spec: mujoco.MjSpec, body: mujoco.MjsBody, type_id: int) -> None: ...

    def annotations(self, type_id: int) -> ObjectAnnotations: ...
