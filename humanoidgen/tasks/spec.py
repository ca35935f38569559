"""Task specifications: which objects go where, how their layout is randomized, and what counts as success.

A `TaskSpec` is plain data (one YAML file per task under `specs/`), validated strictly by pydantic: unknown
fields, unknown object types/models and predicates that name absent objects are errors that name the field.
Objects may carry `aliases` (other names plans use for them); `targets` are the objects' target poses for the
paper's action="target" (schema and checks in targets.py).
"""

from __future__ import annotations

import math
import re
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import AfterValidator, Field, field_validator, model_validator

from humanoidgen.objects import library, stand_ins
from humanoidgen.tasks.bounds import (
    AXES as _AXES,
    MAX_OFFSET_M,
    MAX_POSITION_M,
    MAX_SIZE_M,
    MAX_TIME_LIMIT_S,
    MAX_YAW_DEG,
    Strict as _Strict,
    bad as _bad,
    check_number as _check_number,
)
from humanoidgen.tasks.predicates import Predicate
from humanoidgen.tasks.targets import TargetSpec, check_targets

SAMPLE_ATTEMPTS = 200  # layouts redrawn (same rng stream) until no two footprints overlap
# An alias is another name a plan may use for one object ("rectangular_cube" for cube[0]); it must not end in a digit
# ("cube0" already means cube[0]) nor be a type name.
_ALIAS = re.compile(r"^[a-z][a-z_]*[a-z]$")
# Predicate fields that are lengths (metres), and the ones that are positions; the rest (angles, openness)
# carry their own bounds in predicates.py.
_PREDICATE_LENGTHS = {"xy_tol", "z_tol", "z_gap", "margin", "base_gap", "min_height", "tol"}
_PREDICATE_POSITIONS = {"target_xy"}
_MODEL_TARGET = re.compile(r"^([a-z_]+)(?:\[(\d+)\])?$")  # a family ("cup") or one object of it ("cup[0]")


def _check_predicate(pred: Any) -> Any:
    """Every number of a success predicate finite, lengths within MAX_SIZE_M, positions within MAX_POSITION_M
    (predicates.py bounds only their signs)."""
    for name, value in pred:
        what = f"{pred.type}.{name}"
        if name in _PREDICATE_POSITIONS:
            for axis, v in zip(_AXES, value):
                _check_number(f"{what}.{axis}", v, MAX_POSITION_M, "m")
        elif name in _PREDICATE_LENGTHS and value is not None:
            _check_number(what, value, MAX_SIZE_M, "m")
        elif isinstance(value, float):
            _check_number(what, value, math.inf, "")
    return pred


class ObjectSpec(_Strict):
    """One object of the task, at its default (un-randomized) pose."""

    type: str
    type_id: int = Field(default=0, ge=0)
    pos: tuple[float, float] | tuple[float, float, float]  # a missing z puts the object on the table
    yaw_deg: float = Field(default=0.0, ge=-MAX_YAW_DEG, le=MAX_YAW_DEG)
    openness: float | None = Field(default=None, ge=0.0, le=1.0)
    # Index of an earlier object this one rides with (contents of a cup): it takes that object's position
    # offset and turns with it about its centre, so randomization never pulls contents out of their container.
    follow: int | None = Field(default=None, ge=0)
    # Other names plans may use for this object (the paper's task descriptions say "rectangular_cube",
    # "target_cube"); the scene resolves them (tasks/scene.py).
    aliases: list[str] = Field(default_factory=list, max_length=8)

    @field_validator("aliases")
    @classmethod
    def _alias_names(cls, v: list[str]) -> list[str]:
        for a in v:
            if not _ALIAS.match(a):
                raise _bad(f"alias {a!r} must be lowercase letters and '_' (no digits at the end: 'cube0' already "
                           "names cube[0])")
            if a in library.families():
                raise _bad(f"alias {a!r} is an object type; choose another name")
        return v

    @field_validator("pos", mode="before")
    @classmethod
    def _sane_pos(cls, v: Any) -> Any:
        # Before the tuple union: a NaN would otherwise be reported once per union branch.
        if isinstance(v, (list, tuple)):
            for axis, x in zip(_AXES, v):
                _check_number(axis, x, MAX_POSITION_M, "m")
        return v

    @field_validator("type")
    @classmethod
    def _known_type(cls, v: str) -> str:
        fams = library.families()
        if v not in fams:
            raise ValueError(f"unknown object type {v!r}; valid types: {', '.join(sorted(fams))}")
        return v

    @model_validator(mode="after")
    def _known_model(self) -> ObjectSpec:
        ids = [m.type_id for m in library.family(self.type).models()]
        if self.type_id not in ids:
            raise ValueError(f"type_id {self.type_id} is not a {self.type} model; valid type_ids: {ids}")
        if self.openness is not None and not library.family(self.type).articulated:
            raise ValueError(f"openness applies only to articulated types, not {self.type!r}")
        return self

    @property
    def articulated(self) -> bool:
        return library.family(self.type).articulated


