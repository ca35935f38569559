"""What the objects' annotations mean, in words, for plan authors: each family's frame, its points and axes with
their descriptions and directions, and for articulated objects what `openness` moves, its range in degrees or
millimetres per model, how far plans should ask for and which points and axes each openness moves.

From the family data files (objects/families/<family>/family.yaml, whose schema requires every description) and
the models' annotations; the prompts show it for the task's objects (every family in the scene prompt), the
objects guide for every family (docs/hooks.py), so the three cannot drift apart.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from humanoidgen.objects import library
from humanoidgen.objects.family_data import family_file
from humanoidgen.objects.params import FamilyFile, OpennessSpec
from humanoidgen.objects.schema import Articulation, ObjectAnnotations

CENTER = "the middle of the object's bounding box (every object has it)"
FRAME = ("Points and axes are given in each object's own frame (a moving part's with the part closed, openness 0): "
         "with the object at yaw 0, +x points away from the robot, +y to its left and +z up when it stands upright. "
         "get_point_in_env / get_axis_in_env give them in the world as the object stands now (with `openness=`, "
         "where a moving part's will be).")


def _kind(name: str) -> str:
    fam = library.family(name)
    if fam.articulated:
        return "articulated, fixed to the table"
    return "static, fixed to the table" if getattr(fam, "static", False) else "rigid, free"


def _vec(v: Iterable[float]) -> str:
    return "[" + ", ".join(f"{x:.3g}" if abs(x) > 1e-9 else "0" for x in v) + "]"


def _physical(spec: OpennessSpec, art: Articulation) -> tuple[float, str]:
    """The joint's full range (openness 0 to 1) in the spec's unit."""
    span = abs(art.open - art.closed)
    return (math.degrees(span), "deg") if spec.unit == "deg" else (span * 1000.0, "mm")


def _spec_for(info: FamilyFile, ann: ObjectAnnotations, art: Articulation) -> OpennessSpec | None:
    """The openness spec of a joint: a part's own by its part, the object's own is the spec of the part without a
    joint of its own."""
    own_parts = {a.part for a in ann.part_articulations}
    for spec in info.openness:
        if (art.part is not None and spec.part == art.part) or (art.part is None and spec.part not in own_parts):
            return spec
    return None


def _openness_lines(name: str, info: FamilyFile, anns: dict[int, ObjectAnnotations]) -> list[str]:
    first = next(iter(anns.values()))
    out = []
    for art in [first.articulation, *first.part_articulations]:
        spec = _spec_for(info, first, art)
        if spec is None:
            continue
        where = ("`openness` (the object's)" if art.part is None else
                 f"`{art.part} openness` (a joint of its own: `{art.part} openness` in the state, `part: {art.part}` "
                 "in success predicates)")
        ranges = []
        for type_id, ann in anns.items():
            a = next((x for x in [ann.articulation, *ann.part_articulations] if x is not None and x.part == art.part),
                     None)
            if a is None:
                continue
            full, unit = _physical(spec, a)
            text = f"type_id {type_id}: 0 to {full:.0f} {unit} (0.1 openness = {full / 10:.3g} {unit})"
            held = library.model(name, type_id).params.get("holds_from")
            if held is not None and art.part is None:
                text += f", stays where it is left only from openness {held:g} up (below, it falls shut)"
            ranges.append(text)
        moved = [p.name for p in first.points if p.part is not None and first.articulation_for(p.part) == art]
        axes = [a.name for a in first.axes if a.part is not None and first.articulation_for(a.part) == art]
        line = (f"{where}, 0 closed to 1 open: {spec.moves}; {'; '.join(ranges)}. "
                f"It moves the points {', '.join(moved)} and the axes {', '.join(axes) or '(none)'}; an `openness=` "
                "given with one of them (or with an action on one of them) is this joint's.")
        if spec.recommended_max is not None:
            line += f" Ask for at most {spec.recommended_max:g}: {spec.note}."
        out.append(line)
    return out


def family_text(name: str, type_ids: Iterable[int] | None = None, indent: str = "  ") -> str:
    """One family as a nested bullet list; `type_ids`: the models to cover (default: every model of the family),
    whose points (and, for articulated objects, openness ranges) are shown."""
    info = family_file(name)
    ids = sorted(set(type_ids)) if type_ids is not None else [m.type_id for m in library.family(name).models()]
    anns = {i: library.annotations(name, i) for i in ids}
    present = {p.name for a in anns.values() for p in a.points}
    parts = {p.name: p.part for a in anns.values() for p in a.points}
    lines = [f"- {name} ({_kind(name)}):"]
    if info.articulated:
        lines += [f"{indent}- {t}" for t in _openness_lines(name, info, anns)]
    points = [f"`center`: {CENTER}"]
    for p in info.points:
        if p.name in present:
            on = f" (on the {parts[p.name]}, moves with it)" if parts.get(p.name) else ""
            points.append(f"`{p.name}`{on}: {p.description}")
    lines.append(f"{indent}- points: " + "; ".join(points))
    axes = []
    for a in info.axes:
        on = f" (on the {a.part})" if a.part else ""
        axes.append(f"`{a.name}` {_vec(a.direction)}{on}: {a.description}")
    lines.append(f"{indent}- axes: " + "; ".join(axes))
    return "\n".join(lines)


def objects_text(objects: Iterable[tuple[str, int]], indent: str = "  ") -> str:
    """The frame, then the families of these (type, type_id) objects, each once, with the models present."""
    by_family: dict[str, set[int]] = {}
    for type_name, type_id in objects:
        by_family.setdefault(type_name, set()).add(type_id)
    return FRAME + "\n\n" + "\n".join(family_text(n, ids, indent) for n, ids in sorted(by_family.items()))


def all_families_text(indent: str = "  ") -> str:
    """The frame, then every family with all its models."""
    return FRAME + "\n\n" + "\n".join(family_text(n, None, indent) for n in sorted(library.families()))
