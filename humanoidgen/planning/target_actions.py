"""The paper's "target" actions and "pour", for an object the hand holds; and how an action an object lacks maps
to one it has. (Grasp, pinch, push and move constraints are in `constraint_gen`.)

- "target" / "target1" / "target2": the held object's centre to the pose the task defines for it under that name
  (`tasks/targets.py`), the hand keeping its orientation (a cost) and the object its tilt (within 10 deg). A task
  without that target for the object: "target" lifts the object 10 cm (and says so in the events); the others are
  an error that lists what the object has.
- "target1" / "target2" on an articulated object with a task push target: the pre-push pose and the staged push
  to the task's openness (`push_actions`). Without one: the fingertip on the object's first / second annotated
  push/flip/press point (`constraint_gen._push`), which the events say.
- "pour": the held cup tipped over a receptacle (the one named by relative_obj_name, else the nearest object with
  a "storage" annotation), its pour lip leading.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning import push_actions
from humanoidgen.planning import placing
from humanoidgen.planning.constraint_gen import LIFT, ConstraintGenerationError, Generated, keep_orientation
from humanoidgen.planning.constraints import Const, Constraint
from humanoidgen.planning.push_spec import TaskTargets
from humanoidgen.sim.layout import HAND_BASE_FRAME, OTHER_SIDE, Side
from humanoidgen.sim.scene import SceneObject

TARGET_ACTIONS = ("target", "target1", "target2")
PRESS_END = 1.0  # target2 on a one-point press without openness=: pressed all the way
PUSH_OPERATIONS = ("push", "flip", "press")  # what target1/target2 mean on articulated objects, in annotation order
# Pouring: the cup's centre this far beside the receptacle's centre (on the cup's side) and this far above its rim;
# tipped this much (the first that can be reached). At 130 deg cubes still stick to a cup wall (wood on ceramic
# holds up to about 40 deg of slope), so the steepest comes first.
POUR_TILTS_DEG = (160.0, 140.0, 120.0)
# A target not well above the held object (a place on the table, on another object) is come to from above, over
# the approach's last centimetres: straight across at table height, a pinched object drags on the table and slips.
FROM_ABOVE_BELOW_M = 0.05
SET_DOWN_HIGHER_M = (0.006, 0.012)  # a set-down target tried this much higher where it touches the support
DOWN = np.array([0.0, 0.0, -1.0])
POUR_SIDE_M = 0.06
POUR_ABOVE_RIM_M = 0.16
SAME_WAY_MIN = 0.02  # an openness asked this far from now says which way the part is to move
# An action the object lacks -> the operation that does the same job on it (a laptop screen's edge is pinched,
# not grasped; a drawer handle is grasped, not pinched).
SIMILAR_OPERATIONS = {"grasp": ("pinch",), "pinch": ("grasp",)}


def _label(obj: SceneObject) -> str:
    return f"{obj.type_name} {obj.obj_id}"


def has_task_target(targets: TaskTargets | None, obj: SceneObject, name: str, side: Side) -> bool:
    """A target pose for the held object (a push target is not one: the fingertip pushes the part)."""
    t = targets.find(obj.type_name, obj.obj_id, name, side) if targets is not None else None
    return t is not None and t.spec.push is None


def task_push(env, holding: dict, targets: TaskTargets | None, obj: SceneObject, action: str, side: Side,
              openness: float | None) -> Generated | None:
    """target1/target2 on an articulated object as the task defines its push, and push/flip with an openness
    that push serves (None where it defines none, or the request is not that push)."""
    push = targets.push(obj.type_name, obj.obj_id) if targets is not None else None
    if push is None:
        return None
    if action not in ("target1", "target2"):
        # action="push"/"flip" with openness at the point the task pushes, or the way the task's push moves the
        # part (shutting a screen pushed at its edge, not at its back): that push, staged as the task defines it
        # (a fingertip riding a lid along its arc in one stroke slips off its edge part way).
        if openness is None:
            return None
        at_point = any(o.operation == action and o.point == push.spec.push.point for o in obj.annotations.operations)
        now = push_actions.part_openness(env, obj)
        # (at the openness it is at now: the fingertip put on the part to push it the task's way next)
        same_way = abs(openness - now) <= SAME_WAY_MIN or (openness - now) * (push.spec.push.to - now) > 0
        if not (at_point or same_way):
            return None
    return push_actions.generate(env, holding, obj, side, action, push.spec.push, openness)


def annotated_push_note(obj: SceneObject, action: str, k: int) -> str:
    """Said where target1/target2 fall back to the object's annotated push points (the task defines no push)."""
    ops = [o for o in obj.annotations.operations if o.operation in PUSH_OPERATIONS]
    at = f"its {ops[k].operation!r} at {ops[k].point}" if k < len(ops) else f"push point {k + 1}"
    return (f"this task defines no push for {_label(obj)}: {action} is {at} (its annotated push points, in order); "
            "give openness= to push the part along")


