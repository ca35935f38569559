"""Parametric rigid object families: cube, bottle, can, plate, cup, bowl, pot.

Every model is described as a list of convex primitives (boxes and cylinders) in the object frame; hollow
objects (cup, bowl, pot) are a bottom disc plus a ring of thin box walls, so their collision geometry is really
concave. The primitives are shifted so that the origin is the centre of their bounding box, which is computed
exactly from the primitives (and reported in the annotations). Masses are split over the primitives by volume.

The models (dimensions, colours, masses, materials) and each family's annotation vocabulary (axes, operations,
functions) are data: humanoidgen/objects/families/<family>/ (objects/family_data.py). This module builds a
model's primitives from its parameters and derives its annotated points from that geometry.

World: table top at z = 0, +x forward (away from the robot), +y left, +z up. A hand coming from the robot
approaches along +x.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import mujoco
import numpy as np

from humanoidgen.objects.family import ObjectFamily, ObjectModel
from humanoidgen.objects.family_data import FamilyData, ModelData, family_data, material
from humanoidgen.objects.params import (
    BottleParams,
    BowlParams,
    CanParams,
    CubeParams,
    CupParams,
    PlateParams,
    PotParams,
    RigidParams,
)
from humanoidgen.objects.schema import FunctionAnnotation, KeyPoint, ObjectAnnotations, OperationAnnotation
from humanoidgen.sim.geometry import quat_to_mat

Vec3 = tuple[float, float, float]
RGBA = tuple[float, float, float, float]


# -- primitives -----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Prim:
    """One convex collision primitive in the object frame. `size` is MuJoCo's: box half-sizes, or cylinder
    (radius, half-height); cylinders are always z-aligned (quat only rotates boxes about z/tilts them)."""

    name: str
    kind: str  # "box" | "cylinder"
    size: Vec3
    pos: Vec3
    quat: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)
    rgba: RGBA = (0.6, 0.62, 0.65, 1.0)

    def volume(self) -> float:
        if self.kind == "box":
            return 8.0 * self.size[0] * self.size[1] * self.size[2]
        return math.pi * self.size[0] ** 2 * 2.0 * self.size[1]

    def corners(self) -> np.ndarray:
        """Points whose AABB is the primitive's exact AABB in the object frame."""
        if self.kind == "box":
            s = np.asarray(self.size, float)
            signs = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)], float)
            return (signs * s) @ quat_to_mat(self.quat).T + np.asarray(self.pos, float)
        r, h = self.size[0], self.size[1]
        signs = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)], float)
        return signs * np.array([r, r, h]) + np.asarray(self.pos, float)

    def shifted(self, d: np.ndarray) -> "Prim":
        return replace(self, pos=tuple(float(v) for v in np.asarray(self.pos) + d))


def _quat_zy(theta: float, tilt: float = 0.0) -> tuple[float, float, float, float]:
    """Rotation about z by theta after a rotation about y by tilt (q = qz * qy)."""
    qz = np.array([math.cos(theta / 2), 0.0, 0.0, math.sin(theta / 2)])
    qy = np.array([math.cos(tilt / 2), 0.0, math.sin(tilt / 2), 0.0])
    q = np.zeros(4)
    mujoco.mju_mulQuat(q, qz, qy)
    return tuple(float(v) for v in q)


def _ring(prefix: str, n: int, r_out: float, thick: float, z0: float, z1: float, rgba: RGBA) -> list[Prim]:
    """A vertical cylindrical wall (outer radius r_out, from z0 to z1) made of n thin boxes."""
    rc = r_out - thick / 2
    half_w = r_out * math.tan(math.pi / n) * 1.02  # tangential half width: faces overlap, no gaps
    out = []
    for i in range(n):
        th = 2 * math.pi * i / n
        out.append(Prim(f"{prefix}{i}", "box", (thick / 2, half_w, (z1 - z0) / 2),
                        (rc * math.cos(th), rc * math.sin(th), (z0 + z1) / 2), _quat_zy(th), rgba))
    return out


