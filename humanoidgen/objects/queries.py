"""World-frame key points and axes of objects and hands, as the planner API asks for them.

`env` is anything with `model`, `data` and `scene` (a HumanoidEnv). Objects are addressed by type and
`obj_id` (the order they were added); hand annotations by their names (`grasp_point_base_right_hand`, ...).
"""

from __future__ import annotations

import mujoco
import numpy as np

from humanoidgen.objects.describe import openness
from humanoidgen.objects.hands import HAND_AXIS_NAMES, HAND_POINT_NAMES, hand_axes, hand_points, side_of
from humanoidgen.objects.schema import ObjectAnnotations
from humanoidgen.sim.layout import WRIST_BODY
from humanoidgen.sim.scene import SceneObject

LOCAL_AXES = {"x": np.array([1.0, 0.0, 0.0]), "y": np.array([0.0, 1.0, 0.0]), "z": np.array([0.0, 0.0, 1.0])}


def _frame(model: mujoco.MjModel, data: mujoco.MjData, body: str) -> tuple[np.ndarray, np.ndarray]:
    bid = model.body(body).id
    return data.xpos[bid].copy(), data.xmat[bid].reshape(3, 3).copy()


def _data_at_openness(env, obj: SceneObject, openness: float | None, part: str | None = None) -> mujoco.MjData:
    """The current state, or a copy with the joint that moves `part` (the object's main one, unless that part
    has a joint of its own: a safe's knob) at `openness` (where its parts will be)."""
    if openness is None:
        return env.data
    ann = obj.annotations
    if ann is None or ann.articulation is None:
        raise ValueError(f"{obj.type_name}[{obj.obj_id}] has no moving part; openness does not apply")
    if not 0.0 <= openness <= 1.0:
        raise ValueError(f"openness must be in [0, 1], got {openness}")
    d = mujoco.MjData(env.model)
    d.qpos[:], d.qvel[:] = env.data.qpos, 0.0
    art = ann.articulation_for(part)
    joint = env.model.joint(f"{obj.body}_{art.joint}")
    d.qpos[env.model.jnt_qposadr[joint.id]] = art.joint_position(openness)
    mujoco.mj_kinematics(env.model, d)
    return d


def _object(env, type_name: str, obj_id: int) -> tuple[SceneObject, ObjectAnnotations | None]:
    obj = env.scene.object(type_name, obj_id)
    return obj, obj.annotations


def wrist_point_in_env(env, side: str, local: np.ndarray) -> np.ndarray:
    """World position of a point given in a hand's wrist frame, at the hand's pose now."""
    pos, R = _frame(env.model, env.data, WRIST_BODY[side])
    return pos + R @ np.asarray(local, float)


def get_openness_in_env(env, type_name: str, obj_id: int = 0, part: str | None = None) -> float:
    """How open object `type_name[obj_id]`'s moving part is now: 0 (closed) to 1 (open), as `openness=` counts
    it everywhere. `part`: another moving part by name, for an object with two (a safe's "knob")."""
    obj, ann = _object(env, type_name, obj_id)
    if ann is None or ann.articulation is None:
        raise KeyError(f"{type_name}[{obj_id}] has no moving part, so no openness")
    parts = sorted({k.part for k in ann.points if k.part} | {a.part for a in ann.part_articulations if a.part})
    if part is not None and part not in parts:
        raise KeyError(f"{type_name}[{obj_id}] has no part {part!r}; its parts: {', '.join(parts) or 'none named'}")
    return float(np.clip(openness(env.model, env.data, obj, part), 0.0, 1.0))


# Object point names the paper's plans use, for ours.
PAPER_POINT_NAMES = {"articulated_object_head": "head"}


