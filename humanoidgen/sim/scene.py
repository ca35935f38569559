"""The table scene: floor, table, lights, the robot, six cameras and the objects placed on the table.

A `SceneBuilder` edits one MjSpec; `build()` compiles it into a `Scene` (model plus the bookkeeping that maps
objects to bodies and geoms to segmentation labels).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from collections.abc import Callable
from pathlib import Path
from typing import Any

import mujoco
import numpy as np

from humanoidgen.assets.robot_files import resolve_assets_root
from humanoidgen.sim.cameras import add_cameras
from humanoidgen.sim.layout import ROBOT, ROBOT_BASE_POS, ROOT_BODY, TABLE_THICKNESS, TABLE_TOP_Z, TABLE_X, TABLE_Y
from humanoidgen.sim.meshes import floor_grid, visual_faces
from humanoidgen.sim.robot import build_robot_spec

# Segmentation labels: static world, the robot, then one label per object in the order they were added.
LABEL_BACKGROUND = 0
LABEL_ROBOT = 1
FIRST_OBJECT_LABEL = 2

# The upstream model's feet stand this far below its root body (the robot file's `stand.feet_below_base`).
FLOOR_Z = ROBOT_BASE_POS[2] - ROBOT.data.stand.feet_below_base
# Contacts need a small step for a pinched cube to hold still; 2 ms is the largest that keeps it so.
DEFAULT_TIMESTEP = 0.002


@dataclass(frozen=True)
class SceneObject:
    """An object in the scene, addressed like the paper's API: by type and `obj_id` (order of adding)."""

    type_name: str
    obj_id: int
    body: str
    label: int
    type_id: int = 0
    # Key points and axes: an objects.schema.ObjectAnnotations (None for ad-hoc shapes). Typed loosely here
    # because objects sits above sim: the simulator only carries them.
    annotations: Any = None


@dataclass
class Scene:
    """A compiled scene."""

    model: mujoco.MjModel
    objects: list[SceneObject]
    geom_labels: np.ndarray
    label_names: dict[int, str]

    def object(self, type_name: str, obj_id: int = 0) -> SceneObject:
        for obj in self.objects:
            if obj.type_name == type_name and obj.obj_id == obj_id:
                return obj
        known = sorted({f"{o.type_name}[{o.obj_id}]" for o in self.objects})
        raise KeyError(f"no object {type_name}[{obj_id}] in the scene; objects: {', '.join(known) or 'none'}")


