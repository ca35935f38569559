"""Per-object target poses of a task: where the paper's `action="target"` ("target1", "target2") brings an object.

The paper's API moves a held object to its "target" pose, a pose the task defines for that object (the place above
the bowl, a stacking spot, the hand-over pose). A task lists them under `targets:`:

    targets:
      - {object: "cube[0]", pos: [-0.33, 0.0, 0.025], random: [-0.005, 0.005, -0.005, 0.005]}
      - {object: "cube[1]", relative_to: "cube[0]", offset: [0, 0, 0.045]}
      - {object: "cube[2]", relative_to: ["cube[0]", "cube[1]"], offset: [0, 0, 0.047]}   # above their middle
      - {object: "bottle[0]", relative_to: "bottle[0]", anchor: initial, offset: [0, 0, 0.10]}
      - {object: "cube[0]", hand: right, pos: [-0.34, 0.03, 0.045], note: "hand-over pose"}

- `pos` is a position in the reference workspace (the held object's centre; the world of the robot the specs were
  written for), placed for the robot at hand by its robot file's `workspace` (robots/workspace.py: the identity for
  the H1-2; the G1's moves a mid-air hand-over out and down to where its shorter arms meet); `random` adds an
  offset drawn per episode seed.
- `relative_to` (one object or several: their mean) + `offset` (world frame) follows the reference object: it is
  evaluated when the plan asks (`anchor: current`, default), or at the episode's start (`anchor: initial`, e.g. "10
  cm above where the bottle stood"). `point` uses a key point of the reference instead of its centre.
- `hand` limits a target to the hand holding the object (a hand-over: the right hand's "target" is the hand-over
  pose, the left hand's the final place); a target without `hand` applies to both.
- `push` (articulated objects: a lid, a laptop screen, a drawer front) defines the paper's push pair at once:
  "target1" is the pre-push pose (the index fingertip just off the part at the push point) and "target2" the
  push itself, which moves the part along its joint to openness `to` (planning/push_actions.py executes it):

    targets:
      - {object: "box[0]", push: {point: lid_front, face: inner, to: 0.97, aim: forward, inset: [[0.3, 0.01], [0.97, 0.06]]}}
      - {object: "laptop[0]", push: {point: screen_edge, face: outer, to: 0.0, aim: [0.5, 0, -0.866]}}

  The fingertip's contact point is `point` + inset * axes[0] (in along the part, e.g. "edge_in") + depth * axes[1]
  (the part's normal, e.g. "lid_in": into it from its outer face); `face: inner` puts the fingertip on the part's
  inner side (under a lid: lifting it), `outer` on its outer face (pressing it shut). `inset` is a number or
  [openness, metres] pairs (linear between them: the contact moves in along a rising lid). The fingertip points
  within `aim_cone_deg` of `aim` (an object axis name, or a world direction); `palm_across` keeps the palm across
  an object axis (70-110 deg). The push goes in stages of at most `step` openness; target1 stands `standoff` off
  the contact (inner: back against `aim`, to slide in under the edge; outer: out of the outer face).

Positions are those of the object's centre, at the height where the plan should let go (the paper: "release it
slightly above the target position").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Any, Literal

import numpy as np
from pydantic import BeforeValidator, Field, field_validator, model_validator

from humanoidgen.objects import library
from humanoidgen.sim.layout import OPERABLE_RANGE, ROBOT, TABLE_TOP_Z
from humanoidgen.tasks.bounds import MAX_OFFSET_M, MAX_POSITION_M, Strict, bad, check_number, check_vector
from humanoidgen.tasks.predicates import ObjRef, Ref

if TYPE_CHECKING:
    from humanoidgen.tasks.spec import ObjectSpec

TARGET_NAMES = ("target", "target1", "target2")
MAX_TARGET_HEIGHT_M = 0.6  # above the table: higher is out of both arms' reach
# A target relative to another object is checked at the default layout; randomization may move the reference a few
# cm, so the check allows that much outside the operable range.
RELATIVE_REACH_MARGIN_M = 0.04
RANDOM_STREAM = 0x7A46  # the targets' random offsets come from their own stream, so layouts stay as they were


def _as_list(v: Any) -> Any:
    return [v] if isinstance(v, (str, dict)) else v


PUSH_NAMES = ("target1", "target2")  # a push target defines both: the pre-push pose and the push
MAX_PUSH_OFFSET_M = 0.2  # insets, depths and standoffs: a fingertip's contact on a part is centimetres off its point


class PushSpec(Strict):
    """How a fingertip pushes an articulated object's part to an openness (see the module docstring)."""

    point: str  # a key point on the moving part
    to: float = Field(ge=0.0, le=1.0)  # the openness the push brings the part to
    face: Literal["inner", "outer"]
    axes: tuple[str, str] = ("edge_in", "lid_in")  # (in along the part, into the part from its outer face)
    inset: float | list[tuple[float, float]] = 0.0  # metres along axes[0]; or [openness, metres] pairs
    depth: float = Field(default=0.012, ge=0.0, le=0.05)  # fingertip centre from the point, along axes[1]
    aim: str | tuple[float, float, float]  # the fingertip points this way: an object axis, or a world direction
    aim_cone_deg: float = Field(default=40.0, gt=0.0, le=90.0)
    palm_across: str | None = None  # an object axis the palm stays across (70-110 deg), e.g. "up"
    step: float = Field(default=0.15, ge=0.02, le=0.5)  # openness per stage
    standoff: float = Field(default=0.05, ge=0.0, le=0.15)  # target1: metres off the contact point

    @field_validator("inset")
    @classmethod
    def _inset_table(cls, v: Any) -> Any:
        pairs = [(0.0, v)] if isinstance(v, (int, float)) else v
        if not pairs:
            raise bad("inset: give a number (metres) or [openness, metres] pairs")
        for o, m in pairs:
            if not 0.0 <= o <= 1.0:
                raise bad(f"inset: openness {o:g} is not in [0, 1]")
            check_number("inset", m, MAX_PUSH_OFFSET_M, "m")
        if not isinstance(v, (int, float)):
            return sorted(v)
        return v

    @field_validator("aim")
    @classmethod
    def _aim_direction(cls, v: Any) -> Any:
        if isinstance(v, tuple):
            if not all(math.isfinite(x) for x in v) or math.hypot(*v) < 1e-6:
                raise bad(f"aim: {list(v)} is not a direction (give a non-zero world vector or an object axis name)")
        return v

    def inset_at(self, openness: float) -> float:
        """The contact's inset (m along axes[0]) with the part at `openness`: linear between the table's pairs."""
        if isinstance(self.inset, (int, float)):
            return float(self.inset)
        os_, ms = zip(*self.inset)
        return float(np.interp(openness, os_, ms))

    def label(self) -> str:
        how = (f"under {self.point} (the part's inner face) lifts" if self.face == "inner"
               else f"on the outer face at {self.point} presses")
        return f"push: the index fingertip {how} it to openness {self.to:g}, in stages"


