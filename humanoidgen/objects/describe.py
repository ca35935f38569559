"""Scene descriptions for prompts: the objects' types, ids, poses, bounding boxes, openness and the names of
their annotations (the paper's ASSETS_ATTRIBUTES and ASSETS_STATUS), as compact JSON-ready data. In a task's
scene, also each object's aliases and its target poses (what action="target" / "target1" / "target2" goes to):
their definitions among the attributes, where they are now in the status."""

from __future__ import annotations

import json

import mujoco
import numpy as np

from humanoidgen.objects.articulated import get_openness
from humanoidgen.sim.scene import SceneObject


def openness(model: mujoco.MjModel, data: mujoco.MjData, obj: SceneObject, part: str | None = None) -> float | None:
    """The object's openness in [0, 1] (None for objects without a moving part); with `part`, the openness of the
    joint that moves that part (its own where it has one: a safe's knob)."""
    ann = obj.annotations
    if ann is None or ann.articulation is None:
        return None
    if part is None:
        return get_openness(model, data, obj.body, ann)
    art = ann.articulation_for(part)
    return art.openness_of(float(data.qpos[model.jnt_qposadr[model.joint(f"{obj.body}_{art.joint}").id]]))


def _r(x: np.ndarray, nd: int = 3) -> list[float]:
    return [round(float(v), nd) for v in x]


def _aliases(scene, obj: SceneObject) -> list[str]:
    return sorted(a for a, ref in (getattr(scene, "aliases", None) or {}).items() if ref == (obj.type_name, obj.obj_id))


def _targets(scene, obj: SceneObject) -> list:
    targets = getattr(scene, "targets", None)  # tasks.targets.SceneTargets in a task's scene
    return [] if targets is None else targets.of(obj.type_name, obj.obj_id)


def _target_key(t) -> str:
    # "target" for both hands; "target (right hand)" where a hand-over gives each hand its own; a push target
    # (an articulated part) is both target1 and target2, where the push starts now.
    if t.spec.push is not None:
        return f"target1/target2 (push at {t.spec.push.point})"
    return t.spec.name + (f" ({t.spec.hand} hand)" if t.spec.hand else "")


def object_attributes(obj: SceneObject, scene=None) -> dict:
    """What does not change while the task runs: type, model, bounding box, annotation names; with the scene,
    aliases and target definitions."""
    ann = obj.annotations
    out: dict = {"type": obj.type_name, "obj_id": obj.obj_id, "type_id": obj.type_id}
    if scene is not None and (aliases := _aliases(scene, obj)):
        out["aliases"] = aliases
    if ann is not None:
        out |= {
            "description": ann.description,
            "bbox": {"min": _r(ann.bbox_min), "max": _r(ann.bbox_max)},
            "points": [p.name for p in ann.points],
            "axes": [a.name for a in ann.axes],
            "operations": sorted({f"{o.operation}@{o.point}" for o in ann.operations}),
            "functions": sorted({f"{f.function}@{f.point}" for f in ann.functions}),
        }
    if scene is not None and (targets := _targets(scene, obj)):
        out["targets"] = {name + (f" ({t.spec.hand} hand)" if t.spec.hand else ""): label
                          for t in targets for name, label in t.spec.labels().items()}
    return out


def object_status(model: mujoco.MjModel, data: mujoco.MjData, obj: SceneObject, env=None) -> dict:
    """Where the object is now: pose (p, q = w x y z) and openness; with `env`, where its targets are now (a
    target relative to another object moves with it)."""
    bid = model.body(obj.body).id
    out = {"type": obj.type_name, "obj_id": obj.obj_id, "p": _r(data.xpos[bid]), "q": _r(data.xquat[bid])}
    if (o := openness(model, data, obj)) is not None:
        out["openness"] = round(o, 3)
        for art in obj.annotations.part_articulations:  # a part with a joint of its own: "knob openness"
            out[f"{art.part} openness"] = round(openness(model, data, obj, art.part), 3)
    if env is not None and (targets := _targets(env.scene, obj)):
        out["targets"] = {_target_key(t): _r(t.position(env)) for t in targets}
    return out


def describe_scene(env, as_json: bool = True) -> str | dict:
    """{'attributes': [...], 'status': [...]} for every object of the scene."""
    scene = env.scene
    desc = {
        "attributes": [object_attributes(o, scene) for o in scene.objects],
        "status": [object_status(env.model, env.data, o, env) for o in scene.objects],
    }
    return json.dumps(desc, separators=(",", ":")) if as_json else desc
