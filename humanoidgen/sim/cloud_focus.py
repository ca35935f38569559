"""A point cloud focused on the hands: part of the farthest-point sample drawn from near them.

Farthest-point sampling spreads its points evenly over everything the crop box holds, so a part a hand must
close on gets the share of points its size earns: close_drawer's 1 cm handle post got 1-3 of 256 (docs/results/
policies.md). A focused cloud draws a share of its points by FPS from the points within a radius of the hands
and the rest from the whole crop as before, and interleaves the two so that any prefix of the cloud (a policy
reads the first `num_points`) keeps that share. With no point near a hand the whole cloud is drawn as before.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.sim.fps import farthest_point_sampling


def near_mask(points: np.ndarray, centres: np.ndarray, radius: float) -> np.ndarray:
    """(N,) True where a point lies within `radius` of any of `centres` (K, 3)."""
    centres = np.asarray(centres, dtype=np.float64).reshape(-1, 3)
    near = np.zeros(points.shape[0], dtype=bool)
    for c in centres:
        near |= ((points[:, :3] - c) ** 2).sum(axis=1) <= radius * radius
    return near


def focused_sample(points: np.ndarray, n: int, share: float, centres: np.ndarray, radius: float,
                   seed: int = 0) -> np.ndarray:
    """Indices (n,) into `points`: round(n * share) by FPS among the points within `radius` of `centres`, the
    rest by FPS among all, interleaved in proportion (each prefix holds about its share of near points)."""
    near_idx = np.flatnonzero(near_mask(points, centres, radius)) if share > 0 else np.empty(0, np.int64)
    n_near = int(round(n * share)) if near_idx.size else 0
    whole = farthest_point_sampling(points[:, :3], n - n_near, seed=seed) if n > n_near else np.empty(0, np.int64)
    if n_near == 0:
        return whole
    near = near_idx[farthest_point_sampling(points[near_idx, :3], n_near, seed=seed)]
    # Each point's place in its own sample, as a fraction; a stable sort merges the two samples evenly.
    keys = np.concatenate([(np.arange(whole.size) + 0.5) / max(whole.size, 1), (np.arange(n_near) + 0.5) / n_near])
    return np.concatenate([whole, near])[np.argsort(keys, kind="stable")]