class TargetSpec(Strict):
    """One named target pose of one object (see the module docstring)."""

    object: Ref
    name: Literal["target", "target1", "target2"] = "target"
    hand: Literal["left", "right"] | None = None
    pos: tuple[float, float, float] | None = None
    random: tuple[float, float, float, float] | None = None  # [x1, x2, y1, y2] metres, with `pos` only
    relative_to: Annotated[list[Ref], BeforeValidator(_as_list)] | None = None
    point: str | None = None  # a key point of each reference object (default: its centre)
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)  # world frame, with `relative_to` only
    anchor: Literal["current", "initial"] = "current"
    push: PushSpec | None = None  # an articulated part pushed by a fingertip: defines target1 and target2
    # Where the held object's own z axis points at the target (a world direction, e.g. [0, -1, 0]: a block laid along
    # y for a hand-over); the hand turns it there. Default: the object keeps its tilt.
    up: tuple[float, float, float] | None = None
    note: str | None = Field(default=None, max_length=200)  # what the target is for, shown in the prompts

    @field_validator("pos", "offset", mode="before")
    @classmethod
    def _finite_vectors(cls, v: Any, info) -> Any:
        return check_vector("", v, MAX_POSITION_M if info.field_name == "pos" else MAX_OFFSET_M)

    @field_validator("up", mode="before")
    @classmethod
    def _finite_up(cls, v: Any) -> Any:
        return check_vector("", v, MAX_POSITION_M)

    @field_validator("up")
    @classmethod
    def _unit_up(cls, v: tuple[float, float, float] | None) -> tuple[float, float, float] | None:
        if v is None:
            return v
        n = math.sqrt(sum(x * x for x in v))
        if n < 1e-6:
            raise bad("up: give a direction (e.g. [0, -1, 0]), not the zero vector")
        return (v[0] / n, v[1] / n, v[2] / n)

    @field_validator("random")
    @classmethod
    def _sort_random(cls, v: tuple[float, ...] | None) -> tuple[float, ...] | None:
        if v is None:
            return v
        for name, x in zip(("x1", "x2", "y1", "y2"), v):
            check_number(name, x, MAX_OFFSET_M, "m")
        x1, x2, y1, y2 = v
        return (min(x1, x2), max(x1, x2), min(y1, y2), max(y1, y2))

    @field_validator("relative_to")
    @classmethod
    def _some_reference(cls, v: list[ObjRef] | None) -> list[ObjRef] | None:
        if v is not None and not v:
            raise bad("relative_to: give at least one object, e.g. 'cube[0]'")
        return v

    @model_validator(mode="after")
    def _one_kind(self) -> TargetSpec:
        if self.push is not None:
            others = [f for f in ("pos", "random", "relative_to", "point", "hand", "up") if getattr(self, f) is not None]
            if others or any(self.offset) or self.anchor != "current":
                raise bad(f"a push target takes only object, push and note, not {', '.join(others or ['offset/anchor'])}")
            if self.name == "target2":  # (a dumped spec carries the default "target")
                raise bad("a push target defines target1 (the pre-push pose) and target2 (the push) together: "
                          "leave out name")
            return self
        if (self.pos is None) == (self.relative_to is None):
            raise bad("give either pos (a world position) or relative_to (+ offset), not both or neither "
                      "(or push, for an articulated part)")
        if self.pos is not None:
            for field, set_ in (("point", self.point is not None), ("anchor", self.anchor != "current"),
                                ("offset", any(self.offset))):
                if set_:
                    raise bad(f"{field} applies only to relative_to targets; with pos, put the offset into pos")
        else:
            if self.random is not None:
                raise bad("random applies only to pos targets; a relative_to target moves with its reference")
            if self.object in self.relative_to and self.anchor != "initial":
                raise bad(f"relative_to {self.object} is the object itself: add anchor: initial (relative to where "
                          "it stood at the start), or the target would move with the object")
        return self

    def names(self) -> tuple[str, ...]:
        """The action names this target answers: a push target both target1 and target2."""
        return PUSH_NAMES if self.push is not None else (self.name,)

    def labels(self) -> dict[str, str]:
        """How the prompts show the target's definition, by action name."""
        if self.push is None:
            return {self.name: self.label()}
        note = f" ({self.note})" if self.note else ""
        return {"target1": f"pre-push pose: the index fingertip just off {self.push.point}, finger extended{note}",
                "target2": self.push.label() + note}

    def label(self) -> str:
        """How the prompts show the target's definition."""
        if self.push is not None:
            return self.push.label() + (f" ({self.note})" if self.note else "")
        if self.pos is not None:
            text = f"world {list(self.pos)}" + (f" + random offset in {list(self.random)}" if self.random else "")
        else:
            refs = " and ".join(str(r) for r in self.relative_to)
            of = f"{self.point} of " if self.point else ""
            mid = "the middle of " if len(self.relative_to) > 1 else ""
            when = " where it stood at the start" if self.anchor == "initial" else ""
            text = f"{mid}{of}{refs}{when} + {list(self.offset)}"
        if self.up is not None:
            text += f", its z axis turned to {[round(x, 3) for x in self.up]}"
        return text + (f" ({self.note})" if self.note else "")


