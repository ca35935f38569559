"""The asset library: every object family by name, rigid and articulated, with the models imported from files."""

from __future__ import annotations

from functools import cache

from humanoidgen.objects.family import ObjectFamily, ObjectModel
from humanoidgen.objects.schema import ObjectAnnotations


@cache
def families() -> dict[str, ObjectFamily]:
    from humanoidgen.objects.articulated import ARTICULATED_FAMILIES
    from humanoidgen.objects.barrier import BARRIER_FAMILIES
    from humanoidgen.objects.rigid import RIGID_FAMILIES
    from humanoidgen.objects.safe import SAFE_FAMILIES

    from humanoidgen.objects.imported.family_view import WithImported

    base = {**RIGID_FAMILIES, **ARTICULATED_FAMILIES, **SAFE_FAMILIES, **BARRIER_FAMILIES}
    # Barriers are fixed to the table; every other family also has the models imported from files.
    return {name: fam if name in BARRIER_FAMILIES else WithImported(fam) for name, fam in base.items()}


def family(name: str) -> ObjectFamily:
    fams = families()
    if name not in fams:
        raise KeyError(f"unknown object type {name!r}; known types: {', '.join(sorted(fams))}")
    return fams[name]


def model(name: str, type_id: int) -> ObjectModel:
    fam = family(name)
    models = fam.models()
    for m in models:
        if m.type_id == type_id:
            return m
    raise KeyError(f"{name} has no type_id {type_id}; type_ids: {', '.join(str(m.type_id) for m in models)}")


def model_named(family_name: str, model: str) -> ObjectModel:
    """A model of a family by its type_id ("3") or, for an imported one, its name ("my_mug")."""
    models = family(family_name).models()
    for m in models:
        if str(m.type_id) == model or m.params.get("name") == model:
            return m
    names = [m.params.get("name", str(m.type_id)) for m in models]
    raise KeyError(f"{family_name} has no model {model!r}; models: {', '.join(names)}")


def annotations(name: str, type_id: int) -> ObjectAnnotations:
    model(name, type_id)  # a clear error for an unknown type_id
    return family(name).annotations(type_id)


def add_object(builder, type_name: str, type_id: int = 0, pos: tuple[float, ...] | None = None,
               yaw: float = 0.0):
    """Add model `type_id` of family `type_name` to `builder` (a sim.scene.SceneBuilder); returns its
    SceneObject, annotations attached. `pos` is the object's centre; a missing z (or pos=(x, y)) puts it on the
    table. `yaw` (radians) turns it about the vertical."""
    import numpy as np

    from humanoidgen.sim.geometry import yaw_quat
    from humanoidgen.sim.layout import TABLE_TOP_Z

    fam = family(type_name)
    ann = annotations(type_name, type_id)
    if pos is None:
        pos = (-0.30, 0.0)
    xyz = np.array([pos[0], pos[1], pos[2] if len(pos) > 2 else TABLE_TOP_Z - ann.bbox_min[2]], float)
    # Articulated objects and static families (barriers) stand fixed on the table: no free joint.
    free = not (fam.articulated or getattr(fam, "static", False))
    obj, body = builder.add_object_body(type_name, xyz, yaw_quat(yaw), type_id=type_id, free=free, annotations=ann)
    fam.build(builder.spec, body, type_id)
    return obj