def require_held(holding: dict, obj: SceneObject, side: Side, action: str) -> SceneObject:
    """The object, if the hand `side` holds it; otherwise an error that says what to do first."""
    held = holding.get(side)
    if held is obj or (held is not None and (held.type_name, held.obj_id) == (obj.type_name, obj.obj_id)):
        return held
    other = OTHER_SIDE[side]
    o = holding.get(other)
    if o is not None and (o.type_name, o.obj_id) == (obj.type_name, obj.obj_id):
        raise ConstraintGenerationError(f"{_label(obj)} is held by the {other} hand, not the {side}: use "
                                        f"hand_name={other!r} for action={action!r}")
    now = f"holds {_label(held)}" if held is not None else "holds nothing"
    raise ConstraintGenerationError(
        f"action={action!r} moves the object the hand holds, and the {side} hand {now}, not {_label(obj)}. Take it "
        f"first: generate_constraints(obj_name={obj.type_name!r}, obj_id={obj.obj_id}, action='pinch' (or 'grasp'), "
        f"hand_name={side!r}), move there, then hand_pinch/hand_grasp; then ask for {action!r}")


def to_target(env, holding: dict, targets: TaskTargets | None, obj: SceneObject, action: str, side: Side) -> Generated:
    """Constraints bringing the held object to its task target `action` (see the module docstring)."""
    art = obj.annotations.articulation if obj.annotations is not None else None
    target = targets.find(obj.type_name, obj.obj_id, action, side) if targets is not None else None
    defined = targets.names(obj.type_name, obj.obj_id, side) if targets is not None else []
    has = f"; its targets here: {', '.join(defined)}" if defined else ""
    if target is None and art is not None:
        raise ConstraintGenerationError(
            f"{_label(obj)} has no {action!r} pose in this task{has}; to move its part, use action='grasp' (or "
            "'pinch') with openness=..., or 'target1'/'target2' to push it")
    require_held(holding, obj, side, action)
    frame = HAND_BASE_FRAME[side]
    centre = get_point_in_env(env, "center", obj.type_name, obj.obj_id)
    up = getattr(target.spec, "up", None) if target is not None and art is None else None  # the target turns it
    if target is not None and art is None and up is None:  # a tilted object is stood back up to be set down
        up = next(iter(placing.stand_up_directions(env, side, obj, None) or []), None)
    keep = keep_orientation(env, side, None if art is not None else (obj.type_name, obj.obj_id), up)
    if target is not None:
        goal = target.position(env)
        def at(g: np.ndarray, label: str) -> Generated:
            return Generated([Constraint(env, "point2point", frame, hand_key_point=centre, object_key_point=g,
                                         name=f"{_label(obj)} at its {action}: {label}"), *keep])

        gen = at(goal, target.spec.label())
        if goal[2] <= centre[2] + FROM_ABOVE_BELOW_M:
            gen.approach_axis = DOWN  # and open_hand backs the hand out upward, clear of what it set down
            # An object held turned in the fingers (the G1's slanted pinch) reaches lower than its centre says and
            # touches what it is set on at the goal (block_stack_single, 3 of 10 G1 seeds, 0.3-5.6 mm deep): the
            # same set-down a little higher is tried next, and the object drops that far when let go.
            for dz in SET_DOWN_HIGHER_M:
                higher = at(goal + np.array([0.0, 0.0, dz]), f"{target.spec.label()}, {dz * 1000:.0f} mm higher")
                higher.approach_axis = DOWN
                higher.notes.append(f"{_label(obj)} set down {dz * 1000:.0f} mm higher than its {action}: at the "
                                    "target it touched what it is set on")
                gen.alternatives.append(higher)
        return gen
    if action != "target":
        raise ConstraintGenerationError(
            f"{_label(obj)} has no {action!r} pose in this task{has}; use action='move' with relative_obj_name, "
            "relative_obj_id and relative_p (world offset from that object's centre)")
    gen = Generated([Constraint(env, "point2point", frame, hand_key_point=centre, object_key_point=centre + LIFT,
                                name=f"{_label(obj)} 10 cm higher (no target in this task)"), *keep])
    gen.notes.append(f"{_label(obj)} has no 'target' pose in this task{has}: 'target' lifted it 10 cm instead; to "
                     "put it somewhere, use action='move' with relative_obj_name/relative_obj_id/relative_p")
    return gen


