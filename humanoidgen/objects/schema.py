"""Spatial annotations of an object model: key points and key axes, what the object does (functional) and how
hands operate on it (operations). One schema for every asset, validated by pydantic.

All coordinates are in the object's own frame (origin at the centre of its bounding box, z up when upright),
or, for points and axes with a `part`, in the frame of that moving part's body (they move with the part).
"""

from __future__ import annotations

from pathlib import Path
from typing import Literal

import numpy as np
import yaml
from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

Vec3 = tuple[float, float, float]
Operation = Literal["grasp", "pinch", "press", "pull", "push", "flip"]


class AnnotationError(ValueError):
    """An annotation file or object that does not fit the schema."""


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, defer_build=True)


class KeyPoint(_Strict):
    name: str = Field(min_length=1)
    position: Vec3
    part: str | None = None  # a moving part's body suffix (e.g. "drawer"); None: the object's root body
    description: str = ""


class KeyAxis(_Strict):
    name: str = Field(min_length=1)
    direction: Vec3
    part: str | None = None
    description: str = ""

    @field_validator("direction")
    @classmethod
    def _unit(cls, v: Vec3) -> Vec3:
        n = float(np.linalg.norm(v))
        if abs(n - 1.0) > 1e-3:
            raise ValueError(f"axis direction must be unit length, got |{list(v)}| = {n:.4f}")
        return v


class OperationAnnotation(_Strict):
    """Where and how a hand operation applies: the key point, and the three axes of the paper's section 2.1."""

    operation: Operation
    point: str
    approach_axis: str  # the direction the hand approaches from (pointing from the hand toward the object)
    attach_axis: str  # the direction the fingers close along
    parallel_axis: str  # perpendicular to both, in the palm plane: the part's rotation axis, if any
    # For a grasp around a round body (bottle, can, cup): its diameter at the point (m). The hand then wraps it
    # against the finger pads, clear of the opposed thumb, instead of closing on it at the palm's grasp point.
    width: float | None = Field(default=None, gt=0.0, le=0.12)
    # For a wrap of a body that is not round (a flat bottle): its horizontal extent across the approach (m), which
    # lies along the fingers; None: round, the same as `width`.
    across: float | None = Field(default=None, gt=0.0, le=0.15)


class FunctionAnnotation(_Strict):
    """Where the object exerts its function (storage, pouring, support, ...)."""

    function: str
    point: str
    axis: str


class Articulation(_Strict):
    """The joint whose position is the object's openness: openness 0 is `closed`, 1 is `open` (joint units)."""

    joint: str  # joint suffix; the full name is "<type>_<obj_id>_<joint>"
    closed: float
    open: float
    # The moving part this joint turns or slides (a point or axis with this `part` moves with it). Only needed
    # for a part with a joint of its own besides the object's main one (`ObjectAnnotations.part_articulations`).
    part: str | None = None

    def joint_position(self, openness: float) -> float:
        """Joint position for an openness (0 closed, 1 open; values outside extrapolate)."""
        return self.closed + openness * (self.open - self.closed)

    def openness_of(self, q: float) -> float:
        """Openness of a joint position, clipped to [0, 1]."""
        return float(min(max((q - self.closed) / (self.open - self.closed), 0.0), 1.0))


