"""Success predicates over the simulated state. Each is a pydantic model with a `type` discriminator and its
tolerances; `evaluate(env)` answers ok plus a human-readable detail. A task succeeds when all hold.

Objects are referenced as "cube[0]" or {type: cube, id: 0} (id = order of adding among objects of that type).
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

import mujoco
import numpy as np
from pydantic import Field

from humanoidgen.objects.describe import openness as _openness
from humanoidgen.planning.hand_ops import finger_contacts, is_held
from humanoidgen.sim.layout import TABLE_TOP_Z, TABLE_X, TABLE_Y
from humanoidgen.sim.scene import SceneObject
from humanoidgen.tasks.gentle import MovedGently
from humanoidgen.tasks.held_move import MovedWhileHeld, MovedWhileTouched
from humanoidgen.tasks.predicate_base import ObjRef, PredicateResult, Ref, _cm, _name, _obj, _part_name, _Strict

__all__ = ["ObjRef", "Predicate", "PredicateResult", "Ref", "MovedWhileHeld", "MovedWhileTouched", "MovedGently",
           "evaluate_all"]

def _pose(env, ref: ObjRef) -> tuple[np.ndarray, np.ndarray]:
    """Centre and rotation matrix of the object's root body."""
    bid = env.model.body(_obj(env, ref).body).id
    return env.data.xpos[bid].copy(), env.data.xmat[bid].reshape(3, 3).copy()


def _bbox(env, ref: ObjRef) -> tuple[np.ndarray, np.ndarray]:
    ann = _obj(env, ref).annotations
    if ann is None:
        raise ValueError(f"{ref} has no annotations (no bounding box)")
    return np.asarray(ann.bbox_min), np.asarray(ann.bbox_max)


def _bottom_above_table(env, ref: ObjRef) -> float:
    """Height of the object's bounding-box bottom above the table top (upright; the box is in its own frame)."""
    return float(_pose(env, ref)[0][2] + _bbox(env, ref)[0][2] - TABLE_TOP_Z)


def _support_height(env, ref: ObjRef) -> float:
    """Height of the surface things rest on, above the object's centre: its "support" function point, else the
    bbox top (so a plate counts its floor, not its rim)."""
    ann = _obj(env, ref).annotations
    for fn in ann.functions if ann else []:
        if fn.function == "support":
            return float(ann.point(fn.point).position[2])
    return float(_bbox(env, ref)[1][2])


def _tilt_deg(R: np.ndarray) -> float:
    return math.degrees(math.acos(float(np.clip(R[2, 2], -1.0, 1.0))))


# -- predicates ----------------------------------------------------------------------------------------------
class OnTop(_Strict):
    """`obj` rests on `base`: centred within xy_tol, centre height difference z_gap ± z_tol."""

    type: Literal["on_top"] = "on_top"
    obj: Ref
    base: Ref
    xy_tol: float = Field(default=0.02, gt=0)
    z_gap: float | None = None  # None: base support height + obj's bottom depth (from annotations)
    z_tol: float = Field(default=0.006, gt=0)

    def refs(self) -> list[ObjRef]:
        return [self.obj, self.base]

    def evaluate(self, env) -> PredicateResult:
        p, _ = _pose(env, self.obj)
        b, _ = _pose(env, self.base)
        want = self.z_gap if self.z_gap is not None else _support_height(env, self.base) - _bbox(env, self.obj)[0][2]
        dz, dxy = float(p[2] - b[2]), float(np.linalg.norm(p[:2] - b[:2]))
        ok = abs(dz - want) <= self.z_tol and dxy <= self.xy_tol
        return PredicateResult(ok=ok, detail=f"{_name(self.obj)} is {_cm(dz)} above {_name(self.base)} (want "
                               f"{want * 100:.1f} ± {_cm(self.z_tol)}), xy offset {_cm(dxy)} (max {_cm(self.xy_tol)})")


class OnTable(_Strict):
    """`obj` rests on the table: its bottom within z_tol of the table top, its centre over the table."""

    type: Literal["on_table"] = "on_table"
    obj: Ref
    z_tol: float = Field(default=0.01, gt=0)

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def evaluate(self, env) -> PredicateResult:
        p, _ = _pose(env, self.obj)
        gap = _bottom_above_table(env, self.obj)
        over = TABLE_X[0] <= p[0] <= TABLE_X[1] and TABLE_Y[0] <= p[1] <= TABLE_Y[1]
        ok = abs(gap) <= self.z_tol and over
        return PredicateResult(ok=ok, detail=f"{_name(self.obj)}'s bottom is {_cm(gap)} above the table "
                               f"(max {_cm(self.z_tol)}){'' if over else ', not over the table'}")


class Stacked(_Strict):
    """A vertical stack in order: objs[0] on the table, each next one on top of the one before."""

    type: Literal["stacked"] = "stacked"
    objs: list[Ref] = Field(min_length=2)
    xy_tol: float = Field(default=0.02, gt=0)
    z_tol: float = Field(default=0.006, gt=0)

    def refs(self) -> list[ObjRef]:
        return list(self.objs)

    def evaluate(self, env) -> PredicateResult:
        parts = [OnTable(obj=self.objs[0]).evaluate(env)]
        parts += [OnTop(obj=top, base=base, xy_tol=self.xy_tol, z_tol=self.z_tol).evaluate(env)
                  for base, top in zip(self.objs, self.objs[1:])]
        return PredicateResult(ok=all(r.ok for r in parts), detail="; ".join(r.detail for r in parts))


