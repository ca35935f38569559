"""The statistics of a LeRobot export (meta/stats.json and each episode's row), computed the way
lerobot.datasets.compute_stats computes them, so LeRobot normalises our data as it would its own.

One departure, in the dataset's stats.json only: a state or action dimension that never moved (the idle arm of a
one-arm task, an unused hand; lerobot-doctor's "zero variance" finding) gets a normalisation span of MIN_SPAN
around its value. LeRobot normalises by max - min (or std), with 1e-8 where that is 0, so a joint recorded at
one value would turn an evaluation's deviation of 1e-4 rad into 1e4. The episodes' own stats stay as measured."""

from __future__ import annotations

import numpy as np

QUANTILES = (0.01, 0.10, 0.50, 0.90, 0.99)
MIN_SPAN = 0.02  # rad (state, action) or m / quaternion units (ee_pose): about 1.1 deg; joints moving more keep theirs


def _quantiles(x: np.ndarray, bins: int = 5000) -> dict[str, np.ndarray]:
    """Histogram quantiles per column of x (N, D), as lerobot's RunningQuantileStats computes them for one batch."""
    out = {f"q{int(q * 100):02d}": np.empty(x.shape[1]) for q in QUANTILES}
    n = x.shape[0]
    for d in range(x.shape[1]):
        col = x[:, d]
        edges = np.linspace(col.min() - 1e-10, col.max() + 1e-10, bins + 1)
        cum = np.cumsum(np.histogram(col, bins=edges)[0])
        for q in QUANTILES:
            target = q * n
            i = int(np.searchsorted(cum, target))
            if i == 0:
                v = edges[0]
            elif i >= len(cum):
                v = edges[-1]
            else:
                before, inside = cum[i - 1], cum[i] - cum[i - 1]
                v = edges[i] if inside == 0 else edges[i] + (target - before) / inside * (edges[i + 1] - edges[i])
            out[f"q{int(q * 100):02d}"][d] = v
    return out


def vector_stats(x: np.ndarray) -> dict[str, np.ndarray]:
    """Per-dimension stats of (T,) or (T, D); a (T,) column gets shape (1,) stats, like lerobot's keepdims."""
    x2 = np.asarray(x, np.float64).reshape(len(x), -1)
    stats = {"min": x2.min(0), "max": x2.max(0), "mean": x2.mean(0), "std": x2.std(0),
             "count": np.array([len(x)], np.int64)}
    if len(x2) < 2:
        stats.update({f"q{int(q * 100):02d}": stats["mean"].copy() for q in QUANTILES})
    else:
        stats.update(_quantiles(x2))
    return stats


def _sample_indices(n: int) -> list[int]:
    num = n if n < 100 else max(100, min(int(n ** 0.75), 10_000))
    return np.round(np.linspace(0, n - 1, num)).astype(int).tolist()


def image_stats(frames: np.ndarray) -> dict[str, np.ndarray]:
    """Per-channel stats in [0, 1], shape (3, 1, 1), over up to ~100 sampled frames of (T, H, W, 3) uint8."""
    imgs = frames[_sample_indices(len(frames))]
    h, w = imgs.shape[1:3]
    if max(h, w) >= 300:  # lerobot's auto_downsample_height_width
        f = int(w / 150) if w > h else int(h / 150)
        imgs = imgs[:, ::f, ::f]
    stats = vector_stats(imgs.reshape(-1, 3).astype(np.float64))
    stats["count"] = np.array([len(imgs)], np.int64)
    return {k: v if k == "count" else (v / 255.0).reshape(3, 1, 1) for k, v in stats.items()}


def aggregate(per_episode: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """lerobot's aggregate_feature_stats: count-weighted mean, pooled variance, weighted quantiles."""
    counts = np.stack([s["count"] for s in per_episode]).astype(np.float64)
    total = counts.sum(0)
    means = np.stack([s["mean"] for s in per_episode])
    w = counts.reshape(counts.shape + (1,) * (means.ndim - counts.ndim))
    mean = (means * w).sum(0) / total
    var = ((np.stack([s["std"] for s in per_episode]) ** 2 + (means - mean) ** 2) * w).sum(0) / total
    out = {"min": np.min([s["min"] for s in per_episode], axis=0), "max": np.max([s["max"] for s in per_episode], axis=0),
           "mean": mean, "std": np.sqrt(var), "count": total.astype(np.int64)}
    for q in QUANTILES:
        k = f"q{int(q * 100):02d}"
        out[k] = (np.stack([s[k] for s in per_episode]) * w).sum(0) / total
    return out


def jsonable(stats: dict[str, dict[str, np.ndarray]]) -> dict:
    return {key: {k: np.asarray(v).tolist() for k, v in s.items()} for key, s in stats.items()}


# -- writing --------------------------------------------------------------------------------------------------------


def floor_spread(s: dict[str, np.ndarray], span: float = MIN_SPAN) -> dict[str, np.ndarray]:
    """Feature stats with every dimension's min..max, q01..q99, q10..q90 at least `span` wide and std at least
    span / 2, centred where the data is."""
    out = dict(s)
    for lo, hi in (("min", "max"), ("q01", "q99"), ("q10", "q90")):
        a, b = np.asarray(s[lo], np.float64), np.asarray(s[hi], np.float64)
        narrow = b - a < span
        mid = (a + b) / 2
        out[lo], out[hi] = np.where(narrow, mid - span / 2, a), np.where(narrow, mid + span / 2, b)
    out["std"] = np.maximum(np.asarray(s["std"], np.float64), span / 2)
    return out


def dataset_stats_json(stats: dict[str, dict[str, np.ndarray]], vectors) -> dict:
    """stats.json's content: `vectors` (state, action, ee_pose) with their spread floored, the rest as measured."""
    return jsonable({k: floor_spread(s) if k in vectors else s for k, s in stats.items()})
