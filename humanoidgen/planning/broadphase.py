"""Which (mover, obstacle) geom pairs can be within a distance: the cheap test before `mj_geomDistance`.

A pair's distance is at least the gap between the geoms' bounding spheres (MuJoCo's `geom_rbound` about
`geom_xpos`) and, for a box obstacle, at least the gap between the mover's sphere and the box itself. The box
test matters for big boxes: the table's sphere (0.9 m) reaches every hand and link, and without it the table
made 85% of a hand-over's distance queries. Compiled (numba): the path planners ask this thousands of times
per move for some 30 x 60 pairs, where numpy's per-call overhead cost more than the queries it saved.
"""

from __future__ import annotations

import contextlib
import sys
import threading
from collections.abc import Iterator

import numpy as np
from numba import njit

BOX = 6  # mjtGeom.mjGEOM_BOX


def candidate_pairs(model, data, movers: np.ndarray, obstacles: np.ndarray, cut: float) -> np.ndarray:
    """(k, 2) index pairs (i, j) into movers, obstacles whose lower-bound gap is at most `cut` (metres)."""
    out = np.empty((len(movers) * len(obstacles), 2), np.int64)
    k = _pairs(data.geom_xpos, data.geom_xmat, model.geom_rbound, model.geom_size, model.geom_type,
               _read_only(movers), _read_only(obstacles), float(cut), out)
    return out[:k]


def _read_only(ids) -> np.ndarray:
    """Geom ids as one array type, whoever calls (the collision lists are read-only arrays): a new type would
    compile the kernel again, which a locked-down worker cannot write to its cache."""
    a = np.asarray(ids, np.int64)
    if a.flags.writeable:
        a = a.view()
        a.flags.writeable = False
    return a


def warm_up() -> None:
    """Compile (or load from the cache) the kernel now, for the array types MuJoCo hands it: a process that
    forks locked-down workers does this once, since a worker may not write the compiled code to the cache.
    Numba's first compile or cache load in a process is done without SciPy's BLAS (`without_blas`)."""
    import mujoco

    model = mujoco.MjModel.from_xml_string("<mujoco><worldbody><geom type='box' size='1 1 1'/>"
                                           "<geom type='sphere' size='0.1' pos='0 0 3'/></worldbody></mujoco>")
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    with without_blas():
        candidate_pairs(model, data, np.array([1]), np.array([0]), 0.0)


_BLAS_PROBE = "scipy.linalg"
_blas_lock = threading.Lock()


@contextlib.contextmanager
def without_blas() -> Iterator[None]:
    """Numba's first compile or cache load in a process imports all of its lowering registries, and one of
    them imports scipy.linalg (0.25 s, with numpy.f2py) only to see whether BLAS is there for `np.dot` and
    friends (`numba.np.arraymath._HAVE_BLAS`). This kernel calls none of them: while this holds, scipy.linalg
    cannot be imported, so numba finds no BLAS and moves on. Numba compiles the one function that asks
    (vector inner products) with its own loop instead, and a later `np.dot` or `np.linalg` in a compiled
    function imports SciPy then, as usual. Nothing changes where scipy.linalg is imported already."""
    with _blas_lock:
        if _BLAS_PROBE in sys.modules:
            yield
            return
        sys.modules[_BLAS_PROBE] = None  # type: ignore[assignment]  # the import system's "cannot import"
        try:
            yield
        finally:
            if sys.modules.get(_BLAS_PROBE, 0) is None:
                del sys.modules[_BLAS_PROBE]


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
