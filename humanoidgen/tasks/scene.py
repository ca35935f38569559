"""Turning a task's layout into a running scene, and the footprint geometry the layout sampler checks."""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING

import mujoco
import numpy as np

from humanoidgen.objects.library import add_object
from humanoidgen.objects import library
from humanoidgen.objects.articulated import set_openness
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.scene import Scene, SceneBuilder, SceneObject

if TYPE_CHECKING:
    from humanoidgen.scenes.dressing import SceneDressing
    from humanoidgen.tasks.spec import ResolvedObject, TaskSpec
    from humanoidgen.tasks.targets import SceneTargets

SETTLE_S = 0.3  # long enough for objects dropped from their bbox height to come to rest
_NUMBERED = re.compile(r"^([a-z_]*[a-z])_?(\d+)$")  # "cube0", "cube_1", "bottle1": the paper's way of naming objects


@dataclass
class TaskScene(Scene):
    """A task's scene: the compiled scene plus the task's object aliases and target poses.

    `object()` is where every planner call and query turns a name into an object, so aliases are resolved here
    once: "rectangular_cube" (an alias from the task's YAML), "cube0" / "cube_0" (type and obj_id in one name, as
    the paper's task descriptions write them) and plain "cube" with obj_id."""

    aliases: dict[str, tuple[str, int]] = field(default_factory=dict)
    targets: SceneTargets | None = None

    @classmethod
    def wrap(cls, scene: Scene, aliases: dict[str, tuple[str, int]] | None = None) -> TaskScene:
        return cls(**{f.name: getattr(scene, f.name) for f in fields(Scene)}, aliases=dict(aliases or {}))

    def object(self, type_name: str, obj_id: int = 0) -> SceneObject:
        canonical = self.resolve(type_name, obj_id)
        try:
            return super().object(*canonical)
        except KeyError as exc:
            if not self.aliases:
                raise
            names = ", ".join(f"{a} = {t}[{i}]" for a, (t, i) in sorted(self.aliases.items()))
            raise KeyError(f"{exc.args[0] if exc.args else exc}; aliases: {names}") from None

    def resolve(self, name: str, obj_id: int = 0) -> tuple[str, int]:
        """(type, obj_id) that a plan's (name, obj_id) means."""
        if not isinstance(name, str) or any(o.type_name == name for o in self.objects):
            return name, obj_id
        if name in self.aliases:
            t, i = self.aliases[name]
            if obj_id not in (0, i):
                raise KeyError(f"{name!r} names one object, {t}[{i}]; leave obj_id out (or use "
                               f"obj_name={t!r}, obj_id={obj_id})")
            return t, i
        m = _NUMBERED.match(name)
        if m is not None:
            base, n = m.group(1), int(m.group(2))
            if base in self.aliases:
                # "rectangular_cube0": the paper numbers even a single object; 0 (or its own obj_id) is the only one.
                t, i = self.aliases[base]
                if n not in (0, i):
                    raise KeyError(f"{name!r}: {base!r} names one object, {t}[{i}]; use obj_name={base!r}")
                return self.resolve(base, obj_id)
            if any(o.type_name == base for o in self.objects):
                # obj_id 0 is the default: "cube1" with obj_id left out (or 0) means cube[1].
                if obj_id not in (0, n):
                    raise KeyError(f"{name!r} says obj_id {n} but obj_id={obj_id} was given; use "
                                   f"obj_name={base!r}, obj_id={n}")
                return base, n
        return name, obj_id


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


def build_layout(layout: list[ResolvedObject], settle_s: float = SETTLE_S,
                 aliases: dict[str, tuple[str, int]] | None = None, dressing: SceneDressing | None = None
                 ) -> tuple[TaskScene, HumanoidEnv]:
    """Add the objects in order, set the articulated ones' openness, and let everything settle with the robot
    holding its initial posture. `dressing`: a room around the table and/or a randomized look."""
    builder = SceneBuilder() if dressing is None else \
        SceneBuilder(surface_height=dressing.surface_height, dressing=dressing)
    objs = [add_object(builder, o.type, o.type_id, pos=tuple(o.pos), yaw=o.yaw) for o in layout]
    scene = TaskScene.wrap(builder.build(), aliases)
    env = HumanoidEnv(scene)
    for spec, obj in zip(layout, objs):
        if spec.openness is not None:
            set_openness(env.model, env.data, obj.body, obj.annotations, spec.openness)
    mujoco.mj_forward(env.model, env.data)
    action = env.init_action()
    for _ in range(round(settle_s * env.control_hz)):
        env.step(action)
    return scene, env


def build_scene(spec: TaskSpec, seed: int | None = None, settle_s: float = SETTLE_S,
                dressing: SceneDressing | None = None) -> tuple[TaskScene, HumanoidEnv]:
    """The task's scene for episode `seed` (None: the default layout), with the task's aliases and targets."""
    from humanoidgen.tasks.targets import SceneTargets

    scene, env = build_layout(spec.sample_layout(seed), settle_s=settle_s, aliases=spec.aliases(), dressing=dressing)
    # After settling: a target anchored at an object's start is where the object came to rest.
    scene.targets = SceneTargets(list(spec.targets), seed, env)
    return scene, env
