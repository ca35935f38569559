"""Every object family's models as data: the compiled MuJoCo model and the annotations of each (family, type_id).

The object families moved from Python literals into data files (humanoidgen/objects/families/); this dump, taken
before the move (tests/data/family_snapshot.json), pins that the move changed nothing. Regenerate it only for an
intended change of a model: `python3 tests/family_snapshot.py`.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402

SNAPSHOT = Path(__file__).parent / "data" / "family_snapshot.json"
# The families that lived in objects/rigid.py and objects/articulated.py, and the safe of objects/safe.py (its
# models moved to data later; the first safe, in articulated.py then, was replaced by it and removed).
FAMILIES = ("cube", "bottle", "can", "plate", "cup", "bowl", "pot", "drawer", "laptop", "box", "toaster", "safe")

# Compiled arrays that carry everything a family's build decides: bodies, geoms, joints, their dynamics, masses
# (split over the primitives), contact settings and excluded pairs.
_FIELDS = ("body_parentid", "body_pos", "body_quat", "body_ipos", "body_iquat", "body_mass", "body_inertia",
           "geom_type", "geom_bodyid", "geom_size", "geom_pos", "geom_quat", "geom_rgba", "geom_friction",
           "geom_condim", "geom_solref", "geom_solimp", "jnt_type", "jnt_bodyid", "jnt_pos", "jnt_axis",
           "jnt_range", "jnt_limited", "dof_damping", "dof_frictionloss", "dof_armature", "dof_solref",
           "dof_solimp", "exclude_signature")


def families() -> dict:
    """The rigid and articulated families and the safe by name, from their modules."""
    from humanoidgen.objects.articulated import ARTICULATED_FAMILIES
    from humanoidgen.objects.rigid import RIGID_FAMILIES
    from humanoidgen.objects.safe import SAFE_FAMILIES

    return {**RIGID_FAMILIES, **ARTICULATED_FAMILIES, **SAFE_FAMILIES}


def dump_model(family: str, type_id: int) -> dict:
    """One model built alone into a fresh spec (body "<family>_0" at the origin), compiled, plus annotations."""
    fam = families()[family]
    spec = mujoco.MjSpec()
    body = spec.worldbody.add_body(name=f"{family}_0", pos=[0.0, 0.0, 0.0])
    fam.build(spec, body, type_id)
    model = spec.compile()
    arrays = {f: np.asarray(getattr(model, f)).tolist() for f in _FIELDS}
    names = {kind: [mujoco.mj_id2name(model, obj, i) for i in range(n)] for kind, obj, n in (
        ("body", mujoco.mjtObj.mjOBJ_BODY, model.nbody), ("geom", mujoco.mjtObj.mjOBJ_GEOM, model.ngeom),
        ("joint", mujoco.mjtObj.mjOBJ_JOINT, model.njnt), ("exclude", mujoco.mjtObj.mjOBJ_EXCLUDE, model.nexclude))}
    (model_meta,) = [m for m in fam.models() if m.type_id == type_id]
    return {"description": model_meta.description, "articulated": fam.articulated, "names": names,
            "arrays": arrays, "xml": spec.to_xml(), "annotations": fam.annotations(type_id).model_dump(mode="json")}


def dump_all() -> dict:
    out = {}
    for family in FAMILIES:
        for m in families()[family].models():
            out[f"{family}/{m.type_id}"] = dump_model(family, m.type_id)
    return out


def differences(old, new, path: str = "", tol: float = 1e-12) -> list[str]:
    """Where `new` differs from the snapshot `old` (floats to `tol`). A key the snapshot lacks is no difference
    when its value is empty (None or []): a field the annotation schema gained later, at its default. The words
    describing an annotated point or axis are not the model: they are for plan authors, and every point and axis
    has them (tests/test_annotation_words.py)."""
    if isinstance(old, dict) and isinstance(new, dict):
        if "/annotations/" in path:
            old, new = ({k: v for k, v in d.items() if k != "description"} for d in (old, new))
        out = [f"{path}/{k}: missing" for k in old if k not in new]
        out += [f"{path}/{k}: new field = {new[k]!r}" for k in new if k not in old and new[k] not in (None, [])]
        for k in old.keys() & new.keys():
            out += differences(old[k], new[k], f"{path}/{k}", tol)
        return out
    if isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            return [f"{path}: {len(old)} items, now {len(new)}"]
        return [d for i, (a, b) in enumerate(zip(old, new)) for d in differences(a, b, f"{path}[{i}]", tol)]
    if isinstance(old, float) or isinstance(new, float):
        if isinstance(old, (int, float)) and isinstance(new, (int, float)) and abs(old - new) <= tol:
            return []
    elif old == new and type(old) is type(new):
        return []
    return [f"{path}: {old!r} -> {new!r}"]


if __name__ == "__main__":
    SNAPSHOT.write_text(json.dumps(dump_all(), indent=None, sort_keys=True))
    print(f"wrote {SNAPSHOT} ({SNAPSHOT.stat().st_size} bytes)", file=sys.stderr)
