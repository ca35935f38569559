"""What the hands' contacts say: is an object held (opposing contacts), and where did a released object end.
Pure queries on the simulation state; the planner drives the fingers."""

from __future__ import annotations

import mujoco
import numpy as np

from humanoidgen.sim.layout import HAND_PREFIX, WRIST_BODY, Side
from humanoidgen.sim.scene import Scene, SceneObject


def is_part(obj) -> bool:
    """Whether `obj` (a SceneObject, or None) is an articulated object's part a hand moves, not a rigid body."""
    return obj is not None and obj.annotations is not None and obj.annotations.articulation is not None


def _root(model: mujoco.MjModel, geom: int) -> int:
    return int(model.body_rootid[model.geom_bodyid[geom]])


def hand_part(model: mujoco.MjModel, body: int, side: Side) -> str | None:
    """Which part of `side`'s hand the body is: a finger (thumb, index, ...), "palm", or None (not the hand)."""
    name = model.body(body).name
    prefix = HAND_PREFIX[side] + "_"
    if name.startswith(prefix):
        return name[len(prefix):].split("_")[0]
    return "palm" if name == WRIST_BODY[side] else None


def finger_contacts(model: mujoco.MjModel, data: mujoco.MjData, side: Side, body: str) -> set[str]:
    """Which fingers of `side` touch the object `body`: a subset of thumb, index, middle, ring, pinky, palm."""
    root = model.body(body).id
    touched: set[str] = set()
    for c in data.contact[: data.ncon]:
        for mine, other in ((c.geom1, c.geom2), (c.geom2, c.geom1)):
            if _root(model, other) != root:
                continue
            if (part := hand_part(model, model.geom_bodyid[mine], side)) is not None:
                touched.add(part)
    return touched


def hand_touches(scene: Scene, model: mujoco.MjModel, data: mujoco.MjData, side: Side) -> dict[str, set[str]]:
    """What `side`'s hand touches now: {"cube 1": {"index", "thumb"}, "the table": {"palm"}, ...}."""
    names = {model.body(o.body).id: f"{o.type_name} {o.obj_id}" for o in scene.objects}
    table = model.body("table").id if "table" in [model.body(b).name for b in range(model.nbody)] else -1
    out: dict[str, set[str]] = {}
    for c in data.contact[: data.ncon]:
        for mine, other in ((c.geom1, c.geom2), (c.geom2, c.geom1)):
            part = hand_part(model, model.geom_bodyid[mine], side)
            if part is None:
                continue
            root = _root(model, other)
            label = names.get(root) or ("the table" if model.geom_bodyid[other] == table else None)
            if label is not None:
                out.setdefault(label, set()).add(part)
    return out


def is_held(touched: set[str]) -> bool:
    """Held means squeezed from two sides: the thumb against a finger (or the palm)."""
    return "thumb" in touched and bool(touched & {"index", "middle", "ring", "pinky", "palm"})


def is_pinched(touched: set[str]) -> bool:
    """A pinch proper: the thumb against the index. Thumb and middle alone hold an object at the middle's tip,
    past the index's pad, by one edge: measured after a mid-air hand-over (handover_and_storage_cooperation,
    alt_folder seed 1), such a grip held while still but the block tilted 25 deg in 0.4 s on the carry and fell."""
    return "thumb" in touched and "index" in touched


def resting_on(scene: Scene, model: mujoco.MjModel, data: mujoco.MjData, obj: SceneObject) -> list[str]:
    """What supports the object from below its centre: "table" and other objects ("cube 0"); hands don't count."""
    root = model.body(obj.body).id
    centre = data.xpos[root]
    names: dict[int, str] = {model.body(o.body).id: f"{o.type_name} {o.obj_id}" for o in scene.objects}
    out: list[str] = []
    for c in data.contact[: data.ncon]:
        r1, r2 = _root(model, c.geom1), _root(model, c.geom2)
        if root not in (r1, r2) or c.pos[2] > centre[2]:
            continue
        other = r2 if r1 == root else r1
        if other == 0:
            label = "table"
        elif other in names:
            label = names[other]
        else:
            continue  # the robot
        if label not in out:
            out.append(label)
    return out


def contents(scene: Scene, model: mujoco.MjModel, data: mujoco.MjData, obj: SceneObject) -> list[SceneObject]:
    """The objects resting in or on `obj`, directly or on one another (cubes in a cup): they travel with it."""
    inside: list[SceneObject] = []
    labels = {f"{obj.type_name} {obj.obj_id}"}
    grew = True
    while grew:
        grew = False
        for o in scene.objects:
            if o is obj or o in inside:
                continue
            if labels & set(resting_on(scene, model, data, o)):
                inside.append(o)
                labels.add(f"{o.type_name} {o.obj_id}")
                grew = True
    return inside


def body_speed(model: mujoco.MjModel, data: mujoco.MjData, body: str) -> float:
    vel = np.zeros(6)
    mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_BODY, model.body(body).id, vel, 0)
    return float(np.linalg.norm(vel[3:]))