def get_point_in_env(env, point_name: str = "center", type_name: str | None = None, obj_id: int = 0,
                     related_point: np.ndarray | None = None, openness: float | None = None) -> np.ndarray:
    """World position of a key point.

    - a hand point (`grasp_point_base_left_hand`, `pinch_point_base_right_hand`, ...), at the hand's pose now;
    - `"center"` or a named annotation of object `type_name[obj_id]`; for a point on a moving part,
      `openness` gives where it will be with the part at that openness;
    - `related_point` (metres) is an offset in the object's own frame (for hand points: the world frame):
      "10 cm along the cube's z axis" is `get_point_in_env(env, "center", "cube", 0, related_point=[0, 0, 0.1])`.
    """
    offset = np.zeros(3) if related_point is None else np.asarray(related_point, float)
    point_name = PAPER_POINT_NAMES.get(point_name, point_name)
    if point_name in HAND_POINT_NAMES:
        side = side_of(point_name)
        p = wrist_point_in_env(env, side, hand_points(side)[point_name]) + offset
    else:
        if type_name is None:
            raise KeyError(
                f"{point_name!r} is not a hand point; give type_name for an object point. "
                f"Hand points: {', '.join(HAND_POINT_NAMES)}"
            )
        obj, ann = _object(env, type_name, obj_id)
        kp = None
        if point_name != "center":
            if ann is None:
                raise KeyError(f"{type_name}[{obj_id}] has no annotations; only 'center' applies")
            kp = ann.point(point_name)
        d = _data_at_openness(env, obj, openness, kp.part if kp is not None else None)
        root_pos, root_R = _frame(env.model, d, obj.body)
        if kp is None:
            p = root_pos + root_R @ offset
        else:
            pos, R = _frame(env.model, d, f"{obj.body}_{kp.part}" if kp.part else obj.body)
            p = pos + R @ np.asarray(kp.position) + root_R @ offset
    return p


def get_axis_in_env(env, axis_name: str, obj_type: str | None = None, obj_id: int = 0,
                    openness: float | None = None) -> np.ndarray:
    """World direction (unit) of an axis: a hand axis, an object's local `"x"`/`"y"`/`"z"`, or a named one."""
    if axis_name in HAND_AXIS_NAMES:
        side = side_of(axis_name)
        _, R = _frame(env.model, env.data, WRIST_BODY[side])
        return R @ hand_axes(side)[axis_name]
    if obj_type is None:
        raise KeyError(
            f"{axis_name!r} is not a hand axis; give obj_type for an object axis. Hand axes: {', '.join(HAND_AXIS_NAMES)}"
        )
    obj, ann = _object(env, obj_type, obj_id)
    if axis_name in LOCAL_AXES:
        return _frame(env.model, _data_at_openness(env, obj, openness), obj.body)[1] @ LOCAL_AXES[axis_name]
    if ann is None:
        raise KeyError(f"{obj_type}[{obj_id}] has no annotations; only 'x', 'y', 'z' apply")
    ax = ann.axis(axis_name)
    d = _data_at_openness(env, obj, openness, ax.part)
    _, R = _frame(env.model, d, f"{obj.body}_{ax.part}" if ax.part else obj.body)
    return R @ np.asarray(ax.direction)


def storage_region(env, obj: SceneObject) -> tuple[np.ndarray, np.ndarray, np.ndarray, float] | None:
    """A container's storage region (what the `inside` check and a drop into it read): its "storage" point in the
    world, the container's rotation, the region's lateral half sizes (its bounding box's) and the world height of
    its top; None for an object without a storage function."""
    ann = obj.annotations
    store = next((f.point for f in (ann.functions if ann else []) if f.function == "storage"), None)
    if store is None:
        return None
    s = get_point_in_env(env, store, obj.type_name, obj.obj_id)
    bid = env.model.body(obj.body).id
    root, R = env.data.xpos[bid].copy(), env.data.xmat[bid].reshape(3, 3).copy()
    lo, hi = np.asarray(ann.bbox_min), np.asarray(ann.bbox_max)
    top = float((root + R @ np.array([0.0, 0.0, hi[2]]))[2])
    return s, R, (hi[:2] - lo[:2]) / 2, top
