"""Contents that ride in a container (`follow`) when the container is on another model than the task was written
for (`--model`, `--randomize-models`): they move with the container's storage point, which is where another
cup's opening and inner bottom are (a handled mug's opening is off its box's centre by its handle)."""

from __future__ import annotations

import math

import numpy as np

from humanoidgen.objects import library


def storage_shift(family: str, authored: int, model: int) -> np.ndarray | None:
    """How far (container frame, metres) the storage point of model `model` lies from that of `authored`, both
    standing on the table; None when either has no storage point on its body (a drawer's is on its part)."""
    if authored == model:
        return np.zeros(3)
    out = []
    for type_id in (authored, model):
        ann = library.annotations(family, type_id)
        if not any(p.name == "storage" and p.part is None for p in ann.points):
            return None
        p = np.asarray(ann.point("storage").position, float)
        out.append(p - np.array([0.0, 0.0, ann.bbox_min[2]]))  # the point's height above the object's base
    return out[1] - out[0]


def moved(pos: tuple[float, ...], yaw: float, shift: np.ndarray) -> tuple[float, ...]:
    """`pos` (2 or 3 numbers) moved by `shift` given in the frame of a container turned by `yaw` (radians)."""
    c, s = math.cos(yaw), math.sin(yaw)
    dx, dy = c * shift[0] - s * shift[1], s * shift[0] + c * shift[1]
    head = (float(pos[0] + dx), float(pos[1] + dy))
    return head + ((float(pos[2] + shift[2]),) if len(pos) > 2 else ())
