"""Live facts for the prompts, generated from the code and data themselves so the prompts cannot drift:
the planner API reference (api_reference.py), the asset library with its annotations and what they mean
(object_text.py), the robot/table
layout and the hands' operable ranges, and the success predicates."""

from __future__ import annotations

import json
import typing
from pathlib import Path

from humanoidgen.sim import layout

def api_reference() -> str:
    """The planner API as the prompts show it (generated from the public API: `api_reference.reference`)."""
    from humanoidgen.generation.api_reference import reference

    return reference()


# What each field of a task's push target means (`targets: [{object: ..., push: {...}}]`), for the scene prompt;
# tests/test_api_reference.py fails when these and the push target's fields disagree.
PUSH_FIELDS = {
    "point": "a point on the moving part where the fingertip pushes (one of the object's points)",
    "to": "the openness the push brings the part to (0 to 1)",
    "face": "`inner` lifts the part from under it (its inner face), `outer` presses its outer face",
    "axes": "two axes of the part: the first along it toward its hinge, the second into it from its outer face "
            "(default `[edge_in, lid_in]`)",
    "inset": "metres the contact lies in from the point along the first of `axes` (or `[[openness, metres], ...]` "
             "pairs: an inset that changes as the part turns)",
    "depth": "metres from the point to the fingertip's centre along the second of `axes` (default 0.012)",
    "aim": "the way the fingertip points: an object axis name or a world direction `[x, y, z]`",
    "aim_cone_deg": "how far (deg) the finger may lean off `aim` (default 40)",
    "palm_across": "an object axis the palm stays across (70-110 deg), e.g. `up`",
    "step": "openness pushed per stage (default 0.15)",
    "standoff": "target1 (the pre-push pose): metres the fingertip stays off the contact point (default 0.05)",
}


def push_fields_text() -> str:
    """The push target's fields, required first, each with what it means."""
    from humanoidgen.tasks.targets import PushSpec

    required = [k for k, f in PushSpec.model_fields.items() if f.is_required()]
    optional = [k for k in PushSpec.model_fields if k not in required]
    return "; ".join(f"`{k}`{'' if k in required else ' (optional)'}: {PUSH_FIELDS[k]}" for k in required + optional)


def vocabulary_text(objects: list[tuple[str, int]] | None = None) -> str:
    """What the points, axes and openness of these (type, type_id) objects mean (every family when None)."""
    from humanoidgen.generation import object_text

    return object_text.all_families_text() if objects is None else object_text.objects_text(objects)


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