class Randomization(_Strict):
    """The paper's randomization: offsets added to each object's default position and yaw."""

    position: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)  # [x1, x2, y1, y2] metres
    yaw_deg: tuple[float, float] = (0.0, 0.0)
    openness: tuple[float, float] | None = None  # replaces articulated objects' openness when set
    per_object: list[int] | None = None  # indices of the objects to randomize (None: all)

    @field_validator("position")
    @classmethod
    def _sort_position(cls, v: tuple[float, ...]) -> tuple[float, ...]:
        # The paper's table writes some ranges high-to-low ([0.18, -0.18]); they mean the same box.
        for name, x in zip(("x1", "x2", "y1", "y2"), v):
            _check_number(name, x, MAX_OFFSET_M, "m")
        x1, x2, y1, y2 = v
        return (min(x1, x2), max(x1, x2), min(y1, y2), max(y1, y2))

    @field_validator("yaw_deg")
    @classmethod
    def _sort_yaw(cls, v: tuple[float, float]) -> tuple[float, float]:
        for x in v:
            _check_number("yaw", x, MAX_YAW_DEG, "deg")
        return (min(v), max(v))

    @field_validator("openness")
    @classmethod
    def _openness_range(cls, v: tuple[float, float] | None) -> tuple[float, float] | None:
        if v is None:
            return v
        lo, hi = min(v), max(v)
        if lo < 0.0 or hi > 1.0:
            raise ValueError(f"openness range must lie in [0, 1], got {list(v)}")
        return (lo, hi)


class ResolvedObject(_Strict):
    """An object's pose for one episode: what `build_scene` places."""

    type: str
    type_id: int
    pos: tuple[float, float] | tuple[float, float, float]
    yaw: float  # radians
    openness: float | None = None