class ObjectAnnotations(_Strict):
    family: str
    type_id: int = Field(ge=0)
    description: str
    bbox_min: Vec3
    bbox_max: Vec3
    points: list[KeyPoint] = Field(default_factory=list)
    axes: list[KeyAxis] = Field(default_factory=list)
    operations: list[OperationAnnotation] = Field(default_factory=list)
    functions: list[FunctionAnnotation] = Field(default_factory=list)
    articulation: Articulation | None = None
    # Parts with a joint of their own besides the main one (a safe's knob on its door): an openness asked for a
    # point or axis on such a part is that joint's (`articulation_for`). The object's openness stays the main one.
    part_articulations: list[Articulation] = Field(default_factory=list)

    @field_validator("axes", mode="before")
    @classmethod
    def _plain_axes(cls, v: object) -> object:
        # A family file's axes (params.AxisSpec, a KeyAxis with a required description) are stored as KeyAxis, so
        # that annotations compare equal to themselves read back from their JSON.
        if isinstance(v, list):
            return [KeyAxis(**a.model_dump()) if isinstance(a, KeyAxis) and type(a) is not KeyAxis else a for a in v]
        return v

    @model_validator(mode="after")
    def _references(self) -> "ObjectAnnotations":
        if self.part_articulations and self.articulation is None:
            raise ValueError("part_articulations need a main articulation")
        parts = [a.part for a in self.part_articulations]
        if None in parts or len(set(parts)) != len(parts):
            raise ValueError(f"each part articulation names its own part, got {parts}")
        joints = [self.articulation.joint] + [a.joint for a in self.part_articulations] if self.articulation else []
        if len(set(joints)) != len(joints):
            raise ValueError(f"part articulations need joints of their own, got {joints}")
        for kind, items in (("point", self.points), ("axis", self.axes)):
            names = [i.name for i in items]
            dup = {n for n in names if names.count(n) > 1}
            if dup:
                raise ValueError(f"duplicate {kind} names: {sorted(dup)}")
        points, axes = {p.name for p in self.points}, {a.name for a in self.axes}
        for op in self.operations:
            _need(op.point, points, f"operation {op.operation}: point")
            for field in ("approach_axis", "attach_axis", "parallel_axis"):
                _need(getattr(op, field), axes, f"operation {op.operation}: {field}")
        for fn in self.functions:
            _need(fn.point, points, f"function {fn.function}: point")
            _need(fn.axis, axes, f"function {fn.function}: axis")
        if any(a > b for a, b in zip(self.bbox_min, self.bbox_max)):
            raise ValueError("bbox_min must not exceed bbox_max")
        return self

    def point(self, name: str) -> KeyPoint:
        for p in self.points:
            if p.name == name:
                return p
        raise KeyError(f"{self.family}: no point {name!r}; points: {', '.join(p.name for p in self.points)}")

    def axis(self, name: str) -> KeyAxis:
        for a in self.axes:
            if a.name == name:
                return a
        raise KeyError(f"{self.family}: no axis {name!r}; axes: {', '.join(a.name for a in self.axes)}")

    def articulation_for(self, part: str | None) -> Articulation | None:
        """The joint that moves `part` (a point's or axis's part): its own where it has one, else the main one."""
        for a in self.part_articulations:
            if part is not None and a.part == part:
                return a
        return self.articulation

    def operations_of(self, operation: str) -> list[OperationAnnotation]:
        return [o for o in self.operations if o.operation == operation]


def _need(name: str, known: set[str], what: str) -> None:
    if name not in known:
        raise ValueError(f"{what} {name!r} is not defined (known: {sorted(known)})")


def validation_details(exc: ValidationError) -> str:
    """pydantic's errors as one line: `field.path: message; ...` (shared by every file loader)."""
    return "; ".join(f"{'.'.join(str(x) for x in err['loc']) or '<root>'}: {err['msg']}" for err in exc.errors())


def load_annotations(path: Path) -> ObjectAnnotations:
    """Read and validate an annotation file (YAML or JSON); errors name the file and the offending field."""
    path = Path(path)
    try:
        raw = yaml.safe_load(path.read_text())
    except yaml.YAMLError as exc:
        raise AnnotationError(f"{path}: not valid YAML/JSON: {exc}") from None
    try:
        return ObjectAnnotations.model_validate(raw)
    except ValidationError as exc:
        raise AnnotationError(f"{path}: {validation_details(exc)}") from None


def save_annotations(ann: ObjectAnnotations, path: Path) -> None:
    Path(path).write_text(yaml.safe_dump(ann.model_dump(mode="json"), sort_keys=False))
