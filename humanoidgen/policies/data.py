"""Training data from `hgen dataset export --zarr`: which keys are read, and the (observation, action
sequence) samples cut from its episodes.

Keys read (the export's documented layout):
    data/state         (T, 26) float32  joint positions, action order  -> every policy
    data/action        (T, 26) float32  joint targets                  -> every policy
    data/img           (T, H, W, 3) uint8  the export's --camera        -> DP
    data/point_cloud   (T, N, 3) float32  fused, cropped, FPS-sampled   -> DP3 (the first num_points: FPS order)
    data/ee_pose       (T, 14) float32  the hands' poses               -> a policy with observe_hands ("hands")
    meta/episode_ends  (E,) int64       cumulative frame counts
    attributes task, control_hz, camera, recorder (written by the export; older exports lack them: then the
    task and rate come from the caller)

A sample starting at frame s of an episode [a, b) covers frames s .. s+horizon-1 clipped to the episode (the
first frame repeated before it, the last after it), its observations are the first n_obs_steps of those, as
DP's SequenceSampler pads (n_obs_steps - 1 before, n_action_steps - 1 after)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

# What each policy input is called in the zarr and in the environment's observations.
ZARR_KEYS = {"state": "data/state", "action": "data/action", "img": "data/img", "point_cloud": "data/point_cloud",
             "hands": "data/ee_pose"}
HOW_TO_GET = {
    "point_cloud": "collect with --point-cloud (the default) and export again",
    "img": "collect with the camera in --cameras and export with --camera",
    "hands": "export the dataset again (hgen dataset export), which writes the hands' poses",
}


class DataError(ValueError):
    """Training data that cannot be used; the message says what to do."""


@dataclass
class Demos:
    path: Path
    arrays: dict[str, np.ndarray]
    episode_ends: np.ndarray
    attrs: dict = field(default_factory=dict)

    @property
    def n_episodes(self) -> int:
        return len(self.episode_ends)

    @property
    def n_frames(self) -> int:
        return int(self.episode_ends[-1]) if len(self.episode_ends) else 0


def read_demos(path: Path, keys: tuple[str, ...], episodes: int | None = None, why: str = "") -> Demos:
    """The first `episodes` episodes (all: None) of the zarr at `path`, with the arrays `keys` names."""
    import zarr

    path = Path(path)
    if not path.exists():
        raise DataError(f"no training data at {path}; make it with: hgen dataset export DATASET --zarr {path}")
    try:
        root = zarr.open_group(str(path), mode="r")
        ends = np.asarray(root["meta/episode_ends"][:], np.int64)
    except Exception:  # noqa: BLE001 - any failure to open it means it is not an export
        raise DataError(f"{path} is not a zarr export (no meta/episode_ends); make one with "
                        f"hgen dataset export DATASET --zarr {path}") from None
    if episodes is not None:
        if episodes > len(ends):
            raise DataError(f"{path} has {len(ends)} episodes, fewer than the {episodes} asked for")
        ends = ends[:episodes]
    n = int(ends[-1]) if len(ends) else 0
    if n == 0:
        raise DataError(f"{path} has no frames")
    arrays = {}
    for k in ("action", *keys):
        key = ZARR_KEYS[k]
        if key not in root:
            hint = f"; {HOW_TO_GET[k]}" if k in HOW_TO_GET else ""
            raise DataError(f"{path} has no {key}{' (' + why + ')' if why else ''}{hint}")
        arrays[k] = root[key] if k == "img" else np.asarray(root[key][:n])  # images: read lazily, resized later
    return Demos(path, arrays, ends, dict(root.attrs))


def sequence_index(episode_ends: np.ndarray, horizon: int, n_obs_steps: int, n_action_steps: int) -> np.ndarray:
    """(S, horizon) frame indices of every sample (see the module docstring)."""
    out = []
    start = 0
    steps = np.arange(horizon)
    for end in np.asarray(episode_ends, np.int64):
        first, last = start - (n_obs_steps - 1), end - horizon + (n_action_steps - 1)
        for s in range(first, max(first, last) + 1):
            out.append(np.clip(s + steps, start, end - 1))
        start = end
    return np.asarray(out, np.int64).reshape(-1, horizon)
