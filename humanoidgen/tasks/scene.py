"""Turning a task's layout into a running scene, and the footprint geometry the layout sampler checks."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING

import mujoco
import numpy as np

from humanoidgen.objects import library
from humanoidgen.objects.articulated import set_openness
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.scene import Scene, SceneBuilder

if TYPE_CHECKING:
    from humanoidgen.tasks.spec import ResolvedObject, TaskSpec

SETTLE_S = 0.3  # long enough for objects dropped from their bbox height to come to rest


def footprint(obj: ResolvedObject) -> np.ndarray:
    """The four xy corners of the object's (closed-state) bounding box on the table, turned by its yaw."""
    ann = library.annotations(obj.type, obj.type_id)
    (x0, y0, _), (x1, y1, _) = ann.bbox_min, ann.bbox_max
    local = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
    c, s = math.cos(obj.yaw), math.sin(obj.yaw)
    return local @ np.array([[c, s], [-s, c]]) + np.asarray(obj.pos[:2])


def _separated(a: np.ndarray, b: np.ndarray) -> bool:
    """Separating-axis test for two convex quads."""
    for poly in (a, b):
        for k in range(4):
            edge = poly[(k + 1) % 4] - poly[k]
            axis = np.array([-edge[1], edge[0]])
            pa, pb = a @ axis, b @ axis
            if pa.max() <= pb.min() or pb.max() <= pa.min():
                return True
    return False


def overlapping_pairs(layout: list[ResolvedObject], skip: Iterable[tuple[int, int]] = ()) -> list[tuple[int, int]]:
    """Index pairs whose footprints overlap (pairs in `skip`, e.g. a cup and its contents, are allowed),
    counting only objects resting on the table (no explicit z): contents placed in the air don't collide."""
    skip = {tuple(sorted(p)) for p in skip}
    prints = [footprint(o) for o in layout]
    out = []
    for i in range(len(layout)):
        for j in range(i + 1, len(layout)):
            if (i, j) in skip or len(layout[i].pos) > 2 or len(layout[j].pos) > 2:
                continue
            if not _separated(prints[i], prints[j]):
                out.append((i, j))
    return out


def build_layout(layout: list[ResolvedObject], settle_s: float = SETTLE_S) -> tuple[Scene, HumanoidEnv]:
    """Add the objects in order, set the articulated ones' openness, and let everything settle with the robot
    holding its initial posture."""
    builder = SceneBuilder()
    objs = [builder.add_object(o.type, o.type_id, pos=tuple(o.pos), yaw=o.yaw) for o in layout]
    scene = builder.build()
    env = HumanoidEnv(scene)
    for spec, obj in zip(layout, objs):
        if spec.openness is not None:
            set_openness(env.model, env.data, obj.body, obj.annotations, spec.openness)
    mujoco.mj_forward(env.model, env.data)
    action = env.init_action()
    for _ in range(round(settle_s * env.control_hz)):
        env.step(action)
    return scene, env


def build_scene(spec: TaskSpec, seed: int | None = None, settle_s: float = SETTLE_S) -> tuple[Scene, HumanoidEnv]:
    """The task's scene for episode `seed` (None: the default layout)."""
    return build_layout(spec.sample_layout(seed), settle_s=settle_s)
