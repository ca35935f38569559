"""The asset library: every object family by name, rigid and articulated."""

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

    return {**RIGID_FAMILIES, **ARTICULATED_FAMILIES, **SAFE_FAMILIES, **BARRIER_FAMILIES}


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


def annotations(name: str, type_id: int) -> ObjectAnnotations:
    model(name, type_id)  # a clear error for an unknown type_id
    return family(name).annotations(type_id)