class Pyramid(_Strict):
    """Two bases side by side on the table (centres at most base_gap apart beyond touching), `top` on both: its
    centre between the bases' centres along the line joining them (the paper authors' own check: the top cube's y
    between the two bases'), at most xy_tol off that line, one base height (from bboxes) ± z_tol above them."""

    type: Literal["pyramid"] = "pyramid"
    base1: Ref
    base2: Ref
    top: Ref
    base_gap: float = Field(default=0.015, ge=0)
    xy_tol: float = Field(default=0.02, gt=0)
    z_tol: float = Field(default=0.008, gt=0)

    def refs(self) -> list[ObjRef]:
        return [self.base1, self.base2, self.top]

    def evaluate(self, env) -> PredicateResult:
        b1, b2 = OnTable(obj=self.base1).evaluate(env), OnTable(obj=self.base2).evaluate(env)
        p1, p2, pt = (_pose(env, r)[0] for r in (self.base1, self.base2, self.top))
        w = float(_bbox(env, self.base1)[1][0] + _bbox(env, self.base2)[1][0])  # touching centre distance
        sep = float(np.linalg.norm(p1[:2] - p2[:2]))
        mid = (p1 + p2) / 2
        line = (p2[:2] - p1[:2]) / max(sep, 1e-9)
        rel = pt[:2] - mid[:2]
        along = float(rel @ line)  # from the midpoint toward base2
        across = float(abs(rel[0] * line[1] - rel[1] * line[0]))
        want = _support_height(env, self.base1) - float(_bbox(env, self.top)[0][2])
        dz = float(pt[2] - mid[2])
        ok = (b1.ok and b2.ok and w - 0.005 <= sep <= w + self.base_gap and abs(along) < sep / 2
              and across <= self.xy_tol and abs(dz - want) <= self.z_tol)
        return PredicateResult(ok=ok, detail=f"{b1.detail}; {b2.detail}; bases {_cm(sep)} apart (want {_cm(w)} to "
                               f"{_cm(w + self.base_gap)}); {_name(self.top)} {_cm(along)} from their midpoint along "
                               f"them (between them: under {_cm(sep / 2)}) and {_cm(across)} across (max "
                               f"{_cm(self.xy_tol)}), {_cm(dz)} above them (want {want * 100:.1f} ± {_cm(self.z_tol)})")


class Inside(_Strict):
    """`obj`'s centre is in `container`'s storage region: laterally within the container's bbox (less margin)
    around its "storage" point, between that point (less z_tol) and the container's top (plus z_tol)."""

    type: Literal["inside"] = "inside"
    obj: Ref
    container: Ref
    margin: float = Field(default=0.005, ge=0)
    z_tol: float = Field(default=0.01, ge=0)

    def refs(self) -> list[ObjRef]:
        return [self.obj, self.container]

    def evaluate(self, env) -> PredicateResult:
        from humanoidgen.objects.queries import storage_region

        region = storage_region(env, _obj(env, self.container))
        if region is None:
            return PredicateResult(ok=False, detail=f"{_name(self.container)} has no storage region")
        s, R, half, top = region
        half = half - self.margin
        p, _ = _pose(env, self.obj)
        local = R.T @ (p - s)  # the container's frame, from the storage point
        lateral = bool(np.all(np.abs(local[:2]) <= half))
        vertical = s[2] - self.z_tol <= p[2] <= top + self.z_tol
        return PredicateResult(ok=lateral and vertical, detail=(
            f"{_name(self.obj)} is ({_cm(local[0])}, {_cm(local[1])}) from {_name(self.container)}'s storage point "
            f"(max ±{_cm(half[0])}, ±{_cm(half[1])}), {_cm(p[2] - s[2])} above it (want -{_cm(self.z_tol)} to "
            f"{_cm(top - s[2] + self.z_tol)})"))


class AllInside(_Strict):
    """Every object of `obj_type` (e.g. all cubes poured from a cup) is inside `container`."""

    type: Literal["all_inside"] = "all_inside"
    obj_type: str
    container: Ref
    margin: float = Field(default=0.005, ge=0)
    z_tol: float = Field(default=0.01, ge=0)

    def refs(self) -> list[ObjRef]:
        return [self.container, ObjRef(type=self.obj_type, id=0)]

    def evaluate(self, env) -> PredicateResult:
        objs = [o for o in env.scene.objects if o.type_name == self.obj_type]
        rs = [Inside(obj=ObjRef(type=o.type_name, id=o.obj_id), container=self.container, margin=self.margin,
                     z_tol=self.z_tol).evaluate(env) for o in objs]
        n = sum(r.ok for r in rs)
        return PredicateResult(ok=bool(objs) and n == len(objs),
                               detail=f"{n}/{len(objs)} {self.obj_type}s inside: " + "; ".join(r.detail for r in rs))


