"""Farthest point sampling: exact greedy FPS, compiled (numba) and pruned by buckets of nearby points.

The result is index for index the one of the plain greedy loop (`reference_fps`, what the recorder used
before): the same candidates, the same start, the same squared distances computed in the same order, the
same first-index tie-break. The speed comes from skipping work that cannot change anything: candidates are
grouped into grid cells, and a cell whose bounding box is farther from the newly chosen point than every
running min-distance inside it is not visited (none of its distances could shrink). After the first few
dozen picks most cells are skipped, so a 1024-point sample of 8192 candidates costs about a millisecond
instead of the plain loop's ~25 ms.
"""

from __future__ import annotations

import numpy as np
from numba import njit

_BUCKET_POINTS = 32  # candidates per grid cell on average
# A cell is skipped only when its box distance exceeds the cell's largest min-distance by this relative
# margin: larger than the rounding error of either squared distance, so no update is ever skipped.
_SKIP_MARGIN = 1e-9


def farthest_point_sampling(points: np.ndarray, n: int, seed: int = 0, oversample: int | None = 8) -> np.ndarray:
    """Indices (n,) into ``points`` chosen by farthest point sampling.

    Deterministic for a given ``seed`` (the seed picks the start point and the candidate subset).

    Speed: if ``oversample`` is not None and N > oversample*n, a uniform random subset of ``oversample*n``
    candidates is drawn first. FPS on a dense depth cloud is dominated by N, and an 8x random pre-subsample
    barely changes the coverage while cutting the cost ~N/(8n) times. Pass ``oversample=None`` for exact FPS
    over all points.

    If N < n every index is returned once (in order), then the sequence is repeated cyclically so the output
    always has exactly n entries. Points must be finite (filter with the ``valid`` mask first).
    """
    pts, cand, start = _candidates(points, n, seed, oversample)
    if cand is None:
        return np.resize(np.arange(pts.shape[0], dtype=np.int64), n)
    sub = pts[cand]
    order, starts, lo, hi = _buckets(sub)
    xyz = np.ascontiguousarray(sub[order].T)  # per-axis rows, in bucket order
    chosen = _bucketed_fps(xyz[0], xyz[1], xyz[2], order.astype(np.int64), starts, lo, hi, n,
                           int(np.nonzero(order == start)[0][0]))
    return cand[chosen]


def reference_fps(points: np.ndarray, n: int, seed: int = 0, oversample: int | None = 8) -> np.ndarray:
    """The plain greedy loop (numpy, O(M*n)): the definition `farthest_point_sampling` must match."""
    pts, cand, cur = _candidates(points, n, seed, oversample)
    if cand is None:
        return np.resize(np.arange(pts.shape[0], dtype=np.int64), n)
    cx, cy, cz = (np.ascontiguousarray(pts[cand, k]) for k in range(3))
    chosen = np.empty(n, dtype=np.int64)
    min_d2 = np.full(cand.shape[0], np.inf)
    for i in range(n):
        chosen[i] = cur
        d2 = (cx - cx[cur]) ** 2
        d2 += (cy - cy[cur]) ** 2
        d2 += (cz - cz[cur]) ** 2
        np.minimum(min_d2, d2, out=min_d2)
        cur = int(np.argmax(min_d2))
    return cand[chosen]


def warm_up() -> None:
    """Compile the kernel now (about a second), e.g. in a process that forks workers."""
    farthest_point_sampling(np.random.default_rng(0).random((64, 3)), 8)


def _candidates(points: np.ndarray, n: int, seed: int, oversample: int | None):
    """(points as float64, candidate indices or None when every point is returned, start candidate)."""
    pts = np.asarray(points, dtype=np.float64)
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise ValueError(f"points must be (N, 3), got shape {pts.shape}")
    if n <= 0:
        raise ValueError(f"n must be positive, got {n}")
    n_pts = pts.shape[0]
    if n_pts == 0:
        raise ValueError("farthest_point_sampling got 0 points (empty cloud: check depth validity / crop box)")
    if n_pts <= n:
        return pts, None, 0
    rng = np.random.default_rng(seed)
    if oversample is not None and n_pts > oversample * n:
        cand = np.sort(rng.choice(n_pts, size=oversample * n, replace=False))
    else:
        cand = np.arange(n_pts, dtype=np.int64)
    return pts, cand, int(rng.integers(cand.shape[0]))


def _buckets(sub: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Candidates grouped by grid cell: the order (stable, so each cell lists its candidates by index), the
    cells' start offsets (with the end appended) and the cells' bounding boxes."""
    m = sub.shape[0]
    cells = max(1, int(round((m / _BUCKET_POINTS) ** (1.0 / 3.0))))
    lo, hi = sub.min(axis=0), sub.max(axis=0)
    span = np.where(hi > lo, hi - lo, 1.0)
    ijk = np.minimum((sub - lo) / span * cells, cells - 1).astype(np.int64)
    key = (ijk[:, 0] * cells + ijk[:, 1]) * cells + ijk[:, 2]
    order = np.argsort(key, kind="stable")
    key = key[order]
    starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
    bounds = np.r_[starts, m]
    s = sub[order]
    box_lo = np.minimum.reduceat(s, starts, axis=0)
    box_hi = np.maximum.reduceat(s, starts, axis=0)
    return order, bounds.astype(np.int64), box_lo, box_hi


@njit(cache=True, inline="always")
def _gap2(v, lo, hi):  # pragma: no cover - compiled
    if v < lo:
        return (lo - v) * (lo - v)
    if v > hi:
        return (v - hi) * (v - hi)
    return 0.0


@njit(cache=True, nogil=True)
def _bucketed_fps(x, y, z, orig, bounds, box_lo, box_hi, n, start):  # pragma: no cover - compiled
    m = x.shape[0]
    nb = bounds.shape[0] - 1
    min_d2 = np.full(m, np.inf)
    cell_max = np.full(nb, np.inf)  # the largest min-distance in each cell
    cell_arg = np.empty(nb, np.int64)  # where it is (position in bucket order); first index on ties
    for b in range(nb):
        cell_arg[b] = bounds[b]
    chosen = np.empty(n, np.int64)
    cur = start
    for i in range(n):
        chosen[i] = orig[cur]
        px, py, pz = x[cur], y[cur], z[cur]
        for b in range(nb):
            # Squared distance from the new point to the cell's box: a lower bound for every member.
            g = _gap2(px, box_lo[b, 0], box_hi[b, 0]) + _gap2(py, box_lo[b, 1], box_hi[b, 1]) + \
                _gap2(pz, box_lo[b, 2], box_hi[b, 2])
            if g > cell_max[b] * (1.0 + _SKIP_MARGIN):
                continue
            best, arg = -1.0, bounds[b]
            for j in range(bounds[b], bounds[b + 1]):
                dx = x[j] - px
                dy = y[j] - py
                dz = z[j] - pz
                d = dx * dx
                d += dy * dy
                d += dz * dz
                if d < min_d2[j]:
                    min_d2[j] = d
                if min_d2[j] > best:
                    best, arg = min_d2[j], j
            cell_max[b], cell_arg[b] = best, arg
        # The farthest candidate overall; on equal distances the lowest candidate index, as np.argmax.
        bb = 0
        for b in range(1, nb):
            if cell_max[b] > cell_max[bb] or (cell_max[b] == cell_max[bb] and orig[cell_arg[b]] < orig[cell_arg[bb]]):
                bb = b
        cur = cell_arg[bb]
    return chosen
