"""Which (mover, obstacle) geom pairs can be within a distance: the cheap test before `mj_geomDistance`.

A pair's distance is at least the gap between the geoms' bounding spheres (MuJoCo's `geom_rbound` about
`geom_xpos`) and, for a box obstacle, at least the gap between the mover's sphere and the box itself. The box
test matters for big boxes: the table's sphere (0.9 m) reaches every hand and link, and without it the table
made 85% of a hand-over's distance queries. Compiled (numba): the path planners ask this thousands of times
per move for some 30 x 60 pairs, where numpy's per-call overhead cost more than the queries it saved.
"""

from __future__ import annotations

import numpy as np
from numba import njit

BOX = 6  # mjtGeom.mjGEOM_BOX


def candidate_pairs(model, data, movers: np.ndarray, obstacles: np.ndarray, cut: float) -> np.ndarray:
    """(k, 2) index pairs (i, j) into movers, obstacles whose lower-bound gap is at most `cut` (metres)."""
    out = np.empty((len(movers) * len(obstacles), 2), np.int64)
    k = _pairs(data.geom_xpos, data.geom_xmat, model.geom_rbound, model.geom_size, model.geom_type,
               np.asarray(movers, np.int64), np.asarray(obstacles, np.int64), float(cut), out)
    return out[:k]


def warm_up() -> None:
    """Compile the kernel now (a process that forks workers does this once)."""
    z = np.zeros((2, 3))
    _pairs(z, np.tile(np.eye(3).ravel(), (2, 1)), np.ones(2), np.ones((2, 3)), np.array([BOX, BOX], np.int32),
           np.array([0], np.int64), np.array([1], np.int64), 0.0, np.empty((1, 2), np.int64))


@njit(cache=True, nogil=True)
def _pairs(xpos, xmat, rbound, size, gtype, movers, obstacles, cut, out):  # pragma: no cover - compiled
    k = 0
    for i in range(movers.shape[0]):
        g1 = movers[i]
        cx, cy, cz = xpos[g1, 0], xpos[g1, 1], xpos[g1, 2]
        r = rbound[g1]
        for j in range(obstacles.shape[0]):
            g2 = obstacles[j]
            dx, dy, dz = cx - xpos[g2, 0], cy - xpos[g2, 1], cz - xpos[g2, 2]
            if np.sqrt(dx * dx + dy * dy + dz * dz) - r - rbound[g2] > cut:
                continue
            if gtype[g2] == BOX:
                q2 = 0.0
                for a in range(3):  # the centre in the box's frame: R^T (c - p), R's columns are its axes
                    la = abs(xmat[g2, a] * dx + xmat[g2, 3 + a] * dy + xmat[g2, 6 + a] * dz) - size[g2, a]
                    if la > 0.0:
                        q2 += la * la
                if np.sqrt(q2) - r > cut:
                    continue
            out[k, 0] = i
            out[k, 1] = j
            k += 1
    return k