def _center(prims: list[Prim]) -> tuple[list[Prim], np.ndarray, np.ndarray, np.ndarray]:
    """Shift primitives so the bounding box is centred at the origin; returns (prims, shift, bmin, bmax)."""
    pts = np.concatenate([p.corners() for p in prims])
    lo, hi = pts.min(0), pts.max(0)
    shift = -(lo + hi) / 2
    return [p.shifted(shift) for p in prims], shift, lo + shift, hi + shift


# -- model geometry ---------------------------------------------------------------------------------------------
@dataclass
class Geometry:
    """A model's primitives (object frame), bbox, named points (object frame) and storage opening."""

    prims: list[Prim]
    bmin: np.ndarray
    bmax: np.ndarray
    points: dict[str, np.ndarray]
    opening_radius: float | None = None  # inner radius at the rim, for containers
    rim_z: float | None = None  # top of the rim, for containers
    inner_bottom_z: float | None = None
    axis_xy: tuple[float, float] = (0.0, 0.0)  # where the container's vertical axis (opening centre) is
    # A round grip's diameter by its point (a pot's post handle); a wrap elsewhere takes the body's, at "side".
    widths: dict[str, float] = field(default_factory=dict)


def _finish(prims: list[Prim], points: dict[str, Vec3], widths: dict[str, float] | None = None,
            **container) -> Geometry:
    prims, shift, lo, hi = _center(prims)
    pts = {k: np.asarray(v, float) + shift for k, v in points.items()}
    pts["center"] = np.zeros(3)
    for key in ("rim_z", "inner_bottom_z"):
        if container.get(key) is not None:
            container[key] = float(container[key] + shift[2])
    container["axis_xy"] = (float(shift[0]), float(shift[1]))
    return Geometry(prims, lo, hi, pts, widths=dict(widths or {}), **container)


# A box this much longer along z than across is a block with two ends (see families/cube/family.yaml).
ELONGATED_RATIO = 1.5
# The other end's pinch sits deeper than the top's: a block held by one end lies across the hand (a hand-over),
# and 1.5 cm in, thumb and index hold it level where nearer the end it droops out of the fingers (measured).
END_PINCH_DEPTH = 0.015
# A bottle taken from above (the hand that takes it from the other hand, which wraps the body): the whole hand's
# grasp closes this far below the cap's top, so that the palm (4.5 cm over the hand's grasp point) stays just
# over the cap and the fingers close round the shoulder, whose ledge then rests on them (measured on the 0.33 l
# bottle: 1 cm deeper the palm meets the cap; 3 cm higher only the fingertips reach the shoulder's rim).
SHOULDER_GRIP_DEPTH = 0.042


def _elongated(size: Vec3) -> bool:
    return size[2] >= ELONGATED_RATIO * max(size[0], size[1])


def _box_geometry(p: dict) -> Geometry:
    sx, sy, sz = p["size"]
    prims = [Prim("geom", "box", (sx / 2, sy / 2, sz / 2), (0, 0, 0), rgba=p["rgba"])]
    # Pinch just under 1 cm below the top face: the finger pads then squeeze the sides, not the top edge.
    points = {"top": (0, 0, sz / 2 - 0.005), "pinch": (0, 0, sz / 2 - 0.0095), "support": (0, 0, sz / 2)}
    if _elongated(p["size"]):  # the other end, as far from the top's grip as the block allows
        points |= {"pinch_bottom": (0, 0, -sz / 2 + END_PINCH_DEPTH), "base": (0, 0, -sz / 2)}
    return _finish(prims, points)


def _bottle_geometry(p: dict) -> Geometry:
    r, hb, rn, hn, rgba = p["radius"], p["body_height"], p["neck_radius"], p["neck_height"], p["rgba"]
    shoulder = 0.2 * hb  # a frustum-like shoulder: a mid-radius cylinder between body and neck
    rs = (r + rn) / 2
    prims = [
        Prim("body", "cylinder", (r, hb / 2), (0, 0, hb / 2), rgba=rgba),
        Prim("shoulder", "cylinder", (rs, shoulder / 2), (0, 0, hb + shoulder / 2), rgba=rgba),
        Prim("neck", "cylinder", (rn, hn / 2), (0, 0, hb + shoulder + hn / 2), rgba=rgba),
        Prim("cap", "cylinder", (rn * 1.1, 0.006), (0, 0, hb + shoulder + hn - 0.006), rgba=p["cap_rgba"]),
    ]
    return _finish(prims, {"side": (-r, 0, hb / 2), "side_left": (0, r, hb / 2), "side_right": (0, -r, hb / 2),
                           "neck": (-rn, 0, hb + shoulder + hn / 2), "top": (0, 0, hb + shoulder + hn),
                           "shoulder": (0, 0, hb + shoulder + hn - SHOULDER_GRIP_DEPTH)})


