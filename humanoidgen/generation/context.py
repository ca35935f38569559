"""Live facts for the prompts, generated from the code and data themselves so the prompts cannot drift:
the planner API reference (signatures + docstrings), the asset library with its annotations, the robot/table
layout and the hands' operable ranges, and the success predicates."""

from __future__ import annotations

import inspect
import json
import typing
from pathlib import Path

from humanoidgen.sim import layout

# Public planner methods that plan code should call, in the order a plan tends to use them.
PLANNER_METHODS = (
    "hand_pre_grasp", "hand_pre_pinch", "hand_press", "hand_grasp", "hand_pinch", "open_hand",
    "generate_constraints", "generate_end_effector_pose", "move_to_pose_with_screw",
    "ignore_collision", "restore_collision",
)
PLANNER_ATTRIBUTES = {
    "planner.env": "the simulation (pass it to Constraint, get_point_in_env, get_axis_in_env)",
    "planner.left_hand_init_pose": "the left hand's initial pose (a Pose); move there to take the hand back",
    "planner.right_hand_init_pose": "the right hand's initial pose (a Pose)",
}


def _doc(obj: object) -> str:
    doc = inspect.getdoc(obj) or ""
    return "\n".join("    " + line if line else "" for line in doc.splitlines())


def _signature(fn: typing.Callable, drop_self: bool = True) -> str:
    sig = inspect.signature(fn)
    params = [p for p in sig.parameters.values() if not (drop_self and p.name == "self")]
    return f"({', '.join(_param(p) for p in params)})"


def _param(p: inspect.Parameter) -> str:
    # Annotations are strings here (postponed evaluation); show them bare: `hand_name: str = 'all'`.
    text = p.name
    if p.annotation is not inspect.Parameter.empty:
        ann = p.annotation if isinstance(p.annotation, str) else inspect.formatannotation(p.annotation)
        text += f": {ann.replace('np.ndarray', 'array')}"
    if p.default is not inspect.Parameter.empty:
        text += f" = {p.default!r}" if p.annotation is not inspect.Parameter.empty else f"={p.default!r}"
    return text


def api_reference() -> str:
    """The planner API as the prompt shows it, from the current signatures and docstrings."""
    from humanoidgen.objects.hands import HAND_AXIS_NAMES, HAND_POINT_NAMES
    from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
    from humanoidgen.planning import constraint_gen, constraints
    from humanoidgen.planning.planner import HumanoidMotionPlanner

    out = ["### planner methods (call as `planner.<name>(...)`)"]
    for name in PLANNER_METHODS:
        fn = getattr(HumanoidMotionPlanner, name)
        out.append(f"planner.{name}{_signature(inspect.unwrap(fn))}\n{_doc(fn)}")
    out.append("### `action` values of generate_constraints\n" + _doc(constraint_gen))
    out.append("### planner attributes\n" + "\n".join(f"{k}: {v}" for k, v in PLANNER_ATTRIBUTES.items()))
    out.append("### custom constraints (for what the actions above do not cover)\n"
               f"Constraint{_signature(constraints.Constraint, drop_self=False)}\n"
               f"Const{_signature(constraints.Const, drop_self=False)}\n{_doc(constraints.Const)}\n"
               f"{_doc(constraints)}\n    `end_effector_frame`: {layout.HAND_BASE_FRAME['left']!r} (left) or "
               f"{layout.HAND_BASE_FRAME['right']!r} (right).")
    for fn in (get_point_in_env, get_axis_in_env):
        out.append(f"{fn.__name__}{_signature(fn)}\n{_doc(fn)}")
    out.append(f"Hand points: {', '.join(HAND_POINT_NAMES)}\nHand axes: {', '.join(HAND_AXIS_NAMES)}")
    out.append("A planner call that cannot do its job raises an error naming the call and the reason; the "
               "program stops at that step.")
    return "\n\n".join(out)