@dataclass
class SceneBuilder:
    """Builds the robot at its table; add objects, then `build()`."""

    assets_root: Path | None = None
    timestep: float = DEFAULT_TIMESTEP
    offscreen_size: tuple[int, int] = (1280, 960)
    msaa_samples: int = 0  # multisample anti-aliasing for pictures; it costs ~40% of a software-rendered frame
    # Table top above the floor: the robot's feet stand on the floor, so its base follows (scenes.room).
    surface_height: float = TABLE_TOP_Z - FLOOR_Z
    # Applied to the spec once the table scene is built: a room and a look (scenes.dressing.SceneDressing).
    dressing: Callable[[mujoco.MjSpec], None] | None = None
    spec: mujoco.MjSpec = field(init=False, repr=False)
    _objects: list[SceneObject] = field(default_factory=list, init=False, repr=False)

    def __post_init__(self) -> None:
        root = Path(self.assets_root) if self.assets_root is not None else resolve_assets_root()
        self.spec = build_robot_spec(root, visual_faces())
        self.spec.modelname = "humanoidgen_table"
        opt = self.spec.option
        opt.timestep = self.timestep
        opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
        opt.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
        opt.impratio = 10.0  # stiffer friction: objects held between fingertips do not creep
        self.spec.visual.global_.offwidth = self.offscreen_size[0]
        self.spec.visual.global_.offheight = self.offscreen_size[1]
        self.spec.visual.quality.shadowsize = 2048
        self.spec.visual.quality.offsamples = self.msaa_samples
        self.spec.visual.headlight.ambient = [0.35, 0.35, 0.35]
        self.spec.visual.headlight.diffuse = [0.45, 0.45, 0.45]
        self._add_floor_and_table()
        self._add_lights()
        add_cameras(self.spec)
        base_dz = self.surface_height - (TABLE_TOP_Z - FLOOR_Z)
        self.spec.body(ROOT_BODY).pos = (ROBOT_BASE_POS - [0.0, 0.0, base_dz]).tolist()
        if self.dressing is not None:
            self.dressing(self.spec)

    # -- static world -------------------------------------------------------------------------------------
    def _add_floor_and_table(self) -> None:
        spec = self.spec
        tex = spec.add_texture(
            name="floor_tex", type=mujoco.mjtTexture.mjTEXTURE_2D, builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER,
            rgb1=[0.55, 0.57, 0.6], rgb2=[0.48, 0.5, 0.53], width=256, height=256,
        )
        # No reflective materials: each mirror surface makes the renderer draw the scene once more.
        floor_mat = spec.add_material(name="floor_mat", texrepeat=[6, 6])
        floor_mat.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = tex.name
        spec.add_material(name="table_mat", rgba=[0.62, 0.48, 0.34, 1.0])
        spec.add_material(name="table_leg_mat", rgba=[0.3, 0.3, 0.32, 1.0])
        world = spec.worldbody
        floor_z = TABLE_TOP_Z - self.surface_height
        world.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[4, 4, floor_grid()],
                       pos=[0, 0, floor_z],
                       material="floor_mat")
        cx, cy = np.mean(TABLE_X), np.mean(TABLE_Y)
        hx, hy, ht = (TABLE_X[1] - TABLE_X[0]) / 2, (TABLE_Y[1] - TABLE_Y[0]) / 2, TABLE_THICKNESS / 2
        table = world.add_body(name="table", pos=[cx, cy, TABLE_TOP_Z])
        table.add_geom(name="table_top", type=mujoco.mjtGeom.mjGEOM_BOX, size=[hx, hy, ht], pos=[0, 0, -ht],
                       material="table_mat", friction=[1.0, 0.01, 0.001])  # as grippy as the fingertips
        leg_h = (TABLE_TOP_Z - TABLE_THICKNESS - floor_z) / 2
        for sx in (-1, 1):
            for sy in (-1, 1):
                table.add_geom(
                    type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.03, 0.03, leg_h], material="table_leg_mat",
                    pos=[sx * (hx - 0.05), sy * (hy - 0.05), -TABLE_THICKNESS - leg_h], contype=0, conaffinity=0,
                )

    def _add_lights(self) -> None:
        world = self.spec.worldbody
        world.add_light(name="key", pos=[0.2, -0.6, 2.2], dir=[-0.3, 0.3, -1], diffuse=[0.6, 0.6, 0.6],
                        castshadow=True)
        world.add_light(name="fill", pos=[-0.4, 0.8, 1.8], dir=[0.1, -0.4, -1], diffuse=[0.3, 0.3, 0.3],
                        castshadow=False)

    # -- objects -----------------------------------------------------------------------------------------
    def _next_obj_id(self, type_name: str) -> int:
        return sum(1 for o in self._objects if o.type_name == type_name)

    def add_object_body(self, type_name: str, pos: np.ndarray, quat: np.ndarray = (1, 0, 0, 0),
                        type_id: int = 0, free: bool = True, annotations: Any = None
                        ) -> tuple[SceneObject, mujoco.MjsBody]:
        """Register an object and return its (empty) body for the caller to fill with geoms and joints. A model
        of the asset library is added with `objects.library.add_object`."""
        obj_id = self._next_obj_id(type_name)
        body_name = f"{type_name}_{obj_id}"
        body = self.spec.worldbody.add_body(name=body_name, pos=list(pos), quat=list(quat))
        if free:
            body.add_freejoint(name=f"{body_name}_free")
        obj = SceneObject(type_name=type_name, obj_id=obj_id, body=body_name,
                          label=FIRST_OBJECT_LABEL + len(self._objects), type_id=type_id, annotations=annotations)
        self._objects.append(obj)
        return obj, body

    def add_cube(self, size: float = 0.04, pos: tuple[float, float, float] | None = None,
                 rgba: tuple[float, float, float, float] = (0.85, 0.2, 0.15, 1.0), mass: float = 0.05,
                 quat: tuple[float, float, float, float] = (1, 0, 0, 0)) -> SceneObject:
        """A solid cube of edge `size` (m); by default resting on the table in front of the right hand."""
        if size <= 0 or mass <= 0:
            raise ValueError("cube size and mass must be positive")
        if pos is None:
            pos = (-0.30, -0.10, TABLE_TOP_Z + size / 2)
        obj, body = self.add_object_body("cube", np.asarray(pos, float), np.asarray(quat, float))
        half = size / 2
        body.add_geom(name=f"{obj.body}_geom", type=mujoco.mjtGeom.mjGEOM_BOX, size=[half] * 3, rgba=list(rgba),
                      mass=mass, friction=[1.0, 0.01, 0.001], condim=4)
        return obj

    # -- compile -----------------------------------------------------------------------------------------
    def build(self) -> Scene:
        if before_compile is not None:
            before_compile()
        model = self.spec.compile()
        return Scene(model=model, objects=list(self._objects), geom_labels=_geom_labels(model, self._objects),
                     label_names=_label_names(self._objects))


# Called right before each scene's compile in this process, where set. The workers' fork server sets it while
# one of its threads builds a scene (`sandbox.preload`): its other thread holds back its own imports until the
# scene's spec is built, instead of taking Python's lock from it every few milliseconds, and imports while the
# compile runs without the lock.
before_compile: Callable[[], None] | None = None


def _geom_labels(model: mujoco.MjModel, objects: list[SceneObject]) -> np.ndarray:
    robot_root = model.body(ROOT_BODY).id
    by_body = {model.body(o.body).id: o.label for o in objects}
    labels = np.full(model.ngeom, LABEL_BACKGROUND, dtype=np.int32)
    for g in range(model.ngeom):
        root = int(model.body_rootid[model.geom_bodyid[g]])
        if root == robot_root:
            labels[g] = LABEL_ROBOT
        elif root in by_body:
            labels[g] = by_body[root]
    return labels


def _label_names(objects: list[SceneObject]) -> dict[int, str]:
    names = {-1: "none", LABEL_BACKGROUND: "background", LABEL_ROBOT: "robot"}
    names.update({o.label: f"{o.type_name}[{o.obj_id}]" for o in objects})
    return names
