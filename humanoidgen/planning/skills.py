"""The planner API's actions as constraints: `generate` turns a verb on an object ("grasp", "pinch", "target",
"target1"/"target2", "push"/"flip"/"press", "pour", "move") into the constraints of its goal, from the object's
annotations and the task's targets. It dispatches to the skills below it (`constraint_gen` for grips,
`target_actions` for targets and pushes, `move_action` for moves) and never steps the simulation.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning import move_action, press_force, target_actions
from humanoidgen.planning.constraint_gen import (
    ACTIONS,
    PUSH_ACTIONS,
    PUSH_CONE_DEG,
    ConstraintGenerationError,
    Generated,
    grasp_or_pinch,
    ride_with_part,
)
from humanoidgen.planning.constraints import Const, Constraint
from humanoidgen.planning.push_spec import TaskTargets
from humanoidgen.planning.hand_ops import is_part
from humanoidgen.sim.layout import HAND_BASE_FRAME, Side

# Objects list pull@<point> (a drawer's handle) among their operations; a hand pulls by gripping: the grasp.
PULL_ACTIONS = ("pull",)


def generate(env, holding: dict, obj_name: str, obj_id: int, action: str, side: Side, openness: float | None = None,
             relative_obj_name: str | None = None, relative_obj_id: int | None = None,
             relative_p: np.ndarray | None = None, point: str | None = None, finger_offset: float = 0.0,
             force: float | None = None, targets: TaskTargets | None = None) -> Generated:
    """`targets`: the task's target poses and pushes (None: the task defines none); `force`: a press to that
    force (`press_force`)."""
    ta = target_actions
    if action not in ACTIONS + PUSH_ACTIONS + PULL_ACTIONS:
        raise ConstraintGenerationError(f"unknown action {action!r}; use one of "
                                        f"{', '.join(ACTIONS + PUSH_ACTIONS + PULL_ACTIONS)}")
    obj = env.scene.object(obj_name, obj_id)  # a clear error for an unknown object; aliases resolve here
    pulled = action in PULL_ACTIONS
    if pulled:
        # Authors ask for the pull the object lists by name. A hand pulls a part by gripping it: the part's grasp,
        # and with openness the held grip takes it along.
        if not (obj.annotations is not None and obj.annotations.operations_of("pull")):
            raise ConstraintGenerationError(f"{obj.type_name} has no 'pull' annotation; actions for it: "
                                            f"{', '.join(ta.actions_of(obj))}")
        action = "grasp"
    obj_name, obj_id = obj.type_name, obj.obj_id
    rel = None
    if relative_obj_name is not None:
        rel = env.scene.object(relative_obj_name, relative_obj_id or 0)
        relative_obj_name, relative_obj_id = rel.type_name, rel.obj_id
    if force is not None:
        return press_force.generate(env, side, obj, action, openness, force, _push)
    if action in ("grasp", "pinch"):
        operation, note = ta.operation_for(obj, action)
        gen = grasp_or_pinch(env, side, obj_name, obj_id, operation, openness, point, finger_offset, holding)
        if pulled:
            gen.notes.append(f"pull: the {side} hand's {operation} of {obj.type_name} {obj_id}"
                             + (f", moving the part to openness {openness:g}" if openness is not None else ""))
        if note is not None:
            if operation == "pinch":
                _close_as_pinch(gen)
            gen.notes.append(note)
        elif operation == "grasp" and point is None and openness is None and obj.annotations.operations_of("pinch"):
            # A whole-hand grasp does not fit a small, low object (a 5 cm cube: the straight fingers or the thumb
            # would go 3 cm into the table); its pinch is the planner's last resort (recoveries/pinch_instead.py).
            gen.fallback = grasp_or_pinch(env, side, obj_name, obj_id, "pinch", None, None, finger_offset, holding)
            _close_as_pinch(gen.fallback)
        return gen
    articulated = is_part(obj)
    if action in ta.TARGET_ACTIONS and not (articulated and action != "target"
                                            and not ta.has_task_target(targets, obj, action, side)):
        return ta.to_target(env, holding, targets, obj, action, side)
    if action in ("target1", "target2") + PUSH_ACTIONS:
        if not articulated:
            raise ConstraintGenerationError(f"{obj_name} has no push/flip/press annotation; actions for it: "
                                            f"{', '.join(ta.actions_of(obj))}")
        # The task's push (pre-push pose, then the staged push to its openness), where it defines one.
        if (gen := ta.task_push(env, holding, targets, obj, action, side, openness)) is not None:
            return gen
        k, note = ta.push_index(obj, action)
        k, openness, end_note = ta.press_end(obj, action, k, openness)
        gen = _push(env, side, obj_name, obj_id, k, openness)
        gen.notes += [end_note] if end_note else []
        gen.notes += [note] if note else []
        if action in ("target1", "target2"):
            gen.notes.append(ta.annotated_push_note(obj, action, k))
        return gen
    if action == "pour":
        return ta.pour(env, holding, obj, side, rel)
    return move_action.move(env, holding, obj_name, obj_id, side, rel, relative_p)


def _close_as_pinch(gen: Generated) -> None:
    """hand_grasp on these grips closes as a pinch."""
    for g in [gen, *gen.alternatives]:
        g.posture = g.posture or "pinch"


def _push(env, side: Side, obj_name: str, obj_id: int, k: int, openness: float | None) -> Generated:
    """The fingertip on the object's k-th push/flip/press point (target1: k = 0, target2: k = 1)."""
    obj = env.scene.object(obj_name, obj_id)
    ops = [o for o in obj.annotations.operations if o.operation in target_actions.PUSH_OPERATIONS]
    if len(ops) <= k:
        only = f" ({ops[0].operation} at {ops[0].point})" if len(ops) == 1 else ""
        raise ConstraintGenerationError(
            f"{obj_name} has {len(ops)} push/flip/press point(s){only}, so no target{k + 1}: use action='target1' "
            "(the fingertip on its point), then action='target1' with openness=... (0 to 1) to push the part to that "
            f"openness; actions for it: {', '.join(target_actions.actions_of(obj))}")
    frame = HAND_BASE_FRAME[side]
    op = ops[k]
    target = get_point_in_env(env, op.point, obj_name, obj_id, openness=openness)
    approach = get_axis_in_env(env, op.approach_axis, obj_type=obj_name, obj_id=obj_id, openness=openness)
    press_axis = get_axis_in_env(env, f"{side}_press_axis")
    # A fingertip pushes as well up to PUSH_CONE off the push direction; that freedom keeps far or turned
    # parts (a drawer front at the table's edge) within reach. Along the direction is preferred.
    gen = Generated([
        Constraint(env, "point2point", frame, hand_key_point=get_point_in_env(env, f"press_point_base_{side}_hand"),
                   object_key_point=target, name=f"fingertip on {obj_name} {op.point}"),
        Constraint(env, "angle", frame, hand_axis=press_axis, object_axis=approach, lower=0.0,
                   upper=np.radians(PUSH_CONE_DEG), name=f"fingertip within {PUSH_CONE_DEG} deg of the push direction"),
        Const(env, "parallel", frame, hand_axis=press_axis, object_axis=approach, weight=0.5,
              name="fingertip along the push direction (preferred)"),
    ], approach_axis=approach, approach_object=obj.body)
    ride_with_part(env, gen, obj_name, obj_id, op.point, openness)  # so the hand does not swing about
    return gen
