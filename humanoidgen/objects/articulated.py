"""Parametric articulated object families: drawer, laptop, box, safe, toaster.

Each family builds its object from box geoms into the object's (fixed) body: the root body holds the static
shell, child bodies "<body>_<part>" hold the moving parts, joints are "<body>_<joint>". The object's frame has
its origin at the centre of its bounding box at openness 0 (closed), +x pointing away from the robot, z up.
Joints carry damping and friction loss so that a part stays where a hand leaves it (no drift under gravity).

`set_openness` / `get_openness` map the annotated articulation joint to openness in [0, 1].
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from humanoidgen.objects.family import ObjectFamily, ObjectModel
from humanoidgen.objects.schema import (
    Articulation,
    FunctionAnnotation,
    KeyAxis,
    KeyPoint,
    ObjectAnnotations,
    OperationAnnotation,
)

__all__ = ["ARTICULATED_FAMILIES", "set_openness", "get_openness", "openness_joint"]

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


def _ax(name: str, direction, part: str | None = None, description: str = "") -> KeyAxis:
    d = np.asarray(direction, float)
    d = d / np.linalg.norm(d)
    return KeyAxis(name=name, direction=tuple(float(v) for v in d), part=part, description=description)


def _op(operation: str, point: str, approach: str, attach: str, parallel: str) -> OperationAnnotation:
    return OperationAnnotation(operation=operation, point=point, approach_axis=approach, attach_axis=attach,
                               parallel_axis=parallel)


_BASIC_AXES = [
    _ax("forward", (1, 0, 0), description="away from the robot"),
    _ax("backward", (-1, 0, 0), description="toward the robot"),
    _ax("left", (0, 1, 0)),
    _ax("right", (0, -1, 0)),
    _ax("up", (0, 0, 1)),
    _ax("down", (0, 0, -1)),
]


class _ArticulatedFamily:
    """Common machinery: models from a parameter table, build from a `_Design`, annotations shifted to the
    bounding-box-centred object frame."""

    name: str = ""
    articulated: bool = True
    _params: dict[int, dict] = {}

    # families implement these two
    def _design(self, p: dict) -> _Design:  # pragma: no cover - abstract
        raise NotImplementedError

    def _annot(self, p: dict, design: _Design) -> _Annot:  # pragma: no cover - abstract
        raise NotImplementedError

    def _p(self, type_id: int) -> dict:
        if type_id not in self._params:
            raise KeyError(f"{self.name}: no type_id {type_id}; known: {sorted(self._params)}")
        return self._params[type_id]

    def models(self) -> list[ObjectModel]:
        return [ObjectModel(family=self.name, type_id=t, description=p["description"], params=dict(p))
                for t, p in sorted(self._params.items())]

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


def _add_geoms(body: mujoco.MjsBody, prefix: str, geoms: list[_Geom], shift: np.ndarray) -> None:
    for g in geoms:
        body.add_geom(name=f"{prefix}_{g.name}", type=mujoco.mjtGeom.mjGEOM_BOX, size=list(g.half),
                      pos=(np.asarray(g.pos, float) + shift).tolist(), rgba=list(g.rgba), mass=g.mass,
                      friction=[1.0, 0.01, 0.001], condim=4)


def _shell(D: float, W: float, H: float, t: float, rgba) -> list[_Geom]:
    """A cabinet shell centred at the origin, open toward -x: bottom, top, back and two sides."""
    return [
        _Geom("bottom", (D / 2, W / 2, t / 2), (0, 0, -H / 2 + t / 2), rgba, 0.3),
        _Geom("top", (D / 2, W / 2, t / 2), (0, 0, H / 2 - t / 2), rgba, 0.3),
        _Geom("back", (t / 2, W / 2 - t, H / 2 - t), (D / 2 - t / 2, 0, 0), rgba, 0.2),
        _Geom("side_left", (D / 2, t / 2, H / 2 - t), (0, W / 2 - t / 2, 0), rgba, 0.2),
        _Geom("side_right", (D / 2, t / 2, H / 2 - t), (0, -(W / 2 - t / 2), 0), rgba, 0.2),
    ]


# -- drawer ---------------------------------------------------------------------------------------------------
class DrawerFamily(_ArticulatedFamily):
    name = "drawer"
    _params = {
        0: dict(description="wooden cabinet with one tall drawer", depth=0.22, width=0.20, height=0.26,
                travel=0.15, rgba=(0.70, 0.55, 0.38, 1.0), drawer_rgba=(0.80, 0.66, 0.48, 1.0)),
        1: dict(description="white cabinet with a deep, tall drawer", depth=0.25, width=0.22, height=0.28,
                travel=0.16, rgba=(0.90, 0.90, 0.88, 1.0), drawer_rgba=(0.55, 0.65, 0.78, 1.0)),
    }
    _T, _GAP, _DT = 0.012, 0.004, 0.008  # shell wall, clearance, drawer wall

    def _geometry(self, p: dict) -> dict:
        D, W, H, t, g, dt = p["depth"], p["width"], p["height"], self._T, self._GAP, self._DT
        dx = D - t - g  # drawer depth
        wy = W / 2 - t - g  # drawer half width
        zb, zt = -H / 2 + t + g, H / 2 - t - g
        return dict(D=D, W=W, H=H, t=t, dt=dt, dx=dx, wy=wy, zb=zb, zt=zt, zc=(zb + zt) / 2, hz=(zt - zb) / 2,
                    xc=-D / 2 + dx / 2, bar_x=-D / 2 - 0.06, bar_h=0.006, bar_z=zt - 0.03)

    def _design(self, p: dict) -> _Design:
        q = self._geometry(p)
        D, dt, dx, wy, zb, zc, hz, xc = q["D"], q["dt"], q["dx"], q["wy"], q["zb"], q["zc"], q["hz"], q["xc"]
        c, dc, metal = p["rgba"], p["drawer_rgba"], (0.25, 0.25, 0.27, 1.0)
        drawer = [
            _Geom("drawer_front", (dt / 2, wy, hz), (-D / 2 + dt / 2, 0, zc), dc, 0.06),
            _Geom("drawer_back", (dt / 2, wy, hz), (-D / 2 + dx - dt / 2, 0, zc), dc, 0.04),
            _Geom("drawer_left", ((dx - 2 * dt) / 2, dt / 2, hz), (xc, wy - dt / 2, zc), dc, 0.04),
            _Geom("drawer_right", ((dx - 2 * dt) / 2, dt / 2, hz), (xc, -(wy - dt / 2), zc), dc, 0.04),
            _Geom("drawer_bottom", ((dx - 2 * dt) / 2, wy - dt, dt / 2), (xc, 0, zb + dt / 2), dc, 0.05),
            # A horizontal bar near the top of the front: the hand hooks it palm forward, fingers down, and
            # the fingers then stay clear of the table.
            # Long posts: the opposed thumb reaches ~5 cm past the bar and must not hit the drawer front.
            _Geom("handle_post_left", (0.027, 0.005, 0.005), (-D / 2 - 0.027, 0.035, q["bar_z"]), metal, 0.01),
            _Geom("handle_post_right", (0.027, 0.005, 0.005), (-D / 2 - 0.027, -0.035, q["bar_z"]), metal, 0.01),
            _Geom("handle_bar", (q["bar_h"], 0.05, q["bar_h"]), (q["bar_x"], 0, q["bar_z"]), metal, 0.02),
        ]
        slide = _Joint("slide", "slide", (-1, 0, 0), (0.0, p["travel"]), damping=8.0, frictionloss=2.0)
        return _Design(_shell(D, q["W"], q["H"], q["t"], c), [_Part("drawer", (0, 0, 0), slide, drawer)])

    def _annot(self, p: dict, design: _Design) -> _Annot:
        q = self._geometry(p)
        bx, zc, bz, h = q["bar_x"], q["zc"], q["bar_z"], q["bar_h"]
        points = [
            _pt("handle", (bx, 0, bz), "drawer", "centre of the handle bar"),
            _pt("handle_upper", (bx, 0, bz + h), "drawer", "top of the handle bar (fingers hook over it)"),
            _pt("handle_lower", (bx, 0, bz - h), "drawer", "bottom of the handle bar (fingers from below)"),
            _pt("front", (-q["D"] / 2, q["wy"] / 2, zc), "drawer", "front face beside the handle"),
            _pt("storage", (q["xc"], 0, q["zb"] + q["dt"] + 0.005), "drawer", "inside the drawer"),
            # The paper's "articulated_object_head": where its plans measure a drawer from ('move' with
            # relative_obj_name="drawer" puts things at head + relative_p, e.g. 8 cm in and 10 cm up to drop in).
            _pt("head", (-q["D"] / 2, 0, bz), "drawer", "front of the drawer at the handle's height"),
        ]
        axes = _BASIC_AXES + [_ax("opening", (0, 0, 1), "drawer", "out of the drawer's opening")]
        ops = [
            _op("grasp", "handle_upper", "forward", "down", "left"),
            _op("grasp", "handle_lower", "forward", "up", "left"),
            _op("pull", "handle", "forward", "down", "left"),
            _op("push", "front", "forward", "down", "left"),
        ]
        return _Annot(p["description"], points, axes, ops,
                      [FunctionAnnotation(function="storage", point="storage", axis="opening")],
                      Articulation(joint="slide", closed=0.0, open=p["travel"]))


# -- laptop ---------------------------------------------------------------------------------------------------
class LaptopFamily(_ArticulatedFamily):
    name = "laptop"
    GRIP_DEPTH = 0.015
    _params = {
        0: dict(description="grey 13-inch laptop", depth=0.20, width=0.21, base_h=0.016, screen_t=0.008,
                open_deg=110.0, rgba=(0.55, 0.57, 0.6, 1.0), screen_rgba=(0.2, 0.2, 0.22, 1.0)),
        1: dict(description="black 15-inch laptop", depth=0.22, width=0.22, base_h=0.02, screen_t=0.01,
                open_deg=110.0, rgba=(0.12, 0.12, 0.13, 1.0), screen_rgba=(0.08, 0.08, 0.1, 1.0)),
    }

    def _design(self, p: dict) -> _Design:
        D, W, hb, ts = p["depth"], p["width"], p["base_h"], p["screen_t"]
        base = [_Geom("base", (D / 2, W / 2, hb / 2), (0, 0, hb / 2), p["rgba"], 0.8)]
        screen = [_Geom("screen", (D / 2, W / 2, ts / 2), (-D / 2, 0, ts / 2), p["screen_rgba"], 0.25)]
        hinge = _Joint("hinge", "hinge", (0, 1, 0), (0.0, p["open_deg"] * _DEG), damping=0.3, frictionloss=0.6)
        return _Design(base, [_Part("screen", (D / 2, 0, hb), hinge, screen)])

    def _annot(self, p: dict, design: _Design) -> _Annot:
        D, hb, ts = p["depth"], p["base_h"], p["screen_t"]
        points = [
            _pt("screen_edge", (-D, 0, ts / 2), "screen", "middle of the screen's top edge"),
            # Where a grasp over the top edge centres: GRIP_DEPTH in from the edge, so the fingers wrap the faces.
            _pt("screen_grip", (-D + self.GRIP_DEPTH, 0, ts / 2), "screen", "a grasp over the top edge holds it here"),
            _pt("screen_back", (-0.85 * D, 0, ts), "screen", "lid's outer face near the top edge"),
            _pt("screen_center", (-D / 2, 0, 0), "screen", "centre of the display"),
            _pt("keyboard", (0, 0, hb), None, "centre of the keyboard"),
        ]
        axes = _BASIC_AXES + [
            _ax("edge_in", (1, 0, 0), "screen", "from the top edge toward the hinge"),
            _ax("lid_in", (0, 0, -1), "screen", "into the lid from its outer face; the display's normal"),
            _ax("hinge", (0, 1, 0), "screen", "the hinge axis"),
        ]
        ops = [
            _op("flip", "screen_edge", "edge_in", "lid_in", "hinge"),
            # The hand over the top edge, palm on it, fingers down one face and the thumb down the other (as the
            # box lid's tab is grasped).
            _op("grasp", "screen_grip", "edge_in", "lid_in", "hinge"),
            _op("pinch", "screen_edge", "edge_in", "lid_in", "hinge"),
            _op("push", "screen_back", "lid_in", "edge_in", "hinge"),
        ]
        fns = [FunctionAnnotation(function="display", point="screen_center", axis="lid_in"),
               FunctionAnnotation(function="typing", point="keyboard", axis="up")]
        return _Annot(p["description"], points, axes, ops, fns,
                      Articulation(joint="hinge", closed=0.0, open=p["open_deg"] * _DEG))


# -- box with a hinged lid ------------------------------------------------------------------------------------
class BoxFamily(_ArticulatedFamily):
    name = "box"
    _params = {
        0: dict(description="small red box with a hinged lid", depth=0.14, width=0.16, height=0.08,
                open_deg=100.0, rgba=(0.75, 0.22, 0.18, 1.0), lid_rgba=(0.85, 0.35, 0.25, 1.0)),
        # A free-running hinge: the lid stays up from ~65 deg (openness 0.65) but falls shut by its own weight
        # when let go lower (below ~0.6 within 1-5 s), as a storage box's light lid does; the small box's
        # stiffer hinge holds the lid wherever it is left.
        1: dict(description="blue storage box with a hinged lid that falls shut when let go low",
                depth=0.16, width=0.20, height=0.10, open_deg=100.0, rgba=(0.2, 0.35, 0.7, 1.0),
                lid_rgba=(0.3, 0.45, 0.8, 1.0), hinge_damping=0.05, hinge_friction=0.035),
    }
    _T, _TL, _TAB = 0.008, 0.01, 0.008  # wall, lid thickness, tab half length

    def _design(self, p: dict) -> _Design:
        D, W, H, t, tl, tab = p["depth"], p["width"], p["height"], self._T, self._TL, self._TAB
        c, lc, hw = p["rgba"], p["lid_rgba"], (H - t) / 2
        walls = [
            _Geom("bottom", (D / 2, W / 2, t / 2), (0, 0, t / 2), c, 0.08),
            _Geom("wall_front", (t / 2, W / 2, hw), (-(D / 2 - t / 2), 0, t + hw), c, 0.04),
            _Geom("wall_back", (t / 2, W / 2, hw), (D / 2 - t / 2, 0, t + hw), c, 0.04),
            _Geom("wall_left", (D / 2 - t, t / 2, hw), (0, W / 2 - t / 2, t + hw), c, 0.04),
            _Geom("wall_right", (D / 2 - t, t / 2, hw), (0, -(W / 2 - t / 2), t + hw), c, 0.04),
        ]
        lid = [_Geom("lid", (D / 2, W / 2, tl / 2), (-D / 2, 0, tl / 2), lc, 0.1),
               _Geom("lid_tab", (tab, 0.02, tl / 2 * 0.6), (-D - tab, 0, tl / 2), lc, 0.005)]
        hinge = _Joint("hinge", "hinge", (0, 1, 0), (0.0, p["open_deg"] * _DEG), damping=p.get("hinge_damping", 0.2),
                       frictionloss=p.get("hinge_friction", 0.3))
        return _Design(walls, [_Part("lid", (D / 2, 0, H), hinge, lid)])

    def _annot(self, p: dict, design: _Design) -> _Annot:
        D, tl, tab = p["depth"], self._TL, self._TAB
        points = [
            _pt("lid_front", (-D - 2 * tab, 0, tl / 2), "lid", "tip of the tab on the lid's front edge"),
            # The paper's box lid has two push/flip points (target1: flip up from under the tab; target2: push
            # down on the outer face), like the laptop's screen edge and screen back.
            _pt("lid_top", (-D + 0.015, 0, tl), "lid", "lid's outer face, 1.5 cm in from its front edge"),
            _pt("storage", (0, 0, self._T + 0.005), None, "inside the box, just above its floor"),
        ]
        axes = _BASIC_AXES + [
            _ax("edge_in", (1, 0, 0), "lid", "from the lid's front edge toward the hinge"),
            _ax("lid_in", (0, 0, -1), "lid", "into the lid from its outer face"),
            _ax("hinge", (0, 1, 0), "lid", "the hinge axis"),
            _ax("opening", (0, 0, 1), None, "out of the box's opening"),
        ]
        ops = [_op(o, "lid_front", "edge_in", "lid_in", "hinge") for o in ("grasp", "pinch", "flip")]
        ops.append(_op("push", "lid_top", "lid_in", "edge_in", "hinge"))
        return _Annot(p["description"], points, axes, ops,
                      [FunctionAnnotation(function="storage", point="storage", axis="opening")],
                      Articulation(joint="hinge", closed=0.0, open=p["open_deg"] * _DEG))


# -- safe: cabinet with a hinged door and a knob --------------------------------------------------------------
class SafeFamily(_ArticulatedFamily):
    name = "safe"
    _params = {
        0: dict(description="small grey safe with a dial", depth=0.18, width=0.20, height=0.18,
                open_deg=100.0, rgba=(0.35, 0.37, 0.4, 1.0), door_rgba=(0.45, 0.47, 0.5, 1.0)),
        1: dict(description="dark green safe with a dial", depth=0.20, width=0.20, height=0.22,
                open_deg=100.0, rgba=(0.15, 0.3, 0.2, 1.0), door_rgba=(0.2, 0.38, 0.26, 1.0)),
    }
    _T, _TD = 0.015, 0.015  # wall, door thickness

    def _design(self, p: dict) -> _Design:
        D, W, H, td = p["depth"], p["width"], p["height"], self._TD
        dc, metal = p["door_rgba"], (0.75, 0.75, 0.7, 1.0)
        door = [_Geom("door", (td / 2, W / 2 - 0.002, H / 2 - 0.005), (-td / 2, W / 2, 0), dc, 0.4)]
        knob = [_Geom("knob_shaft", (0.01, 0.006, 0.006), (-0.01, 0, 0), metal, 0.01),
                _Geom("knob_dial", (0.006, 0.018, 0.018), (-0.026, 0, 0), metal, 0.02)]
        door_j = _Joint("hinge", "hinge", (0, 0, 1), (0.0, p["open_deg"] * _DEG), damping=0.3, frictionloss=0.3)
        knob_j = _Joint("knob_hinge", "hinge", (1, 0, 0), (0.0, np.pi), damping=0.01, frictionloss=0.02,
                        armature=0.001)
        return _Design(_shell(D, W, H, self._T, p["rgba"]), [
            _Part("door", (-D / 2, -W / 2, 0), door_j, door),
            _Part("knob", (-td, 0.75 * W, 0), knob_j, knob, parent="door"),
        ])

    def _annot(self, p: dict, design: _Design) -> _Annot:
        W, H, td = p["width"], p["height"], self._TD
        points = [
            _pt("door_edge", (-td, W - 0.015, 0), "door", "door's outer face near its free edge"),
            _pt("knob", (-0.032, 0, 0), "knob", "front of the dial"),
            _pt("storage", (0, 0, -H / 2 + self._T + 0.005), None, "inside the safe, above its floor"),
        ]
        axes = _BASIC_AXES + [
            _ax("front", (-1, 0, 0), None, "out of the safe's opening"),
            _ax("door_in", (1, 0, 0), "door", "into the door from its outer face"),
            _ax("door_across", (0, 1, 0), "door", "from the hinge toward the free edge"),
            _ax("door_hinge", (0, 0, 1), "door", "the door's hinge axis"),
            _ax("knob_axis", (1, 0, 0), "knob", "the dial's rotation axis"),
        ]
        ops = [
            _op("pull", "door_edge", "door_in", "door_across", "door_hinge"),
            _op("push", "door_edge", "door_in", "door_across", "door_hinge"),
            _op("pinch", "knob", "knob_axis", "door_across", "door_hinge"),
        ]
        return _Annot(p["description"], points, axes, ops,
                      [FunctionAnnotation(function="storage", point="storage", axis="front")],
                      Articulation(joint="hinge", closed=0.0, open=p["open_deg"] * _DEG))


# -- toaster --------------------------------------------------------------------------------------------------
class ToasterFamily(_ArticulatedFamily):
    name = "toaster"
    _params = {
        0: dict(description="silver two-slot toaster", depth=0.14, width=0.20, height=0.18, travel=0.08,
                rgba=(0.78, 0.78, 0.8, 1.0)),
        1: dict(description="red two-slot toaster", depth=0.15, width=0.21, height=0.19, travel=0.09,
                rgba=(0.8, 0.15, 0.12, 1.0)),
    }
    # The lever sticks 6 cm out of the front face: a fingertip pressing its middle keeps the curled fingers
    # clear of the body (at 4 cm the pinky caught the front face halfway down).
    _LEVER = (0.03, 0.012, 0.008)

    def _lever_pos(self, p: dict) -> tuple[float, float, float]:
        return (-p["depth"] / 2 - self._LEVER[0], p["width"] / 2 - 0.04, 0.8 * p["height"])

    def _design(self, p: dict) -> _Design:
        D, W, H = p["depth"], p["width"], p["height"]
        dark = (0.1, 0.1, 0.1, 1.0)
        shell = [_Geom("body", (D / 2, W / 2, H / 2), (0, 0, H / 2), p["rgba"], 1.0)] + [
            _Geom(f"slot_{i}", (0.3 * D, 0.012, 0.002), (0, s * 0.04, H + 0.002), dark, 0.001)
            for i, s in enumerate((1, -1))
        ]
        lever = [_Geom("lever", self._LEVER, (0, 0, 0), (0.1, 0.1, 0.1, 1.0), 0.03)]
        slide = _Joint("slide", "slide", (0, 0, -1), (0.0, p["travel"]), damping=5.0, frictionloss=1.0)
        return _Design(shell, [_Part("lever", self._lever_pos(p), slide, lever)])

    def _annot(self, p: dict, design: _Design) -> _Annot:
        points = [
            _pt("lever_top", (0, 0, self._LEVER[2]), "lever", "top of the lever"),
            _pt("slot", (0, 0.04, p["height"] + 0.004), None, "top of a bread slot"),
        ]
        ops = [_op("press", "lever_top", "down", "left", "forward")]
        return _Annot(p["description"], points, list(_BASIC_AXES), ops,
                      [FunctionAnnotation(function="toasting", point="slot", axis="up")],
                      Articulation(joint="slide", closed=0.0, open=p["travel"]))


ARTICULATED_FAMILIES: dict[str, ObjectFamily] = {
    f.name: f for f in (DrawerFamily(), LaptopFamily(), BoxFamily(), SafeFamily(), ToasterFamily())
}


# -- openness -------------------------------------------------------------------------------------------------
def openness_joint(model: mujoco.MjModel, body_name: str, ann: ObjectAnnotations) -> int:
    """The id of the object's articulation joint ("<body>_<joint>")."""
    if ann.articulation is None:
        raise ValueError(f"{ann.family}: the object has no articulation")
    return model.joint(f"{body_name}_{ann.articulation.joint}").id


def set_openness(model: mujoco.MjModel, data: mujoco.MjData, body_name: str, ann: ObjectAnnotations,
                 openness: float) -> None:
    """Put the articulation joint at `openness` (clipped to [0, 1]) with zero velocity, then mj_forward."""
    j = openness_joint(model, body_name, ann)
    data.qpos[model.jnt_qposadr[j]] = ann.articulation.joint_position(float(np.clip(openness, 0.0, 1.0)))
    data.qvel[model.jnt_dofadr[j]] = 0.0
    mujoco.mj_forward(model, data)


def get_openness(model: mujoco.MjModel, data: mujoco.MjData, body_name: str, ann: ObjectAnnotations) -> float:
    """The articulation joint's position as openness (0 closed, 1 open), clipped to [0, 1]."""
    j = openness_joint(model, body_name, ann)
    return ann.articulation.openness_of(float(data.qpos[model.jnt_qposadr[j]]))