# -- checks against the task's objects (called from TaskSpec's validator) -----------------------------------------
def _default_point(obj: ObjectSpec, point: str | None) -> np.ndarray | None:
    """Where a key point of an object lies at the default layout (None for points on a moving part)."""
    ann = library.annotations(obj.type, obj.type_id)
    z = obj.pos[2] if len(obj.pos) > 2 else TABLE_TOP_Z - ann.bbox_min[2]  # resting on the table
    centre = np.array([obj.pos[0], obj.pos[1], z])
    if point is None or point == "center":
        return centre
    kp = ann.point(point)
    if kp.part is not None:
        return None
    c, s = math.cos(math.radians(obj.yaw_deg)), math.sin(math.radians(obj.yaw_deg))
    x, y, pz = kp.position
    return centre + np.array([c * x - s * y, s * x + c * y, pz])


def _out_of_reach(p: np.ndarray, hand: str | None, margin: float) -> str | None:
    sides = [hand] if hand else ["left", "right"]
    xs = OPERABLE_RANGE["left"].x
    y_lo = min(OPERABLE_RANGE[s].y[0] for s in sides)
    y_hi = max(OPERABLE_RANGE[s].y[1] for s in sides)
    who = f"the {hand} hand's" if hand else "the hands'"
    if not (xs[0] - margin <= p[0] <= xs[1] + margin and y_lo - margin <= p[1] <= y_hi + margin):
        return (f"({p[0]:.3f}, {p[1]:.3f}) is outside {who} operable range x in [{xs[0]}, {xs[1]}], "
                f"y in [{y_lo}, {y_hi}]")
    if not TABLE_TOP_Z <= p[2] <= TABLE_TOP_Z + MAX_TARGET_HEIGHT_M:
        return f"height {p[2]:.3f} m is not between the table top and {MAX_TARGET_HEIGHT_M} m above it"
    return None


