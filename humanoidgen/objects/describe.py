"""Scene descriptions for prompts: the objects' types, ids, poses, bounding boxes, openness and the names of
their annotations (the paper's ASSETS_ATTRIBUTES and ASSETS_STATUS), as compact JSON-ready data."""

from __future__ import annotations

import json

import mujoco
import numpy as np

from humanoidgen.objects.articulated import get_openness
from humanoidgen.sim.scene import SceneObject


def openness(model: mujoco.MjModel, data: mujoco.MjData, obj: SceneObject) -> float | None:
    """The object's openness in [0, 1] (None for objects without a moving part)."""
    ann = obj.annotations
    if ann is None or ann.articulation is None:
        return None
    return get_openness(model, data, obj.body, ann)


def _r(x: np.ndarray, nd: int = 3) -> list[float]:
    return [round(float(v), nd) for v in x]


def object_attributes(obj: SceneObject) -> dict:
    """What does not change while the task runs: type, model, bounding box, annotation names."""
    ann = obj.annotations
    out: dict = {"type": obj.type_name, "obj_id": obj.obj_id, "type_id": obj.type_id}
    if ann is not None:
        out |= {
            "description": ann.description,
            "bbox": {"min": _r(ann.bbox_min), "max": _r(ann.bbox_max)},
            "points": [p.name for p in ann.points],
            "axes": [a.name for a in ann.axes],
            "operations": sorted({f"{o.operation}@{o.point}" for o in ann.operations}),
            "functions": sorted({f"{f.function}@{f.point}" for f in ann.functions}),
        }
    return out


def object_status(model: mujoco.MjModel, data: mujoco.MjData, obj: SceneObject) -> dict:
    """Where the object is now: pose (p, q = w x y z) and openness."""
    bid = model.body(obj.body).id
    out = {"type": obj.type_name, "obj_id": obj.obj_id, "p": _r(data.xpos[bid]), "q": _r(data.xquat[bid])}
    if (o := openness(model, data, obj)) is not None:
        out["openness"] = round(o, 3)
    return out


def describe_scene(env, as_json: bool = True) -> str | dict:
    """{'attributes': [...], 'status': [...]} for every object of the scene."""
    scene = env.scene
    desc = {
        "attributes": [object_attributes(o) for o in scene.objects],
        "status": [object_status(env.model, env.data, o) for o in scene.objects],
    }
    return json.dumps(desc, separators=(",", ":")) if as_json else desc