class TaskSpec(_Strict):
    name: str = Field(pattern=r"^[a-z0-9_]+$")
    description: str = Field(min_length=1)
    arms: Literal["single", "bimanual"]
    horizon: Literal["short", "long"]
    objects: list[ObjectSpec] = Field(min_length=1)
    randomization: Randomization = Field(default_factory=Randomization)
    success: list[Annotated[Predicate, AfterValidator(_check_predicate)]] = Field(min_length=1)  # all must hold
    # The episode's horizon: where a policy's episode is cut (`envs`). A plan's commands get a budget of
    # episodes.replay.PLAN_TIME_FACTOR times it (demonstrations are slower than the horizon asks of a policy).
    time_limit_s: float = Field(default=30.0, gt=0, le=MAX_TIME_LIMIT_S)
    # control steps; None: time_limit_s at the control rate
    max_steps: int | None = Field(default=None, gt=0, le=round(MAX_TIME_LIMIT_S * 50))
    plan: str | None = None  # a reference plan (.py) next to the YAML, written separately
    # Families ("cup") or objects ("bottle[1]") whose model each episode draws from the family's imported models
    # (hgen ... --randomize-models): the draw comes from the episode's seed on a stream of its own, once per
    # episode, so the poses drawn are those without it and pinning the drawn models (--model bottle[1]=NAME)
    # gives the same episode.
    randomize_models: list[str] = Field(default_factory=list, max_length=16)
    # Named target poses of objects, for the paper's action="target" / "target1" / "target2" (tasks/targets.py).
    targets: list[TargetSpec] = Field(default_factory=list, max_length=64)

    @field_validator("randomize_models")
    @classmethod
    def _model_families(cls, v: list[str]) -> list[str]:
        unknown = sorted({r for r in v if _MODEL_TARGET.match(r) is None
                          or _MODEL_TARGET.match(r).group(1) not in library.families()})
        if unknown:
            raise ValueError(f"randomize_models: unknown families {unknown}")
        return v

    @model_validator(mode="after")
    def _references(self) -> TaskSpec:
        n = len(self.objects)
        for i, o in enumerate(self.objects):
            if o.follow is not None and o.follow >= i:
                raise ValueError(f"objects.{i}.follow: must name an earlier object (index < {i}), got {o.follow}")
        for i in self.randomization.per_object or []:
            if not 0 <= i < n:
                raise ValueError(f"randomization.per_object: index {i} out of range (there are {n} objects)")
        counts: dict[str, int] = {}
        for o in self.objects:
            counts[o.type] = counts.get(o.type, 0) + 1
        present = ", ".join(f"{t}[0..{c - 1}]" for t, c in counts.items())
        for k, pred in enumerate(self.success):
            for ref in pred.refs():
                if ref.id >= counts.get(ref.type, 0):
                    raise ValueError(f"success.{k} ({pred.type}): no object {ref}; the task has {present}")
        check_targets(self.targets, self.objects, present)
        self._check_aliases()
        if self.plan is not None and not self.plan.endswith(".py"):
            raise ValueError(f"plan: expected a .py file name, got {self.plan!r}")
        return self

    def _check_aliases(self) -> None:
        owner: dict[str, int] = {}
        for i, o in enumerate(self.objects):
            for a in o.aliases:
                if a in owner:
                    raise _bad(f"objects.{i}.aliases: {a!r} already names objects.{owner[a]}; an alias names one object")
                owner[a] = i

    def aliases(self) -> dict[str, tuple[str, int]]:
        """alias -> (type, obj_id) of the object it names."""
        out: dict[str, tuple[str, int]] = {}
        counts: dict[str, int] = {}
        for o in self.objects:
            for a in o.aliases:
                out[a] = (o.type, counts.get(o.type, 0))
            counts[o.type] = counts.get(o.type, 0) + 1
        return out

    def step_limit(self, control_hz: float = 50.0) -> int:
        return self.max_steps if self.max_steps is not None else math.ceil(self.time_limit_s * control_hz)

    def default_layout(self) -> list[ResolvedObject]:
        return [ResolvedObject(type=o.type, type_id=o.type_id, pos=o.pos, yaw=math.radians(o.yaw_deg),
                               openness=o.openness) for o in self.objects]

    def sample_layout(self, seed: int | None) -> list[ResolvedObject]:
        """The objects' poses for episode `seed` (deterministic per seed; None: the default layout).
        Draws are repeated until no two footprints overlap."""
        if seed is None:
            return self.default_layout()
        from humanoidgen.tasks.scene import overlapping_pairs

        rng = np.random.default_rng(seed)
        models = self._draw_models(seed)
        for _ in range(SAMPLE_ATTEMPTS):
            layout = self._with_drawn(self._draw(rng), models)
            if not overlapping_pairs(layout, skip=self._follow_pairs()):
                return layout
        raise ValueError(f"{self.name}: no overlap-free layout in {SAMPLE_ATTEMPTS} draws for seed {seed}")

    def _follow_pairs(self) -> set[tuple[int, int]]:
        return {(o.follow, i) for i, o in enumerate(self.objects) if o.follow is not None}

    def _draw(self, rng: np.random.Generator) -> list[ResolvedObject]:
        r = self.randomization
        chosen = set(range(len(self.objects)) if r.per_object is None else r.per_object)
        x1, x2, y1, y2 = r.position
        offsets: list[tuple[float, float, float]] = []
        out: list[ResolvedObject] = []
        for i, o in enumerate(self.objects):
            # Always draw, so one object's draws don't depend on whether another is randomized.
            d = (rng.uniform(x1, x2), rng.uniform(y1, y2), math.radians(rng.uniform(*r.yaw_deg)))
            op = rng.uniform(*r.openness) if r.openness is not None else None
            if o.follow is not None:
                parent = self.objects[o.follow]
                pdx, pdy, pyaw = offsets[o.follow]
                rel = np.subtract(o.pos[:2], parent.pos[:2])
                c, s = math.cos(pyaw), math.sin(pyaw)
                xy = (parent.pos[0] + pdx + c * rel[0] - s * rel[1], parent.pos[1] + pdy + s * rel[0] + c * rel[1])
                d = (xy[0] - o.pos[0], xy[1] - o.pos[1], pyaw)
            elif i not in chosen:
                d = (0.0, 0.0, 0.0)
            offsets.append(d)
            pos = (o.pos[0] + d[0], o.pos[1] + d[1], *o.pos[2:])
            openness = o.openness
            if o.articulated and op is not None and (i in chosen):
                openness = float(op)
            out.append(ResolvedObject(type=o.type, type_id=o.type_id, pos=pos,
                                      yaw=math.radians(o.yaw_deg) + d[2], openness=openness))
        return out

    def _with_drawn(self, layout: list[ResolvedObject], models: dict[int, int]) -> list[ResolvedObject]:
        """The layout on the drawn models; contents (`follow`) move with their container's storage point."""
        from humanoidgen.tasks.contents import moved, storage_shift

        out = [r.model_copy(update={"type_id": models[i]}) if i in models else r for i, r in enumerate(layout)]
        for i, o in enumerate(self.objects):
            p = o.follow
            if p is not None and p in models:
                shift = storage_shift(self.objects[p].type, self.objects[p].type_id, models[p])
                if shift is not None:
                    out[i] = out[i].model_copy(update={"pos": moved(out[i].pos, out[p].yaw, shift)})
        return out

    def _draw_models(self, seed: int) -> dict[int, int]:
        """Object index -> the type_id drawn for it, for each object that `randomize_models` names (by its family
        or by itself), from the family's models that may stand in for it (`stand_ins.drawable_models`)."""
        if not self.randomize_models:
            return {}
        mrng = np.random.default_rng([int(seed) % 2**63, 0x5EED])
        out, counts = {}, {}
        for i, o in enumerate(self.objects):
            k = counts[o.type] = counts.get(o.type, -1) + 1
            if o.type in self.randomize_models or f"{o.type}[{k}]" in self.randomize_models:
                ids = [m.type_id for m in stand_ins.drawable_models(o.type, like=o.type_id)]
                if ids:
                    out[i] = int(mrng.choice(ids))
        return out
