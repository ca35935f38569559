"""Draw what stays still once per episode, and only what moves in every frame.

A recorded episode is rendered after its physics (`episodes.render_replay`), so every frame's configuration is
known before the first is drawn. A geom at the same pose in all of them (the floor, the table, the robot's
legs and torso, an object nobody touches) looks the same in every frame of a camera that does not move
either, as long as nothing in the picture depends on other geoms: no shadows, no reflecting material, no
see-through colour, no moving light (checked; otherwise nothing is layered). The renderer's lighting is per
vertex and per geom, so a still geom's pixels do not depend on what moves in front of it.

So for each still camera the still geoms are drawn once into a colour and a depth layer (`StillLayer`), and
each frame draws the moving geoms alone and keeps their pixels where they are nearer than the layer's: the
depth test the renderer does, on the same depth-buffer values. The frames are the renderer's own pixels
(tested against drawing everything at once); the one case that could differ, a moving and a still surface at
exactly the same depth value, is left to the still one here and to draw order there. Measured on recorded
episodes (six 320x240 cameras, four of them still; `bench/still_layers.py`, identical arrays): drawing a
hand-over frame took 36% less CPU, rendering its episode with clouds and depth 28% less, block_stack_single's
23% less.

The still geoms are moved to a group of their own (`STILL_GROUP`) in a copy of the model, so a rig can draw
them, or everything else, by geom group.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass

import mujoco
import numpy as np
from numba import njit

from humanoidgen.sim.cameras import pose_data

STILL_GROUP = 4  # no scene geom uses it: MuJoCo draws groups 0-2 by default, the robot's collision meshes are 3
DEFAULT_GROUPS = (0, 1, 2)


@dataclass(frozen=True)
class StillParts:
    """What stays still through an episode: drawn geoms (mask over the model's geoms) and camera names."""

    geoms: np.ndarray
    cameras: frozenset[str]

    @property
    def worth_layering(self) -> bool:
        return bool(self.cameras) and bool(self.geoms.any())


@dataclass(frozen=True)
class StillLayer:
    """One still camera's still geoms: colour (H, W, 3) uint8 and depth-buffer values (H, W) float32, both as
    the renderer holds them (bottom row first; `zero_far`: 0 at the far plane, larger is nearer, as MuJoCo's
    reversed depth map reads them)."""

    rgb: np.ndarray
    zbuf: np.ndarray
    zero_far: bool

    def under(self, rgb: np.ndarray, zbuf: np.ndarray) -> None:
        """Put the layer under a moving-geoms pass, in place: its pixels stay where they are nearer."""
        if rgb.shape != self.rgb.shape or zbuf.shape != self.zbuf.shape:
            raise ValueError(f"a {self.zbuf.shape} layer cannot go under a {zbuf.shape} pass")
        _under(rgb, zbuf, self.rgb, self.zbuf, self.zero_far)


def warm_up() -> None:
    """Compile (or load from numba's cache) the compositing kernel now."""
    StillLayer(np.zeros((1, 1, 3), np.uint8), np.zeros((1, 1), np.float32), True).under(
        np.zeros((1, 1, 3), np.uint8), np.zeros((1, 1), np.float32))


def still_parts(model: mujoco.MjModel, configurations: Sequence[np.ndarray], shadows: bool = False,
                groups: Sequence[int] = DEFAULT_GROUPS) -> StillParts:
    """The geoms of `groups` and the cameras whose poses are the same, bit for bit, in every configuration;
    nothing when layering could change a pixel (shadows, a moving light, reflection, transparency)."""
    nothing = StillParts(np.zeros(model.ngeom, bool), frozenset())
    drawn = np.isin(model.geom_group, list(groups))
    if shadows or len(configurations) < 2 or not _pixels_are_per_geom(model, drawn):
        return nothing
    data = mujoco.MjData(model)
    pose_data(model, data, configurations[0])
    first = _poses(data)
    geom_still, cam_still = np.ones(model.ngeom, bool), np.ones(model.ncam, bool)
    for q in configurations[1:]:
        pose_data(model, data, q)
        geoms, cams, lights = _poses(data)
        geom_still &= (geoms == first[0]).all(axis=1)
        cam_still &= (cams == first[1]).all(axis=1)
        if not (lights == first[2]).all():
            return nothing
    return StillParts(geom_still & drawn, frozenset(model.camera(int(i)).name for i in np.flatnonzero(cam_still)))


def layered_model(model: mujoco.MjModel, still: StillParts) -> mujoco.MjModel:
    """A copy of `model` with the still geoms in `STILL_GROUP` (the physics is not run on it)."""
    out = copy.copy(model)
    out.geom_group[still.geoms] = STILL_GROUP
    return out


def moving_groups(groups: Sequence[int]) -> tuple[int, ...]:
    return tuple(g for g in groups if g != STILL_GROUP)


def _poses(data: mujoco.MjData) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return (np.concatenate([data.geom_xpos, data.geom_xmat], axis=1),
            np.concatenate([data.cam_xpos, data.cam_xmat], axis=1),
            np.concatenate([data.light_xpos, data.light_xdir], axis=1))


def _pixels_are_per_geom(model: mujoco.MjModel, drawn: np.ndarray) -> bool:
    """No drawn geom is see-through or reflects others (its pixels would depend on what is behind or near)."""
    if (model.geom_rgba[drawn, 3] < 1.0).any():
        return False
    mats = model.geom_matid[drawn]
    mats = mats[mats >= 0]
    return not ((model.mat_rgba[mats, 3] < 1.0).any() or (model.mat_reflectance[mats] > 0.0).any())


# Compiled: numpy's masked copies took about 1 ms a view (two full passes and a broadcast mask), this one pass
# about a twentieth of it, and it lets go of the GIL, so two renderer threads composite at once.
@njit(cache=True, nogil=True)
def _under(rgb, zbuf, layer_rgb, layer_zbuf, zero_far):  # pragma: no cover - compiled
    h, w = zbuf.shape
    for i in range(h):
        for j in range(w):
            z, s = zbuf[i, j], layer_zbuf[i, j]
            if (z > s) if zero_far else (z < s):
                continue
            zbuf[i, j] = s
            for k in range(3):
                rgb[i, j, k] = layer_rgb[i, j, k]
