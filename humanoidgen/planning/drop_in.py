"""Letting a carried object into a deep container from above its top.

A plan that brings a held block to "10 cm above the drawer's storage point" and opens the hand means "drop it in".
In a deep container that point lies between the walls: the drawer's walls stand 23 cm, the cabinet's top hangs
over the back of the open drawer and the fingers, reaching forward past the block, would be under it. The goal
pose there can be solved (the hand squeezed in, 5 mm from everything) but no path leads into it. When a move
of a held object finds no path and its goal puts the object inside a container's storage region below the
container's top, the move instead ends straight above that goal with the object's lowest corner DROP_CLEARANCE_M
over the top (then a little higher, DROP_HIGHER_M), so that letting go drops it in; an event says how much
higher it was let go. The hand must be able to open fully there without touching the container (an open thumb
that swings onto the drawer's wall top drags the drawer on the next move: measured, openness 0.89 to 0.64). Pure
geometry here (the region is `objects.queries.storage_region`, as the `inside` check reads it); the planner's part
is the transit stage's recovery `recoveries/carry_into.py`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from humanoidgen.objects.queries import storage_region
from humanoidgen.planning.placing import is_container, lowest_offset
from humanoidgen.sim.scene import SceneObject

DROP_CLEARANCE_M = 0.015  # the held object's lowest corner this far above the container's top
DROP_HIGHER_M = (0.0, 0.03, 0.06, 0.09)  # and, if the hand cannot get there or open there, this much higher again
STORAGE_BELOW_M = 0.01  # a centre this far below the storage point still counts as in the container


@dataclass(frozen=True)
class DropIn:
    container: SceneObject
    top: float  # world height of the container's top

    def raises(self, held: SceneObject, centre: np.ndarray, R_held: np.ndarray) -> tuple[float, ...]:
        """How far to move a goal with `held`'s centre at `centre` (orientation R_held) up to let it go above
        the top, lowest first."""
        base = self.top + DROP_CLEARANCE_M - (float(centre[2]) - lowest_offset(held, R_held))
        return tuple(max(base, 0.0) + h for h in DROP_HIGHER_M)


def object_geoms(model, obj: SceneObject) -> np.ndarray:
    """All geoms of an object's bodies (a drawer's cabinet and its sliding part)."""
    root = model.body(obj.body).id
    return np.flatnonzero(model.body_rootid[model.geom_bodyid] == root)


def drop_in(env, held: SceneObject, centre: np.ndarray, R_held: np.ndarray) -> DropIn | None:
    """The container `held` would be in with its centre at `centre` (orientation R_held) and its lowest corner
    below the container's top; None if none."""
    bottom = float(centre[2]) - lowest_offset(held, R_held)
    for o in env.scene.objects:
        if o is held or not is_container(o):
            continue
        s, R, half, top = storage_region(env, o)
        local = R.T @ (np.asarray(centre, float) - s)
        if np.all(np.abs(local[:2]) <= half) and centre[2] >= s[2] - STORAGE_BELOW_M and bottom < top:
            return DropIn(o, top)
    return None