class Lifted(_Strict):
    """`obj`'s centre is at least min_height above where it would rest on the table."""

    type: Literal["lifted"] = "lifted"
    obj: Ref
    min_height: float = Field(default=0.05, gt=0)

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def evaluate(self, env) -> PredicateResult:
        h = _bottom_above_table(env, self.obj)
        return PredicateResult(ok=h >= self.min_height,
                               detail=f"{_name(self.obj)} is {_cm(h)} above the table (min {_cm(self.min_height)})")


def _openness_check(env, ref: ObjRef, part: str | None, value: float, bound: str) -> PredicateResult:
    """An openness at least ("min") or at most ("max") `value`: the object's, or that of `part`'s own joint."""
    obj = _obj(env, ref)
    o = _openness(env.model, env.data, obj, part)
    if o is None:
        return PredicateResult(ok=False, detail=f"{_name(ref)} has no moving part")
    what = _part_name(ref, part)
    if part is not None:
        art = obj.annotations.articulation_for(part)
        if art.part != part:
            return PredicateResult(ok=False, detail=f"{_name(ref)} has no joint of its own for part {part!r}")
        what += f" (turned {math.degrees(abs(art.joint_position(o) - art.closed)):.0f} deg)" if _is_hinge(env, obj, art) else ""
    ok = o >= value if bound == "min" else o <= value
    return PredicateResult(ok=ok, detail=f"{what} openness {o:.2f} ({bound} {value:.2f})")


def _is_hinge(env, obj: SceneObject, art) -> bool:
    return env.model.jnt_type[env.model.joint(f"{obj.body}_{art.joint}").id] == mujoco.mjtJoint.mjJNT_HINGE


class OpennessAtLeast(_Strict):
    type: Literal["openness_at_least"] = "openness_at_least"
    obj: Ref
    value: float = Field(ge=0, le=1)
    part: str | None = None  # a part with a joint of its own (a safe's knob); None: the object's openness

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def evaluate(self, env) -> PredicateResult:
        return _openness_check(env, self.obj, self.part, self.value, "min")


class OpennessAtMost(_Strict):
    type: Literal["openness_at_most"] = "openness_at_most"
    obj: Ref
    value: float = Field(ge=0, le=1)
    part: str | None = None  # a part with a joint of its own (a safe's knob); None: the object's openness

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def evaluate(self, env) -> PredicateResult:
        return _openness_check(env, self.obj, self.part, self.value, "max")


class Upright(_Strict):
    type: Literal["upright"] = "upright"
    obj: Ref
    max_tilt_deg: float = Field(default=15.0, gt=0, le=180)
    either_end: bool = False  # an object alike at both ends (a block) stands upright on either of them

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def evaluate(self, env) -> PredicateResult:
        t = _tilt_deg(_pose(env, self.obj)[1])
        t = min(t, 180.0 - t) if self.either_end else t
        return PredicateResult(ok=t <= self.max_tilt_deg,
                               detail=f"{_name(self.obj)} tilted {t:.1f}° (max {self.max_tilt_deg:.1f}°)")


class Held(_Strict):
    """The `side` hand squeezes `obj` (thumb against a finger or the palm)."""

    type: Literal["held"] = "held"
    obj: Ref
    side: Literal["left", "right"]

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def evaluate(self, env) -> PredicateResult:
        touched = finger_contacts(env.model, env.data, self.side, _obj(env, self.obj).body)
        return PredicateResult(ok=is_held(touched), detail=f"{self.side} hand touches {_name(self.obj)} with "
                               f"{', '.join(sorted(touched)) or 'nothing'} (held needs the thumb and another)")


class Near(_Strict):
    """`obj`'s centre is within tol of target_xy on the table plane."""

    type: Literal["near"] = "near"
    obj: Ref
    target_xy: tuple[float, float]
    tol: float = Field(default=0.03, gt=0)

    def refs(self) -> list[ObjRef]:
        return [self.obj]

    def evaluate(self, env) -> PredicateResult:
        d = float(np.linalg.norm(_pose(env, self.obj)[0][:2] - np.asarray(self.target_xy)))
        return PredicateResult(ok=d <= self.tol, detail=f"{_name(self.obj)} is {_cm(d)} from "
                               f"({self.target_xy[0]:.3f}, {self.target_xy[1]:.3f}) (max {_cm(self.tol)})")


Predicate = Annotated[
    OnTop | OnTable | Stacked | Pyramid | Inside | AllInside | Lifted | OpennessAtLeast | OpennessAtMost | Upright | Held
    | MovedWhileHeld | MovedWhileTouched | MovedGently | Near,
    Field(discriminator="type"),
]


def evaluate_all(predicates: list, env) -> PredicateResult:
    """A task's success: all predicates hold; the detail lists each."""
    rs = [p.evaluate(env) for p in predicates]
    return PredicateResult(ok=all(r.ok for r in rs),
                           detail="\n".join(f"[{'ok' if r.ok else 'no'}] {p.type}: {r.detail}" for p, r in zip(predicates, rs)))
