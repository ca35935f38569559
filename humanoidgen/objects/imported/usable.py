"""Whether an imported model offers what its family's tasks need (the `usable` rules of the family's
family.yaml: a drawer's handle high enough over the table for the hooked fingers, standing far enough out of the
front to be held). A model that fails a rule stays a model of its family (`--model` takes it) but is never
drawn by `--randomize-models` (`stand_ins.drawable_models`); the library's manifest names such models and the
reason, and a test checks the two agree."""

from __future__ import annotations

import mujoco
import numpy as np

from humanoidgen.objects.imported.model_file import ImportedModel


def unusable_reason(model: ImportedModel) -> str | None:
    """The first rule of its family the model fails, as a sentence with the measured value; None if it passes."""
    rules = family_rules(model.info.family)
    if not rules:
        return None
    where = _points_closed(model)
    base = float(model.annotations.bbox_min[2])
    for rule in rules:
        p = where[rule.point]
        if rule.min_height is not None:
            got = float(p[2] - base)
            if got < rule.min_height:
                return (f"its {rule.point} is {100 * got:.1f} cm over its base (at least {100 * rule.min_height:.1f} "
                        f"cm wanted): {rule.why}")
        else:
            got = float(where[rule.from_point][0] - p[0])
            if got < rule.min_out:
                return (f"its {rule.point} stands {100 * got:.1f} cm out of its {rule.from_point} (at least "
                        f"{100 * rule.min_out:.1f} cm wanted): {rule.why}")
    return None


def family_rules(family: str) -> list:
    """The `usable` rules of the family's family.yaml (params.UsableRule)."""
    from humanoidgen.objects import library
    from humanoidgen.objects.family_data import family_data

    fam = library.family(family)
    base = getattr(fam, "base", fam)
    params = getattr(base, "Params", None)
    return list(family_data(family, params).info.usable) if params is not None else []


_CACHE: dict[tuple[str, int], dict[str, np.ndarray]] = {}


def _points_closed(model: ImportedModel) -> dict[str, np.ndarray]:
    """Every annotated point in the object frame with the model closed (its moving parts at openness 0)."""
    key = (str(model.folder), (model.folder / "model.yaml").stat().st_mtime_ns)
    if key not in _CACHE:
        _CACHE[key] = _points(model)
    return _CACHE[key]


def _points(model: ImportedModel) -> dict[str, np.ndarray]:
    from humanoidgen.objects.imported.build import build_imported

    spec = mujoco.MjSpec()
    body = spec.worldbody.add_body(name="obj")
    build_imported(spec, body, model)
    m = spec.compile()
    d = mujoco.MjData(m)
    art = model.annotations.articulation
    if art is not None:
        d.qpos[m.jnt_qposadr[m.joint(f"obj_{art.joint}").id]] = art.joint_position(0.0)
    mujoco.mj_kinematics(m, d)
    out = {}
    for kp in model.annotations.points:
        b = m.body(f"obj_{kp.part}" if kp.part else "obj").id
        out[kp.name] = d.xpos[b] + d.xmat[b].reshape(3, 3) @ np.asarray(kp.position, float)
    return out
