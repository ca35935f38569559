"""The machinery of the articulated families: a declarative design of box geoms, parts and joints, built into a
scene; annotations shifted into the bounding-box-centred object frame.

Every articulated family is a `_DataFamily` (objects/articulated.py, objects/safe.py): it reads its models and
annotation vocabulary from humanoidgen/objects/families/<family>/ and computes only geometry and point positions.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import mujoco
import numpy as np

from humanoidgen.objects.family import ObjectModel
from humanoidgen.objects.family_data import FamilyData, FamilyDataError, ModelData, family_data
from humanoidgen.objects.params import ArticulatedParams
from humanoidgen.objects.schema import (
    Articulation,
    FunctionAnnotation,
    KeyAxis,
    KeyPoint,
    ObjectAnnotations,
    OperationAnnotation,
)

_DEG = np.pi / 180.0
# Friction loss is a soft constraint: under a load below its bound it still yields slowly. Near-hard impedance
# keeps a part that a hand left (half-open laptop screen, drawer) where it is.
_SOLIMP_FRICTION = [0.9999, 0.9999, 0.001, 0.5, 2.0]
_SOLREF_FRICTION = [0.02, 1.0]


# -- a small declarative description of an articulated object (design coordinates, closed state) ------------
@dataclass(frozen=True)
class _Geom:
    name: str
    half: tuple[float, float, float]
    pos: tuple[float, float, float]  # in its body's frame
    rgba: tuple[float, float, float, float]
    mass: float = 0.05


@dataclass(frozen=True)
class _Joint:
    name: str
    kind: str  # "slide" | "hinge"
    axis: tuple[float, float, float]
    range: tuple[float, float]  # metres or radians
    damping: float
    frictionloss: float
    armature: float = 0.005


def _joint(name: str, kind: str, axis: tuple[float, float, float], range_: tuple[float, float],
           dynamics: Mapping[str, float]) -> _Joint:
    """A joint whose damping, friction loss and armature come from a model's parameters (`JointDynamics`)."""
    return _Joint(name, kind, axis, range_, damping=dynamics["damping"], frictionloss=dynamics["frictionloss"],
                  armature=dynamics["armature"])


@dataclass
class _Part:
    name: str
    pos: tuple[float, float, float]  # body origin in its parent's frame (design coordinates for the root)
    joint: _Joint
    geoms: list[_Geom]
    parent: str | None = None  # another part's name; None: the object's root body