def _can_geometry(p: dict) -> Geometry:
    r, h = p["radius"], p["height"]
    prims = [Prim("body", "cylinder", (r, h / 2), (0, 0, h / 2), rgba=p["rgba"])]
    return _finish(prims, {"side": (-r, 0, h / 2), "side_left": (0, r, h / 2), "side_right": (0, -r, h / 2),
                           "top": (0, 0, h)})


def _plate_geometry(p: dict) -> Geometry:
    R, t, rim_h, n = p["radius"], p["thickness"], p["rim_height"], 16
    rim_t = 0.008
    prims = [Prim("base", "cylinder", (R - rim_t / 2, t / 2), (0, 0, t / 2), rgba=p["rgba"])]
    if rim_h > 0:
        prims += _ring("rim", n, R, rim_t, t * 0.5, t + rim_h, p["rgba"])
    top = t + rim_h
    return _finish(prims, {"rim": (-(R - rim_t / 2), 0, top), "support": (0, 0, t)})


def _cup_like(p: dict, handles: tuple[str, ...]) -> Geometry:
    """Cup / pot: bottom disc + vertical ring of walls, handles on +y ("left") and/or -y ("right")."""
    R, H, t, tb, n, rgba = p["radius"], p["height"], p["wall"], p["bottom"], p["n_walls"], p["rgba"]
    prims = [Prim("bottom", "cylinder", (R - t / 2, tb / 2), (0, 0, tb / 2), rgba=rgba)]
    # walls start 1 mm above the table so the object stands on its (flat) bottom disc
    prims += _ring("wall", n, R, t, 0.001, H, rgba)
    # Side grasps a little above half height, so that the wrapping hand's little finger clears the table.
    points: dict[str, Vec3] = {
        "side": (-R, 0, 0.6 * H),
        "rim": (-(R - t / 2), 0, H),
        "lip": (0, -(R - t / 2), H) if "left" in handles and "right" not in handles else (R - t / 2, 0, H),
        "storage": (0, 0, tb + 0.01),
    }
    if "right" not in handles:  # the flank without a handle
        points["side_right"] = (0, -R, 0.6 * H)
    ext, bar_t = p["handle_reach"], p["handle_thick"]
    widths: dict[str, float] = {}  # round grips' diameters, by point
    for side in handles:
        s = 1.0 if side == "left" else -1.0
        if p["handle_style"] == "loop":  # cup: a vertical loop of three boxes
            zc, span = H * 0.55, H * 0.5
            for k, z in (("top", zc + span / 2), ("bot", zc - span / 2)):
                prims.append(Prim(f"handle_{side}_{k}", "box", (0.006, ext / 2 + t / 2, bar_t / 2),
                                  (0, s * (R + ext / 2 - t / 2), z), rgba=rgba))
            prims.append(Prim(f"handle_{side}_grip", "box", (0.006, bar_t / 2, span / 2 + bar_t / 2),
                              (0, s * (R + ext - bar_t / 2), zc), rgba=rgba))
            points[f"handle_{side}"] = (0, s * (R + ext - bar_t / 2), zc)
        elif p["handle_style"] == "post":  # pot: an upright round grip, held off the wall by an arm at each end
            _post_handle(prims, points, widths, side, p)
        else:  # pot: a horizontal bar sticking out near the top
            w = p["handle_width"]
            zc = H - 0.02
            prims.append(Prim(f"handle_{side}", "box", (w / 2, ext / 2 + t / 2, bar_t / 2),
                              (0, s * (R + ext / 2 - t / 2), zc), rgba=p["handle_rgba"]))
            points[f"handle_{side}"] = (0, s * (R + ext * 0.6), zc)
    return _finish(prims, points, widths, opening_radius=R - t, rim_z=H, inner_bottom_z=tb)