def check_targets(targets: list[TargetSpec], objects: list[ObjectSpec], present: str) -> None:
    """References exist, points exist, names are unique, and every target lies within reach (at the default
    layout). Raises a custom error naming `targets.<k>.<field>`."""
    by_ref: dict[str, ObjectSpec] = {}
    counts: dict[str, int] = {}
    for o in objects:
        by_ref[f"{o.type}[{counts.get(o.type, 0)}]"] = o
        counts[o.type] = counts.get(o.type, 0) + 1
    seen: set[tuple[str, str, str | None]] = set()
    for k, t in enumerate(targets):
        where = f"targets.{k}"
        refs = [t.object] + list(t.relative_to or [])
        for field, ref in zip(["object"] + ["relative_to"] * (len(refs) - 1), refs):
            if str(ref) not in by_ref:
                raise bad(f"{where}.{field}: no object {ref}; the task has {present}")
        for name in t.names():
            key = (str(t.object), name, t.hand)
            if key in seen:
                hand = f" for the {t.hand} hand" if t.hand else ""
                raise bad(f"{where}: {t.object} has two '{name}' targets{hand} (a push target is both target1 and "
                          f"target2); give them different names ({', '.join(TARGET_NAMES)}) or hands")
            seen.add(key)
        if t.push is not None:
            _check_push(t.push, by_ref[str(t.object)], f"{where}.push")
            continue
        if t.pos is not None:
            x1, x2, y1, y2 = t.random or (0.0, 0.0, 0.0, 0.0)
            for dx, dy in ((x1, y1), (x1, y2), (x2, y1), (x2, y2)):
                if (why := _out_of_reach(np.add(t.pos, (dx, dy, 0.0)), t.hand, 0.0)) is not None:
                    raise bad(f"{where}.pos: {why}" + (" (with its random offset)" if t.random else ""))
            continue
        points = []
        for ref in t.relative_to:
            obj = by_ref[str(ref)]
            if t.point is not None:
                ann = library.annotations(obj.type, obj.type_id)
                names = [p.name for p in ann.points]
                if t.point not in names and t.point != "center":
                    raise bad(f"{where}.point: {ref} has no key point {t.point!r}; its points: {', '.join(names)}")
            points.append(_default_point(obj, t.point))
        if any(p is None for p in points):
            continue  # a point on a moving part: where it is depends on the openness; checked when used
        p = np.mean(points, axis=0) + np.asarray(t.offset)
        if (why := _out_of_reach(p, t.hand, RELATIVE_REACH_MARGIN_M)) is not None:
            raise bad(f"{where}.offset: at the default layout the target {why}")