@dataclass
class _Design:
    geoms: list[_Geom]  # on the root body
    parts: list[_Part] = field(default_factory=list)

    def part_origin(self, name: str) -> np.ndarray:
        """A part body's origin in design coordinates (closed state: all parts unrotated)."""
        part = next(p for p in self.parts if p.name == name)
        base = np.zeros(3) if part.parent is None else self.part_origin(part.parent)
        return base + np.asarray(part.pos, float)

    def bbox(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
        groups = [(np.zeros(3), self.geoms)] + [(self.part_origin(p.name), p.geoms) for p in self.parts]
        for origin, geoms in groups:
            for g in geoms:
                c, h = origin + np.asarray(g.pos, float), np.asarray(g.half, float)
                lo, hi = np.minimum(lo, c - h), np.maximum(hi, c + h)
        return lo, hi

    def center(self) -> np.ndarray:
        lo, hi = self.bbox()
        return (lo + hi) / 2

    def geom_names(self) -> list[str]:
        return [g.name for g in self.geoms] + [g.name for p in self.parts for g in p.geoms]


@dataclass
class _Annot:
    """Annotations in design coordinates (root points) or part-local coordinates (part points)."""

    description: str
    points: list[KeyPoint]
    axes: list[KeyAxis]
    operations: list[OperationAnnotation]
    functions: list[FunctionAnnotation]
    articulation: Articulation


def _pt(name: str, pos, part: str | None = None, description: str = "") -> KeyPoint:
    return KeyPoint(name=name, position=tuple(float(v) for v in pos), part=part, description=description)


def _op(operation: str, point: str, approach: str, attach: str, parallel: str) -> OperationAnnotation:
    return OperationAnnotation(operation=operation, point=point, approach_axis=approach, attach_axis=attach,
                               parallel_axis=parallel)


class _ArticulatedFamily:
    """Common machinery: build from a `_Design`, annotations shifted to the bounding-box-centred object frame."""

    name: str = ""
    articulated: bool = True

    # subclasses implement these three
    def _p(self, type_id: int) -> dict:  # pragma: no cover - abstract
        raise NotImplementedError

    def _design(self, p: dict) -> _Design:  # pragma: no cover - abstract
        raise NotImplementedError

    def _annot(self, p: dict, design: _Design) -> _Annot:  # pragma: no cover - abstract
        raise NotImplementedError

    def build(self, spec: mujoco.MjSpec, body: mujoco.MjsBody, type_id: int) -> None:
        design = self._design(self._p(type_id))
        shift = -design.center()
        prefix = body.name
        degree = bool(spec.compiler.degree)
        _add_geoms(body, prefix, design.geoms, shift)
        bodies = {None: body}
        for part in design.parts:  # parents come before their children
            parent = bodies[part.parent]
            pos = np.asarray(part.pos, float) + (shift if part.parent is None else 0.0)
            child = parent.add_body(name=f"{prefix}_{part.name}", pos=pos.tolist())
            j = part.joint
            lo, hi = j.range
            if j.kind == "hinge" and degree:
                lo, hi = lo / _DEG, hi / _DEG
            child.add_joint(
                name=f"{prefix}_{j.name}",
                type=mujoco.mjtJoint.mjJNT_HINGE if j.kind == "hinge" else mujoco.mjtJoint.mjJNT_SLIDE,
                axis=list(j.axis), range=[lo, hi], limited=mujoco.mjtLimited.mjLIMITED_TRUE,
                damping=j.damping, frictionloss=j.frictionloss, armature=j.armature,
                solimp_friction=_SOLIMP_FRICTION, solref_friction=_SOLREF_FRICTION,
            )
            _add_geoms(child, prefix, part.geoms, np.zeros(3))
            bodies[part.name] = child
        # A part slides/turns inside or against its shell with no clearance: the root body is welded to the
        # world, so MuJoCo's parent filter does not apply; exclude every pair of the object's bodies instead.
        names = [body.name] + [f"{prefix}_{p.name}" for p in design.parts]
        for i, a in enumerate(names):
            for b in names[i + 1:]:
                spec.add_exclude(name=f"{a}__{b}_exclude", bodyname1=a, bodyname2=b)

    def annotations(self, type_id: int) -> ObjectAnnotations:
        p = self._p(type_id)
        design = self._design(p)
        center = design.center()
        lo, hi = design.bbox()
        a = self._annot(p, design)
        points = [kp if kp.part is not None else kp.model_copy(
            update={"position": tuple(float(v) for v in np.asarray(kp.position) - center)}) for kp in a.points]
        return ObjectAnnotations(
            family=self.name, type_id=type_id, description=a.description,
            bbox_min=tuple(float(v) for v in lo - center), bbox_max=tuple(float(v) for v in hi - center),
            points=points, axes=a.axes, operations=a.operations, functions=a.functions,
            articulation=a.articulation,
        )


class _DataFamily(_ArticulatedFamily):
    """A family whose models and annotation vocabulary are data (families/<name>/, validated against `Params`).
    Subclasses give `_design` (geoms, parts, joints from a model's parameters), `_positions` (where each point
    of family.yaml is, in design or part coordinates) and `_articulation`."""

    Params: type[ArticulatedParams] = ArticulatedParams

    def _positions(self, p: dict) -> dict[str, tuple[float, float, float]]:  # pragma: no cover - abstract
        raise NotImplementedError

    def _articulation(self, p: dict) -> Articulation:  # pragma: no cover - abstract
        raise NotImplementedError

    def _data(self) -> FamilyData:
        return family_data(self.name, self.Params)

    def _model(self, type_id: int) -> ModelData:
        models = self._data().models
        if type_id not in models:
            raise KeyError(f"{self.name}: no type_id {type_id}; known: {sorted(models)}")
        return models[type_id]

    def _p(self, type_id: int) -> dict:
        m = self._model(type_id)
        p = {"description": m.description, **m.params}
        # `masses` is the one free-form mapping of a model: every geom of the design needs exactly one entry.
        try:
            names = self._design(p).geom_names()
        except KeyError as exc:
            raise FamilyDataError(f"{m.path}: masses: no mass for geom {exc.args[0]!r}") from None
        extra = sorted(set(p["masses"]) - set(names))
        if extra:
            raise FamilyDataError(f"{m.path}: masses: no geom named {extra} (geoms: {names})")
        return p

    def models(self) -> list[ObjectModel]:
        return [ObjectModel(self.name, m.type_id, m.description, {k: v for k, v in m.params.items() if k in m.own})
                for m in self._data().models.values()]

    def _annot(self, p: dict, design: _Design) -> _Annot:
        info = self._data().info
        positions = self._positions(p)
        named = [s.name for s in info.points]
        if sorted(named) != sorted(positions):
            raise FamilyDataError(f"{self._data().path}: points: the family code places {sorted(positions)}, "
                                  f"the file names {sorted(named)}")
        points = [_pt(s.name, positions[s.name], s.part, s.description) for s in info.points]
        ops = [_op(o.operation, o.point, o.approach_axis, o.attach_axis, o.parallel_axis) for o in info.operations]
        fns = [FunctionAnnotation(function=f.function, point=f.point, axis=f.axis) for f in info.functions]
        return _Annot(p["description"], points, list(info.axes), ops, fns, self._articulation(p))


def _add_geoms(body: mujoco.MjsBody, prefix: str, geoms: list[_Geom], shift: np.ndarray) -> None:
    for g in geoms:
        body.add_geom(name=f"{prefix}_{g.name}", type=mujoco.mjtGeom.mjGEOM_BOX, size=list(g.half),
                      pos=(np.asarray(g.pos, float) + shift).tolist(), rgba=list(g.rgba), mass=g.mass,
                      friction=[1.0, 0.01, 0.001], condim=4)


def _shell(D: float, W: float, H: float, t: float, rgba, masses: Mapping[str, float]) -> list[_Geom]:
    """A cabinet shell centred at the origin, open toward -x: bottom, top, back and two sides."""
    m = masses
    return [
        _Geom("bottom", (D / 2, W / 2, t / 2), (0, 0, -H / 2 + t / 2), rgba, m["bottom"]),
        _Geom("top", (D / 2, W / 2, t / 2), (0, 0, H / 2 - t / 2), rgba, m["top"]),
        _Geom("back", (t / 2, W / 2 - t, H / 2 - t), (D / 2 - t / 2, 0, 0), rgba, m["back"]),
        _Geom("side_left", (D / 2, t / 2, H / 2 - t), (0, W / 2 - t / 2, 0), rgba, m["side_left"]),
        _Geom("side_right", (D / 2, t / 2, H / 2 - t), (0, -(W / 2 - t / 2), 0), rgba, m["side_right"]),
    ]