def _receptacle(env, obj: SceneObject) -> SceneObject:
    """The nearest other object that can hold what is poured (it has a "storage" annotation)."""
    here = get_point_in_env(env, "center", obj.type_name, obj.obj_id)
    cands = [o for o in env.scene.objects if o is not obj and o.annotations is not None
             and any(f.function == "storage" for f in o.annotations.functions)]
    if not cands:
        raise ConstraintGenerationError("there is nothing to pour into (no object with a 'storage' annotation); "
                                        "name one with relative_obj_name/relative_obj_id")
    dist = [np.linalg.norm((get_point_in_env(env, "center", o.type_name, o.obj_id) - here)[:2]) for o in cands]
    return cands[int(np.argmin(dist))]


def pour(env, holding: dict, obj: SceneObject, side: Side, receptacle: SceneObject | None) -> Generated:
    """The held object beside and above the receptacle, tipped toward it; the steepest reachable tilt first."""
    require_held(holding, obj, side, "pour")
    ann = obj.annotations
    functions = {f.function: f for f in (ann.functions if ann is not None else [])}
    if "pour" not in functions and "storage" not in functions:
        can = sorted({o.type_name for o in env.scene.objects if o.annotations is not None
                      and any(f.function in ("pour", "storage") for f in o.annotations.functions)})
        raise ConstraintGenerationError(f"{obj.type_name} cannot pour (no 'pour' annotation); objects here that can: "
                                        f"{', '.join(can) or 'none'}")
    into = receptacle if receptacle is not None else _receptacle(env, obj)
    if into is obj:
        raise ConstraintGenerationError(f"{_label(obj)} cannot pour into itself; name the receptacle with "
                                        "relative_obj_name/relative_obj_id")
    frame = HAND_BASE_FRAME[side]
    rc = get_point_in_env(env, "center", into.type_name, into.obj_id)
    rim_z = rc[2] + (into.annotations.bbox_max[2] if into.annotations is not None else 0.0)
    here = get_point_in_env(env, "center", obj.type_name, obj.obj_id)
    away = np.array([*(here - rc)[:2], 0.0])
    # Beside the receptacle on the side the cup comes from (straight above it: from the robot's side).
    away = away / np.linalg.norm(away) if np.linalg.norm(away) > 1e-3 else np.array([-1.0, 0.0, 0.0])
    toward, up = -away, np.array([0.0, 0.0, 1.0])
    goal = rc + POUR_SIDE_M * away
    goal[2] = rim_z + POUR_ABOVE_RIM_M
    body_up = get_axis_in_env(env, "z", obj_type=obj.type_name, obj_id=obj.obj_id)
    lip = functions.get("pour")
    lip_axis = get_axis_in_env(env, lip.axis, obj_type=obj.type_name, obj_id=obj.obj_id) if lip else None
    ways = []
    for tilt in POUR_TILTS_DEG:
        th = np.radians(tilt)
        cons = [Constraint(env, "point2point", frame, hand_key_point=here, object_key_point=goal,
                           name=f"{_label(obj)} beside and above {_label(into)}"),
                Constraint(env, "parallel", frame, hand_axis=body_up, object_axis=np.cos(th) * up + np.sin(th) * toward,
                           name=f"{_label(obj)} tipped {tilt:.0f} deg toward {_label(into)}")]
        if lip_axis is not None:
            # Tipping turns a lip that faces the receptacle down and over it: prefer the grip that does so (a cost,
            # since the hand's grip fixes how the cup turns).
            cons.append(Const(env, "parallel", frame, hand_axis=lip_axis, object_axis=np.cos(th) * toward - np.sin(th) * up,
                              weight=0.3, name=f"pour lip ({lip.point}) toward {_label(into)} (preferred)"))
        ways.append(Generated(cons))
    ways[0].alternatives = ways[1:]
    ways[0].notes.append(f"pour: {_label(obj)} tipped toward {_label(into)}")
    return ways[0]