def layout_text() -> str:
    """Robot pose, table extent, frames and the hands' operable ranges (from sim/layout.py)."""
    L, R = layout.OPERABLE_RANGE["left"], layout.OPERABLE_RANGE["right"]
    return "\n".join([
        "- World frame: +x points forward from the robot, +y to its left, +z up; metres and radians.",
        f"- The robot stands at {layout.ROBOT_BASE_POS.tolist()} facing +x.",
        f"- Table top: z = {layout.TABLE_TOP_Z}, x from {layout.TABLE_X[0]} to {layout.TABLE_X[1]}, "
        f"y from {layout.TABLE_Y[0]} to {layout.TABLE_Y[1]}.",
        f"- Left hand operable range: x in [{L.x[0]}, {L.x[1]}], y in [{L.y[0]}, {L.y[1]}].",
        f"- Right hand operable range: x in [{R.x[0]}, {R.x[1]}], y in [{R.y[0]}, {R.y[1]}].",
        "- Being inside a range is necessary, not sufficient: a hand may still fail because of the object's "
        "orientation, collisions or the hand's shape.",
    ])


def assets_text() -> str:
    """Every family and model with its size and annotation names (points, axes, operations, functions)."""
    from humanoidgen.objects import library

    lines = []
    for name, fam in sorted(library.families().items()):
        kind = ("articulated, fixed to the table, has openness" if fam.articulated
                else "static, fixed to the table: an obstacle to keep clear of" if getattr(fam, "static", False)
                else "rigid, free")
        lines.append(f"- {name} ({kind}):")
        for m in fam.models():
            ann = library.annotations(name, m.type_id)
            size = [round(b - a, 3) for a, b in zip(ann.bbox_min, ann.bbox_max)]
            ops = sorted({f"{o.operation}@{o.point}" for o in ann.operations})
            fns = sorted({f"{f.function}@{f.point}" for f in ann.functions})
            lines.append(f"  - type_id {m.type_id}: {m.description}; size {size}; points "
                         f"{[p.name for p in ann.points]}; axes {[a.name for a in ann.axes]}; operations {ops}"
                         + (f"; functions {fns}" if fns else ""))
    return "\n".join(lines)


def predicates_text() -> str:
    """One line per success predicate: its `type`, fields with defaults, and docstring."""
    from humanoidgen.tasks.predicates import Predicate

    union = typing.get_args(Predicate)[0]
    lines = []
    for cls in typing.get_args(union):
        fields = [f"{k}" + ("" if f.is_required() else f"={f.default!r}")
                  for k, f in cls.model_fields.items() if k != "type"]
        doc = " ".join((cls.__doc__ or "").split())
        lines.append(f"  - `{cls.model_fields['type'].default}` ({', '.join(fields)})" + (f": {doc}" if doc else ""))
    lines.append('  Objects are referenced as "cube[0]" (type[obj_id]).')
    return "\n".join(lines)


def example_spec_yaml(name: str = "block_stack_single") -> str:
    from humanoidgen.tasks.registry import SPECS_DIR

    return (SPECS_DIR / f"{name}.yaml").read_text().strip()


def example_plan(name: str = "block_stack_single") -> tuple[str, str]:
    """(task description, the reference plan rendered as one fenced block per step)."""
    from humanoidgen.episodes.plans import load_plan
    from humanoidgen.tasks.registry import SPECS_DIR, load_task

    spec = load_task(name)
    plan = load_plan(Path(SPECS_DIR / f"{name}.py"))
    blocks = [f"```python\n# step: {s.title}\n{s.code.strip()}\n```" for s in plan.steps]
    return spec.description, "\n".join(blocks)


def hands_text(hands: dict) -> str:
    return "\n".join(f"- {side}: p={v['p']}, q={v['q']}" for side, v in hands.items())


def compact_json(items: list) -> str:
    return "\n".join(json.dumps(x, separators=(", ", ": ")) for x in items)
