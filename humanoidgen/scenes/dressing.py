"""Dressing a scene: a room around the task and a randomized look, applied to the SceneBuilder's MjSpec.

Everything added here is static and purely visual (contype = conaffinity = 0, on the world body): a room's
walls, furniture and clutter and the distractors cost nothing in collision and cannot touch the task. What
a room changes physically is only the work surface's height above the floor: the robot's feet stand on the
floor, so its base moves with the floor (`surface_height`, see `SceneBuilder`). The task's table stays the
collision surface and keeps its extent; in a room it is drawn as a counter (a cabinet under the top).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from humanoidgen.scenes.frames import apply_point, inverse, yaw_of
from humanoidgen.scenes.room import DEFAULT_SURFACE_HEIGHT, Part, Room, generate_room
from humanoidgen.scenes.visuals import VisualParams, draw_visuals
from humanoidgen.sim.geometry import look_at_quat, yaw_quat
from humanoidgen.sim.layout import TABLE_THICKNESS, TABLE_TOP_Z, TABLE_X, TABLE_Y

_SHAPES = {"box": mujoco.mjtGeom.mjGEOM_BOX, "cylinder": mujoco.mjtGeom.mjGEOM_CYLINDER,
           "sphere": mujoco.mjtGeom.mjGEOM_SPHERE}


@dataclass(frozen=True)
class SceneDressing:
    """A room (None: the tabletop scene) and a look (None: the default one)."""

    room: Room | None = None
    visuals: VisualParams | None = None

    @classmethod
    def from_seeds(cls, room_seed: int | None = None, visual_seed: int | None = None) -> SceneDressing:
        return cls(generate_room(room_seed) if room_seed is not None else None,
                   draw_visuals(visual_seed) if visual_seed is not None else None)

    @property
    def surface_height(self) -> float:
        return self.room.surface_height if self.room is not None else DEFAULT_SURFACE_HEIGHT

    def to_dict(self) -> dict:
        """Everything needed to rebuild the same scene (stored in episode metadata), plus T_{O -> O'}."""
        return {"room": self.room.to_dict() if self.room else None,
                "visuals": self.visuals.to_dict() if self.visuals else None,
                "o_to_o_prime": self.room.transform.to_dict() if self.room else None}

    @classmethod
    def from_dict(cls, d: dict | None) -> SceneDressing:
        d = d or {}
        return cls(Room.from_dict(d["room"]) if d.get("room") else None,
                   VisualParams.from_dict(d["visuals"]) if d.get("visuals") else None)

    def __call__(self, spec: mujoco.MjSpec) -> None:
        if self.room is not None:
            dress_room(spec, self.room)
        if self.visuals is not None:
            apply_visuals(spec, self.visuals, in_room=self.room is not None)


def add_part(spec: mujoco.MjSpec, part: Part, name: str, to_task=None, material: str | None = None) -> None:
    """A static visual geom; `to_task` maps room coordinates into the tabletop world (None: already there)."""
    pos, yaw = np.asarray(part.pos, float), part.yaw
    if to_task is not None:
        pos, yaw = apply_point(to_task, pos), yaw + yaw_of(to_task)
    kw = {"material": material} if material else {"rgba": list(part.rgba)}
    spec.worldbody.add_geom(name=name, type=_SHAPES[part.shape], size=list(part.size) + [0] * (3 - len(part.size)),
                            pos=pos.tolist(), quat=yaw_quat(yaw).tolist(), contype=0, conaffinity=0, **kw)


def dress_room(spec: mujoco.MjSpec, room: Room) -> None:
    """Floor, walls, furniture and clutter of `room`, placed around the task (tabletop-world coordinates)."""
    to_task = inverse(room.transform)
    floor_z = TABLE_TOP_Z - room.surface_height
    sx, sy, _ = room.size
    # The floor plane keeps its height (the robot stands on it); it is resized and moved to the room.
    floor = spec.geom("floor")
    centre = apply_point(to_task, np.array([sx / 2, sy / 2, 0.0]))
    floor.pos = [float(centre[0]), float(centre[1]), floor_z]
    floor.quat = yaw_quat(yaw_of(to_task)).tolist()
    floor.size = [sx / 2, sy / 2, floor.size[2]]  # its rendering grid: the detail's (sim.meshes.floor_grid)
    tex = spec.texture("floor_tex")
    tex.rgb1, tex.rgb2 = list(room.floor_rgb[0]), list(room.floor_rgb[1])
    spec.material("floor_mat").texrepeat = [max(1.0, sx * 2), max(1.0, sy * 2)]
    spec.add_material(name="room_wall_mat", rgba=list(room.wall_rgba))
    spec.material("table_mat").rgba = list(room.surface_rgba)
    for i, part in enumerate(room.parts):
        # Room parts stand on the room floor (z up from it): T^-1 puts that floor at floor_z.
        add_part(spec, part, f"room_{part.kind}_{i}", to_task, "room_wall_mat" if part.kind == "wall" else None)
    # The cabinet under the work surface: floor to the table top's underside, inset so the top overhangs.
    hx, hy = (TABLE_X[1] - TABLE_X[0]) / 2 - 0.03, (TABLE_Y[1] - TABLE_Y[0]) / 2 - 0.03
    hz = (room.surface_height - TABLE_THICKNESS) / 2
    base = Part("box", (float(np.mean(TABLE_X)) + 0.01, float(np.mean(TABLE_Y)), TABLE_TOP_Z - TABLE_THICKNESS - hz),
                (hx, hy, hz), room.base_rgba, kind="surface")
    add_part(spec, base, "room_surface_base")


def apply_visuals(spec: mujoco.MjSpec, v: VisualParams, in_room: bool = False) -> None:
    """Colours, table texture, lights, camera jitter and distractors of `v` (see `scenes.visuals`)."""
    from humanoidgen.sim.cameras import CAMERAS

    table = spec.material("table_mat")
    table.rgba = list(v.table_rgba)
    if v.table_texture != "flat":
        builtin = {"checker": mujoco.mjtBuiltin.mjBUILTIN_CHECKER, "gradient": mujoco.mjtBuiltin.mjBUILTIN_GRADIENT,
                   "cross": mujoco.mjtBuiltin.mjBUILTIN_FLAT}[v.table_texture]
        mark = mujoco.mjtMark.mjMARK_CROSS if v.table_texture == "cross" else mujoco.mjtMark.mjMARK_NONE
        tex = spec.add_texture(name="table_tex", type=mujoco.mjtTexture.mjTEXTURE_2D, builtin=builtin, mark=mark,
                               rgb1=list(v.table_rgba[:3]), rgb2=list(v.table_rgb2), markrgb=list(v.table_rgb2),
                               width=128, height=128)
        table.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = tex.name
        table.texrepeat = [4, 4]
        table.rgba = [1, 1, 1, 1]  # the texture carries the colour
    tex = spec.texture("floor_tex")
    tex.rgb1, tex.rgb2 = list(v.floor_rgb[0]), list(v.floor_rgb[1])
    if in_room:
        spec.material("room_wall_mat").rgba = list(v.wall_rgba)
    key, fill = spec.light("key"), spec.light("fill")
    key.dir = list(v.key_dir)
    key.pos = (np.array([-0.3, 0.0, TABLE_TOP_Z]) - 2.2 * np.asarray(v.key_dir)).tolist()
    key.diffuse = [v.key_diffuse] * 3
    fill.diffuse = [v.fill_diffuse] * 3
    spec.visual.headlight.ambient = [v.ambient] * 3
    for cam in CAMERAS:
        j = v.cameras.get(cam.name)
        if j is None:
            continue
        eye, target = np.add(cam.eye, j.eye), np.add(cam.target, j.target)
        c = spec.camera(cam.name)
        c.pos = eye.tolist()
        c.quat = look_at_quat(eye, target, np.array(cam.up)).tolist()
        c.fovy = cam.fovy + j.fovy
    for i, part in enumerate(v.distractors):
        add_part(spec, part, f"distractor_{i}")


# A randomized scene, as evaluation (`TaskEnvConfig.randomize`) and training data (`hgen collect --room random
# --randomize-visuals`, the policy study's randomized data) draw it from the episode's seed: a room (background,
# clutter, the table's height) and a look (textures, lighting, camera jitter, distractors).
RANDOMIZED = {"room": "random", "randomize_visuals": True}


def episode_dressing(room: str | int | None, randomize_visuals: bool, seed: int | None) -> dict | None:
    """The dressing of episode `seed` as stored data: `room` is None (tabletop), a room seed or "random" (a room
    per episode, drawn from its seed); with `randomize_visuals` the look is drawn from the episode's seed."""
    from humanoidgen.scenes.room import room_seed_for

    room_seed = room_seed_for(room, seed)
    visual_seed = (0 if seed is None else seed) if randomize_visuals else None
    if room_seed is None and visual_seed is None:
        return None
    return SceneDressing.from_seeds(room_seed, visual_seed).to_dict()