def operation_for(obj: SceneObject, operation: str) -> tuple[str, str | None]:
    """The operation to use for a grasp/pinch request, and a note when it had to be mapped to another one."""
    ann = obj.annotations
    if ann is None:
        raise ConstraintGenerationError(f"{_label(obj)} has no annotations; only action='move' applies to it")
    if ann.operations_of(operation):
        return operation, None
    has = sorted({o.operation for o in ann.operations})
    for other in SIMILAR_OPERATIONS.get(operation, ()):
        if ann.operations_of(other):
            points = ", ".join(sorted({o.point for o in ann.operations_of(other)}))
            return other, (f"{obj.type_name} has no {operation!r} annotation: used its {other!r} at {points} instead "
                           f"(it has: {', '.join(has)})")
    raise ConstraintGenerationError(f"{obj.type_name} has no {operation!r} annotation; it supports: "
                                    f"{', '.join(has) or 'nothing'} (as actions: {', '.join(actions_of(obj))})")


def actions_of(obj: SceneObject) -> list[str]:
    """The generate_constraints actions that make sense for the object, for error messages."""
    ann = obj.annotations
    ops = {o.operation for o in ann.operations} if ann is not None else set()
    out = [a for a in ("grasp", "pinch") if a in ops]
    pushes = [o for o in (ann.operations if ann is not None else []) if o.operation in PUSH_OPERATIONS]
    out += [f"target{k + 1} ({o.operation} at {o.point})" for k, o in enumerate(pushes[:2])]
    if len(pushes) == 1 and pushes[0].operation == "press":
        out.append(f"target2 (the press at {pushes[0].point} to its end)")
    return out + ["target (once held)", "move"]


def press_end(obj: SceneObject, action: str, k: int, openness: float | None) -> tuple[int, float | None, str | None]:
    """target2 on an object whose one push-like operation is a press (a toaster's lever): the press's end, the
    fingertip on the press point pressing the part to `openness` (default 1, all the way). Returns (index,
    openness, note); other actions and objects unchanged."""
    ops = [o for o in obj.annotations.operations if o.operation in PUSH_OPERATIONS] if obj.annotations else []
    if action != "target2" or k != 1 or len(ops) != 1 or ops[0].operation != "press":
        return k, openness, None
    to = PRESS_END if openness is None else openness
    return 0, to, (f"{_label(obj)} has one press point ({ops[0].point}): target2 is the press's end, the fingertip "
                   f"pressing it to openness {to:g}" + (" (all the way; give openness= for less)" if openness is None
                                                       else ""))


def push_index(obj: SceneObject, action: str) -> tuple[int, str | None]:
    """target1/target2 -> index 0/1 of the object's push/flip/press annotations; "push"/"flip"/"press" (not paper
    actions, but plans use them) -> the first annotation of that kind, else the first push-like one (noted)."""
    if action in ("target1", "target2"):
        return (0 if action == "target1" else 1), None
    ops = [o for o in obj.annotations.operations if o.operation in PUSH_OPERATIONS] if obj.annotations else []
    for k, o in enumerate(ops):
        if o.operation == action:
            return k, None
    if not ops:
        raise ConstraintGenerationError(f"{obj.type_name} has no push/flip/press annotation; actions for it: "
                                        f"{', '.join(actions_of(obj))}")
    return 0, f"{obj.type_name} has no {action!r} annotation: used its {ops[0].operation!r} at {ops[0].point} (target1)"