# A post handle's arms: this thick (vertical) and wide (horizontal), at the post's two ends.
POST_ARM_THICK, POST_ARM_WIDE = 0.01, 0.012


def _post_handle(prims: list[Prim], points: dict[str, Vec3], widths: dict[str, float], side: str, p: dict) -> None:
    """An upright round grip on the `side` ("left": +y) of a pot, its top level with the rim. A hand wraps it
    the way it wraps a bottle (a grasp with a `width`), so its annotated point is the grip's outer surface at mid
    height, where the hand's palm comes from; the grip's length is free of the arms, so the curled fingers fit
    between them."""
    R, H, t = p["radius"], p["height"], p["wall"]
    s = 1.0 if side == "left" else -1.0
    r, length, axis = p["handle_thick"] / 2, p["handle_height"], R + p["handle_reach"]
    zc = H - length / 2
    rgba = p["handle_rgba"]
    prims.append(Prim(f"handle_{side}", "cylinder", (r, length / 2), (0, s * axis, zc), rgba=rgba))
    arm_len = axis - (R - t)  # from inside the wall to the grip's axis
    for k, z in (("top", H - POST_ARM_THICK / 2), ("bot", H - length + POST_ARM_THICK / 2)):
        prims.append(Prim(f"handle_{side}_{k}", "box", (POST_ARM_WIDE / 2, arm_len / 2, POST_ARM_THICK / 2),
                          (0, s * (R - t + arm_len / 2), z), rgba=rgba))
    points[f"grip_{side}"] = (0, s * (axis + r), zc)
    widths[f"grip_{side}"] = 2 * r


def _bowl_geometry(p: dict) -> Geometry:
    """Bottom disc + ring of walls tilted outward by `tilt`."""
    Rb, L, t, tb, n, rgba = p["bottom_radius"], p["wall_length"], p["wall"], p["bottom"], p["n_walls"], p["rgba"]
    tilt = math.radians(p["tilt_deg"])
    r_top = Rb + L * math.sin(tilt)
    half_w = (r_top + t) * math.tan(math.pi / n) * 1.02
    prims = [Prim("bottom", "cylinder", (Rb, tb / 2), (0, 0, tb / 2), rgba=rgba)]
    # wall centre: the inner bottom edge touches the disc's rim at height tb; lowest corner stays >= 1 mm
    ca, sa = math.cos(tilt), math.sin(tilt)
    rc = Rb + (L / 2) * sa + (t / 2) * ca
    zc = (L / 2) * ca - (t / 2) * sa + tb
    zc = max(zc, 0.001 + (L / 2) * ca + (t / 2) * sa)
    for i in range(n):
        th = 2 * math.pi * i / n
        prims.append(Prim(f"wall{i}", "box", (t / 2, half_w, L / 2), (rc * math.cos(th), rc * math.sin(th), zc),
                          _quat_zy(th, tilt), rgba))
    top_z = zc + (L / 2) * ca  # wall mid-plane top
    r_rim = rc + (L / 2) * sa
    return _finish(prims, {"side": (-r_rim, 0, top_z - 0.01), "rim": (-r_rim, 0, top_z),
                           "storage": (0, 0, tb + 0.01)},
                   opening_radius=r_rim - t / 2 * ca, rim_z=top_z, inner_bottom_z=tb)


