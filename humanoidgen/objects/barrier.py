"""Barriers: static boxes and walls fixed to the table, obstacles the hands must work around.

A barrier is a rigid family (its models are data: families/barrier/) whose `family.yaml` says `static: true`,
so the scene gives it no free joint: it stands where the task puts it however hard a hand or a carried block
pushes on it. It has no operations (nothing grips it); its one function, `obstacle`, tells a scene description
(and an LLM prompt) what it is for. The planner avoids it like any other object's geoms.

`covered_share` measures how much of a table region barriers occupy, seen from above: the measure of the paper's
"more than 60% of the workspace is occupied by barriers" (blocks_stack_hard_with_barrier).
"""

from __future__ import annotations

import mujoco
import numpy as np

from humanoidgen.objects.family import ObjectFamily
from humanoidgen.objects.params import BarrierParams
from humanoidgen.objects.rigid import Geometry, Prim, RigidFamily, _finish
from humanoidgen.sim.layout import Range2D

__all__ = ["BarrierFamily", "BARRIER_FAMILIES", "covered_share"]


def _barrier_geometry(p: dict) -> Geometry:
    sx, sy, sz = p["size"]
    prims = [Prim("geom", "box", (sx / 2, sy / 2, sz / 2), (0, 0, 0), rgba=p["rgba"])]
    # "top": the middle of the top face, what a prompt needs to know how high the obstacle stands.
    return _finish(prims, {"top": (0, 0, sz / 2)})


class BarrierFamily(RigidFamily):
    name = "barrier"
    Params = BarrierParams
    _geometry = staticmethod(_barrier_geometry)  # static: from family.yaml (RigidFamily.static)


BARRIER_FAMILIES: dict[str, ObjectFamily] = {f.name: f for f in (BarrierFamily(),)}


def covered_share(model: mujoco.MjModel, data: mujoco.MjData, bodies: list[str], region: Range2D,
                  cell: float = 0.002) -> float:
    """The share of `region` (a rectangle on the table) that the box geoms of `bodies` cover seen from above.

    Counted on a grid of `cell`-sized squares: a square is covered when its centre, at the height of a geom's
    centre, lies inside that geom. That is exact for boxes turned only about the vertical (barriers stand
    upright); overlapping barriers count once."""
    xs = np.arange(region.x[0] + cell / 2, region.x[1], cell)
    ys = np.arange(region.y[0] + cell / 2, region.y[1], cell)
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    covered = np.zeros(gx.shape, bool)
    ids = {model.body(b).id for b in bodies}
    for g in range(model.ngeom):
        if model.geom_bodyid[g] not in ids:
            continue
        if model.geom_type[g] != mujoco.mjtGeom.mjGEOM_BOX:
            raise ValueError(f"covered_share counts boxes only; geom {g} of {model.body(model.geom_bodyid[g]).name} "
                             "is not one")
        c, rot, half = data.geom_xpos[g], data.geom_xmat[g].reshape(3, 3), model.geom_size[g]
        pts = np.stack([gx - c[0], gy - c[1], np.zeros_like(gx)], axis=-1) @ rot  # world -> geom frame
        covered |= np.all(np.abs(pts) <= half, axis=-1)
    return float(covered.mean())