def _check_push(push: PushSpec, obj: ObjectSpec, where: str) -> None:
    """The push's point is on the object's moving part and its axes exist."""
    ann = library.annotations(obj.type, obj.type_id)
    if ann.articulation is None:
        raise bad(f"{where}: {obj.type} has no moving part to push; push targets are for lids, screens, drawers")
    points = {p.name: p for p in ann.points}
    if push.point not in points or points[push.point].part is None:
        on_part = [n for n, p in points.items() if p.part is not None]
        raise bad(f"{where}.point: {obj.type} has no key point {push.point!r} on its moving part; those: "
                  f"{', '.join(on_part)}")
    axes = [a.name for a in ann.axes]
    named = [("axes", a) for a in push.axes] + [("aim", push.aim)] * isinstance(push.aim, str)
    named += [("palm_across", push.palm_across)] * (push.palm_across is not None)
    for field, name in named:
        if name not in axes:
            raise bad(f"{where}.{field}: {obj.type} has no axis {name!r}; its axes: {', '.join(axes)}")


# -- an episode's targets ------------------------------------------------------------------------------------------
@dataclass
class Target:
    """A target of one episode: its definition, its drawn random offset and (anchor initial) its start point."""

    spec: TargetSpec
    random_offset: np.ndarray
    initial: np.ndarray | None = None

    def position(self, env) -> np.ndarray:
        """The world position the held object's centre goes to, now."""
        from humanoidgen.objects.queries import get_point_in_env

        s = self.spec
        if s.push is not None:  # where the push starts: its point on the part, now
            return get_point_in_env(env, s.push.point, s.object.type, s.object.id)
        if s.pos is not None:  # a position about the arms' reach: placed in this robot's workspace
            return ROBOT.workspace.point(np.asarray(s.pos, float) + self.random_offset)
        if s.anchor == "initial" and self.initial is not None:
            base = self.initial
        else:
            base = np.mean([get_point_in_env(env, s.point or "center", r.type, r.id) for r in s.relative_to], axis=0)
        return base + np.asarray(s.offset, float)


class SceneTargets:
    """The task's targets for one episode (random offsets drawn from `seed`; anchors read from the settled scene)."""

    def __init__(self, specs: list[TargetSpec], seed: int | None, env) -> None:
        from humanoidgen.objects.queries import get_point_in_env

        rng = np.random.default_rng([RANDOM_STREAM, seed]) if seed is not None else None
        self.targets: list[Target] = []
        for s in specs:
            offset = np.zeros(3)
            if s.random is not None and rng is not None:
                offset[:2] = rng.uniform(s.random[0], s.random[1]), rng.uniform(s.random[2], s.random[3])
            initial = None
            if s.anchor == "initial":
                initial = np.mean([get_point_in_env(env, s.point or "center", r.type, r.id) for r in s.relative_to],
                                  axis=0)
            self.targets.append(Target(s, offset, initial))

    def of(self, type_name: str, obj_id: int) -> list[Target]:
        return [t for t in self.targets if (t.spec.object.type, t.spec.object.id) == (type_name, obj_id)]

    def find(self, type_name: str, obj_id: int, name: str, side: str) -> Target | None:
        """The object's target `name` for the hand `side`: one given for that hand first, else one for both."""
        mine = [t for t in self.of(type_name, obj_id) if name in t.spec.names() and t.spec.hand in (side, None)]
        mine.sort(key=lambda t: t.spec.hand is None)
        return mine[0] if mine else None

    def names(self, type_name: str, obj_id: int, side: str | None = None) -> list[str]:
        """The target names defined for the object (for the hand `side`, if given), for error messages."""
        return sorted({n for t in self.of(type_name, obj_id) if side is None or t.spec.hand in (side, None)
                       for n in t.spec.names()})

    def push(self, type_name: str, obj_id: int) -> Target | None:
        """The object's push target (target1/target2 on an articulated part), if the task defines one."""
        return next((t for t in self.of(type_name, obj_id) if t.spec.push is not None), None)