# -- families -------------------------------------------------------------------------------------------------------
class RigidFamily:
    """A parametric rigid family: its models and annotation vocabulary are data (families/<name>/), validated
    against `Params`; subclasses give the geometry built from a model's parameters."""

    name: str = ""
    articulated: bool = False
    Params: type[RigidParams] = RigidParams

    # -- ObjectFamily ------------------------------------------------------------------------------------------
    @property
    def static(self) -> bool:
        """Fixed to the table (no free joint from the scene): what the family's `family.yaml` says (barriers)."""
        return self._data().info.static

    def models(self) -> list[ObjectModel]:
        return [ObjectModel(self.name, m.type_id, m.description, {k: v for k, v in m.params.items() if k in m.own})
                for m in self._data().models.values()]

    def geometry(self, type_id: int) -> Geometry:
        return self._geometry(self._model(type_id).params)

    def build(self, spec: mujoco.MjSpec, body: mujoco.MjsBody, type_id: int) -> None:
        p = self._model(type_id).params
        geo = self._geometry(p)
        total = sum(g.volume() for g in geo.prims)
        friction = list(material(p["material"]))
        for g in geo.prims:
            kind = mujoco.mjtGeom.mjGEOM_BOX if g.kind == "box" else mujoco.mjtGeom.mjGEOM_CYLINDER
            size = list(g.size) if g.kind == "box" else [g.size[0], g.size[1], 0.0]
            body.add_geom(name=f"{body.name}_{g.name}", type=kind, size=size, pos=list(g.pos), quat=list(g.quat),
                          rgba=list(g.rgba), mass=p["mass"] * g.volume() / total, friction=friction, condim=4)

    def annotations(self, type_id: int) -> ObjectAnnotations:
        m = self._model(type_id)
        geo = self._geometry(m.params)
        info = self._data().info
        # An operation or function that `requires` a point only some models have (a long block's second end) is
        # left out of the others.
        ops = [o for o in info.operations if o.requires is None or o.requires in geo.points]
        fns = [f for f in info.functions if f.requires is None or f.requires in geo.points]
        pnames = {"center"} | {o.point for o in ops} | {f.point for f in fns}
        points = [KeyPoint(name=n, position=tuple(float(v) for v in geo.points[n]))
                  for n in geo.points if n in pnames]
        return ObjectAnnotations(
            family=self.name, type_id=type_id, description=m.description,
            bbox_min=tuple(float(v) for v in geo.bmin), bbox_max=tuple(float(v) for v in geo.bmax),
            points=points, axes=list(info.axes),
            operations=[OperationAnnotation(operation=o.operation, point=o.point, approach_axis=o.approach_axis,
                                            attach_axis=o.attach_axis, parallel_axis=o.parallel_axis,
                                            width=_diameter(geo, o.point) if o.wrap else None) for o in ops],
            functions=[FunctionAnnotation(function=f.function, point=f.point, axis=f.axis) for f in fns],
        )

    # -- helpers ---------------------------------------------------------------------------------------------
    def _data(self) -> FamilyData:
        return family_data(self.name, self.Params)

    def _model(self, type_id: int) -> ModelData:
        models = self._data().models
        if type_id not in models:
            raise ValueError(f"{self.name}: no type_id {type_id}; known: {', '.join(map(str, models))}")
        return models[type_id]

    def _geometry(self, p: dict) -> Geometry:
        raise NotImplementedError


def _diameter(geo: Geometry, point: str) -> float:
    """The diameter of the round body wrapped at `point`: a grip's own where the geometry gives one (a pot's
    post handle), else the body's at its side grasp point (on the surface, on the body's -x)."""
    if point in geo.widths:
        return round(geo.widths[point], 4)
    return round(-2.0 * float(geo.points["side"][0]), 4)


class CubeFamily(RigidFamily):
    name = "cube"
    Params = CubeParams
    _geometry = staticmethod(_box_geometry)


class BottleFamily(RigidFamily):
    name = "bottle"
    Params = BottleParams
    _geometry = staticmethod(_bottle_geometry)


class CanFamily(RigidFamily):
    name = "can"
    Params = CanParams
    _geometry = staticmethod(_can_geometry)


class PlateFamily(RigidFamily):
    name = "plate"
    Params = PlateParams
    _geometry = staticmethod(_plate_geometry)


class CupFamily(RigidFamily):
    name = "cup"
    Params = CupParams

    def _geometry(self, p: dict) -> Geometry:
        return _cup_like(p, ("left",))  # the handle on the left (+y): the cup pours to the right


class BowlFamily(RigidFamily):
    name = "bowl"
    Params = BowlParams
    _geometry = staticmethod(_bowl_geometry)


class PotFamily(RigidFamily):
    name = "pot"
    Params = PotParams

    def _geometry(self, p: dict) -> Geometry:
        return _cup_like(p, ("left", "right"))


RIGID_FAMILIES: dict[str, ObjectFamily] = {
    f.name: f for f in (CubeFamily(), BottleFamily(), CanFamily(), PlateFamily(), CupFamily(), BowlFamily(),
                        PotFamily())
}
