"""Annotation transfer, geometric, no learned weights: the family's annotated template (its model type_id 0) is
aligned to a new mesh and each key point is carried over and snapped to the matching feature of the new
surface, with a confidence per point.

Alignment: the mesh is upright already (the importer turned its up axis to +z). Its vertical axis is the centre
of its base; its yaw puts the family's handles where the template has them (a cup's handle on +y, a pot's two
on +-y), found as the part of the surface that stands out of the body's radius at its height; rotationally
symmetric families (bottle, can, bowl, plate) keep their yaw; a box turns the smallest rectangle around its
footprint square to the axes, its long side onto y (a pinch's fingers close along x, across the narrow side). ICP
of the template's surface, scaled to the mesh's box, over the family's symmetric yaws, then says how well the
template fits (and picks the yaw where no handle decides it).

Snapping (by point name): a side grasp point goes onto the body's outer surface at the template's relative
height, in the template's direction; the rim and the pouring lip onto the top opening; storage just above the
inner bottom (a ray down the axis); top, pinch, support and a bottle's shoulder grip a fixed depth below the top
(a ray down the axis); a handle point into the handle. Any other point is the ICP-mapped template point moved
to the nearest surface.

A point's confidence is 1 when its feature was found and the snapped point agrees with the ICP-mapped
template point, lower as they disagree or the template fits badly, and 0.3 at most when the feature was not
found. Below `LOW_CONFIDENCE` the importer warns and writes the point into the override file.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import trimesh
from scipy.spatial import ConvexHull, cKDTree

from humanoidgen.objects.imported.template import ray_hits, template_mesh
from humanoidgen.objects.schema import KeyPoint, ObjectAnnotations

LOW_CONFIDENCE = 0.5
ROUND_BASE = 0.6  # a round family's base narrower than this (short/long spread) is not standing on it
N_SAMPLES = 4000
HANDLED = {"cup": 1, "pot": 2}  # families whose yaw is set by their handles: how many
SYMMETRIC = {"bottle", "can", "bowl", "plate"}
SIDE_POINTS = {"side", "side_left", "side_right", "neck"}
RIM_POINTS = {"rim", "lip"}
TOP_POINTS = {"top", "pinch", "support", "shoulder"}
BOTTOM_POINTS = {"pinch_bottom", "base"}
HANDLE_POINTS = {"handle_left", "handle_right", "grip_left", "grip_right"}
_STANDS_OUT, _STANDS_OUT_M = 1.18, 0.004  # a surface farther from the axis than this times the body's radius
# at its height, plus this much, stands out of the body (a handle)
NOT_ROUND = 0.1  # a body whose extent across a grasp differs from its width by more than this fraction is flat


@dataclass
class PointResult:
    name: str
    position: np.ndarray
    confidence: float
    rule: str
    found: bool
    width: float | None = None
    across: float | None = None  # a side point's horizontal extent across the approach, where not round


@dataclass
class TransferResult:
    """The turn that puts the mesh in the family's frame, the annotations in that frame and the points' fate."""

    transform: np.ndarray  # 4x4: upright mesh -> object frame (yaw about the vertical axis, then centred)
    annotations: ObjectAnnotations
    points: list[PointResult]
    icp_rms: float
    yaw: float
    seconds: float = 0.0
    notes: list[str] = field(default_factory=list)

    def low(self) -> list[PointResult]:
        return [p for p in self.points if p.confidence < LOW_CONFIDENCE]


def _rz(yaw: float) -> np.ndarray:
    c, s = math.cos(yaw), math.sin(yaw)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _base_axis(samples: np.ndarray) -> np.ndarray:
    """The vertical axis (x, y): the centre of the lowest 15% of the surface, where no handle is."""
    z0, z1 = samples[:, 2].min(), samples[:, 2].max()
    low = samples[samples[:, 2] <= z0 + 0.15 * (z1 - z0)]
    low = low if len(low) >= 20 else samples
    return (low[:, :2].min(0) + low[:, :2].max(0)) / 2


def _base_roundness(samples: np.ndarray) -> float:
    """How round the lowest 15% of the surface is: the ratio of its short to its long horizontal spread."""
    z0, z1 = samples[:, 2].min(), samples[:, 2].max()
    low = samples[samples[:, 2] <= z0 + 0.15 * (z1 - z0)][:, :2]
    if len(low) < 20:
        return 1.0
    w = np.linalg.eigvalsh(np.cov((low - low.mean(0)).T))
    return float(math.sqrt(max(w[0], 0.0) / max(w[1], 1e-12)))


def _standing_out(samples: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """A mask of the samples that stand out of the body's radius at their height (handles)."""
    rel = samples[:, :2] - axis
    r = np.linalg.norm(rel, axis=1)
    z = samples[:, 2]
    bins = np.linspace(z.min(), z.max() + 1e-9, 13)
    idx = np.clip(np.digitize(z, bins) - 1, 0, 11)
    body = np.array([np.percentile(r[idx == k], 40) if np.any(idx == k) else 0.0 for k in range(12)])
    ref = np.maximum(body[idx], np.median(body[body > 0]) if np.any(body > 0) else 0.0)
    return r > _STANDS_OUT * ref + _STANDS_OUT_M


def _handle_yaw(samples: np.ndarray, axis: np.ndarray, n_handles: int) -> float | None:
    out = _standing_out(samples, axis)
    if out.sum() < max(15, 0.01 * len(samples)):
        return None
    rel = samples[out, :2] - axis
    ang = np.arctan2(rel[:, 1], rel[:, 0])
    if n_handles == 1:
        mean = math.atan2(np.sin(ang).mean(), np.cos(ang).mean())
        return math.pi / 2 - mean
    mean2 = 0.5 * math.atan2(np.sin(2 * ang).mean(), np.cos(2 * ang).mean())
    return math.pi / 2 - mean2


def _handle_box(samples: np.ndarray, axis: np.ndarray, side: float) -> tuple[np.ndarray, np.ndarray] | None:
    """The box of the handle on the +y (side 1) or -y (side -1) of the axis, or None where none stands out."""
    out = _standing_out(samples, axis) & (side * (samples[:, 1] - axis[1]) > 0)
    if out.sum() < 10:
        return None
    pts = samples[out]
    return np.percentile(pts, 2, axis=0), np.percentile(pts, 98, axis=0)


def _box_yaw(samples: np.ndarray) -> float:
    """The yaw that squares the smallest rectangle around the footprint to the axes, its long side onto y (a
    pinch's fingers close across x). Not the principal axes: a square footprint has none of its own (its
    spread is the same every way), and Meta-World's square bin came out turned 11 deg by them."""
    xy = samples[:, :2]
    hull = xy[ConvexHull(xy).vertices]
    edges = np.roll(hull, -1, axis=0) - hull
    angles = np.arctan2(edges[:, 1], edges[:, 0])[np.linalg.norm(edges, axis=1) > 1e-9]
    best = None
    for th in angles:  # the smallest enclosing rectangle has a side along an edge of the hull
        c, s = math.cos(th), math.sin(th)
        p = hull @ np.array([[c, -s], [s, c]])  # the hull in the frame turned by th
        ext = p.max(0) - p.min(0)
        if best is None or ext[0] * ext[1] < best[0] - 1e-12:
            best = (ext[0] * ext[1], th, ext)
    _, th, ext = best
    longest = th if ext[0] >= ext[1] else th + math.pi / 2
    return float(math.pi / 2 - longest)


def _box(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return points.min(0), points.max(0)


def _icp(src: np.ndarray, dst_tree: cKDTree, dst: np.ndarray, iters: int = 12) -> tuple[np.ndarray, float]:
    """Yaw + translation that bring `src` onto `dst` (points), and the final rms distance."""
    R, t = np.eye(3), np.zeros(3)
    cur = src.copy()
    for _ in range(iters):
        d, j = dst_tree.query(cur)
        m = dst[j]
        a, b = cur - cur.mean(0), m - m.mean(0)
        H = a[:, :2].T @ b[:, :2]
        U, _, Vt = np.linalg.svd(H)
        R2 = Vt.T @ U.T
        if np.linalg.det(R2) < 0:
            Vt[1] *= -1
            R2 = Vt.T @ U.T
        Rs = np.eye(3)
        Rs[:2, :2] = R2
        ts = m.mean(0) - cur.mean(0) @ Rs.T
        cur = cur @ Rs.T + ts
        R, t = Rs @ R, Rs @ t + ts
    d, _ = dst_tree.query(cur)
    return np.column_stack([R, t]), float(np.sqrt(np.mean(d ** 2)))


@dataclass
class _Frame:
    """The new mesh, in the object frame, with what the rules ask of it."""

    mesh: trimesh.Trimesh
    samples: np.ndarray
    tree: cKDTree
    axis: np.ndarray
    bmin: np.ndarray
    bmax: np.ndarray

    def ray(self, origin, direction) -> np.ndarray:
        return ray_hits(self.mesh.triangles, np.asarray(origin, float), np.asarray(direction, float))


def _template(family: str):
    from humanoidgen.objects.rigid import RIGID_FAMILIES

    fam = RIGID_FAMILIES[family]
    return fam.geometry(0), fam.annotations(0)


def transfer(upright: trimesh.Trimesh, family: str, type_id: int, description: str) -> TransferResult:
    """Align the family's template to `upright` (metres, z up) and carry its annotations over."""
    import time

    t0 = time.perf_counter()
    geo, tann = _template(family)
    tmesh = template_mesh(geo)
    samples = np.asarray(trimesh.sample.sample_surface(upright, N_SAMPLES, seed=0)[0])
    axis = _base_axis(samples)
    notes: list[str] = []
    round_ = _base_roundness(samples) if family in SYMMETRIC or family in HANDLED else 1.0
    if round_ < ROUND_BASE:
        notes.append(f"its base is not round (aspect {round_:.2f}) as a {family}'s is: is it upright? "
                     "(--up names the file's up axis)")
    handle_found = True
    if family in HANDLED:
        yaw0 = _handle_yaw(samples, axis, HANDLED[family])
        handle_found = yaw0 is not None
        if not handle_found:
            notes.append("no handle stands out of the body: the yaw is the best template fit")
        yaws = [yaw0] if handle_found else [k * math.pi / 4 for k in range(8)]
    elif family in SYMMETRIC:
        yaws = [0.0]
    else:
        yaws = [_box_yaw(samples)]
    tsamples = np.asarray(trimesh.sample.sample_surface(tmesh, 1500, seed=1)[0])
    best = None
    for yaw in yaws:
        pts = (samples - [*axis, 0.0]) @ _rz(yaw).T
        lo, hi = _box(pts)
        ctr = (lo + hi) / 2
        pts = pts - ctr
        tlo, thi = geo.bmin, geo.bmax
        scale = (hi - lo) / np.maximum(thi - tlo, 1e-6)
        src = (tsamples - (tlo + thi) / 2) * scale
        tree = cKDTree(pts)
        T, rms = _icp(src, tree, pts)
        if best is None or rms < best[1]:
            best = (yaw, rms, T, scale, ctr)
    yaw, rms, T_icp, scale, ctr = best
    # upright -> object frame: about the base axis by yaw, then the box centred
    A = np.eye(4)
    A[:3, :3] = _rz(yaw)
    A[:3, 3] = -(_rz(yaw) @ np.array([*axis, 0.0])) - ctr
    mesh = upright.copy()
    mesh.apply_transform(A)
    pts = samples @ A[:3, :3].T + A[:3, 3]
    lo, hi = _box(np.asarray(mesh.vertices))
    frame = _Frame(mesh, pts, cKDTree(pts), (A[:3, :3] @ np.array([*axis, 0.0]) + A[:3, 3])[:2], lo, hi)
    size = float(np.linalg.norm(hi - lo))
    fit = math.exp(-(rms / (0.04 * size)) ** 2) * min(1.0, round_ / ROUND_BASE) ** 4
    tctr = (geo.bmin + geo.bmax) / 2

    def icp_mapped(p: np.ndarray) -> np.ndarray:
        q = (p - tctr) * scale
        return T_icp[:, :3] @ q + T_icp[:, 3]

    results = []
    for kp in tann.points:
        p = np.asarray(kp.position, float)
        res = _snap(kp.name, p, geo, tmesh, frame, family)
        mapped = icp_mapped(p)
        d = float(np.linalg.norm(res.position - mapped))
        agree = math.exp(-(d / (0.25 * size)) ** 2)
        if kp.name == "center":
            res.confidence = 1.0
        else:
            res.confidence = round((1.0 if res.found else 0.3) * math.sqrt(agree * fit)
                                   * (1.0 if handle_found or kp.name not in HANDLE_POINTS else 0.4), 3)
        results.append(res)
    ann = _annotations(tann, results, family, type_id, description, lo, hi)
    return TransferResult(A, ann, results, rms, yaw, time.perf_counter() - t0, notes)


def _annotations(tann: ObjectAnnotations, results: list[PointResult], family: str, type_id: int,
                 description: str, lo: np.ndarray, hi: np.ndarray) -> ObjectAnnotations:
    by = {r.name: r for r in results}
    points = [KeyPoint(name=r.name, position=tuple(round(float(v), 5) for v in r.position)) for r in results]
    ops = []
    for o in tann.operations:
        w, across = o.width, None
        if w is not None and by[o.point].width is not None:
            w = round(float(min(max(by[o.point].width, 0.01), 0.12)), 4)
            if by[o.point].across is not None:
                across = round(float(min(max(by[o.point].across, 0.01), 0.15)), 4)
        ops.append(o.model_copy(update={"width": w, "across": across}))
    return ObjectAnnotations(family=family, type_id=type_id, description=description,
                             bbox_min=tuple(float(v) for v in lo), bbox_max=tuple(float(v) for v in hi),
                             points=points, axes=tann.axes, operations=ops, functions=tann.functions)


def _across(f: _Frame, z: float, d: np.ndarray, r: float, width: float) -> float | None:
    """The body's horizontal extent across the approach `d` at height z, where it is not round (it differs from
    `width` by more than NOT_ROUND), else None. Surfaces that stand out of the body (a handle) do not count."""
    at = np.abs(f.samples[:, 2] - z) < 0.01
    ref = float(np.percentile(np.linalg.norm(f.samples[at, :2] - f.axis, axis=1), 40)) if at.sum() >= 10 else r
    limit = _STANDS_OUT * max(r, ref) + _STANDS_OUT_M
    sides = []
    for sgn in (1.0, -1.0):
        hits = [h for h in f.ray([*f.axis, z], [-sgn * d[1], sgn * d[0], 0.0]) if h <= limit]
        if not hits:
            return None
        sides.append(float(hits[-1]))
    across = sum(sides)
    return across if abs(across - width) > NOT_ROUND * width else None


def _snap(name: str, p: np.ndarray, geo, tmesh: trimesh.Trimesh, f: _Frame, family: str) -> PointResult:
    tH = geo.bmax[2] - geo.bmin[2]
    H = f.bmax[2] - f.bmin[2]
    taxis = np.asarray(geo.axis_xy, float)
    if name == "center":
        return PointResult(name, np.zeros(3), 1.0, "centre", True)
    if name in SIDE_POINTS or name in RIM_POINTS:
        d = p[:2] - taxis
        d = d / (np.linalg.norm(d) or 1.0)
        if name in SIDE_POINTS:
            z = f.bmin[2] + (p[2] - geo.bmin[2]) / tH * H
            hits = f.ray([*f.axis, z], [d[0], d[1], 0.0])
            if len(hits):
                r = float(hits[-1])
                # The diameter across: the far wall is the last surface the ray back meets within the body's
                # radius; beyond it stands a handle (a mug grasped opposite its handle is 8 cm wide, not 12).
                back = [h for h in f.ray([*f.axis, z], [-d[0], -d[1], 0.0]) if h <= _STANDS_OUT * r + _STANDS_OUT_M]
                width = r + float(back[-1]) if len(back) else 2 * r
                return PointResult(name, np.array([*(f.axis + d * r), z]), 1.0, "surface at relative height",
                                   True, width, _across(f, z, d, r, width))
        else:
            rel = f.samples[:, :2] - f.axis
            r = np.linalg.norm(rel, axis=1)
            cosang = (rel @ d) / np.maximum(r, 1e-9)
            top = f.samples[:, 2] > f.bmax[2] - max(0.01 * H, 0.003)
            sel = top & (cosang > math.cos(math.radians(30)))
            if sel.sum() >= 3:
                rr = float(np.median(r[sel]))
                z = float(f.samples[sel, 2].max())
                return PointResult(name, np.array([*(f.axis + d * rr), z]), 1.0, "top opening", True)
    elif name == "storage":
        hits = f.ray([*f.axis, f.bmax[2] + 0.01], [0, 0, -1.0])
        thits = ray_hits(tmesh.triangles, np.array([*taxis, geo.bmax[2] + 0.01]), np.array([0, 0, -1.0]))
        if len(hits) and len(thits):
            z0 = f.bmax[2] + 0.01 - hits[0]
            tz0 = geo.bmax[2] + 0.01 - thits[0]
            if z0 < f.bmin[2] + 0.5 * H:  # the ray went into an opening, not onto a lid
                return PointResult(name, np.array([*f.axis, z0 + (p[2] - tz0)]), 1.0, "inner bottom", True)
    elif name in TOP_POINTS or name in BOTTOM_POINTS:
        up = name in TOP_POINTS
        sgn = -1.0 if up else 1.0
        start = (f.bmax[2] + 0.01) if up else (f.bmin[2] - 0.01)
        tstart = (geo.bmax[2] + 0.01) if up else (geo.bmin[2] - 0.01)
        hits = f.ray([*f.axis, start], [0, 0, sgn])
        thits = ray_hits(tmesh.triangles, np.array([*taxis, tstart]), np.array([0, 0, sgn]))
        if len(hits) and len(thits):
            z = start + sgn * hits[0]
            tz = tstart + sgn * thits[0]
            return PointResult(name, np.array([*f.axis, z + (p[2] - tz)]), 1.0, "along the axis from the end",
                               True)
    elif name in HANDLE_POINTS:
        side = 1.0 if name.endswith("left") else -1.0
        box = _handle_box(f.samples, f.axis, side)
        tsamples = np.asarray(trimesh.sample.sample_surface(tmesh, N_SAMPLES, seed=2)[0])
        tbox = _handle_box(tsamples, taxis, side)
        if box is not None and tbox is not None:
            frac = (p - tbox[0]) / np.maximum(tbox[1] - tbox[0], 1e-6)
            pos = box[0] + frac * (box[1] - box[0])
            width = float(box[1][0] - box[0][0]) if name.startswith("grip") else None
            return PointResult(name, pos, 1.0, "handle", True, width)
    # fall back: the template point scaled into the box, moved to the nearest surface
    q = (p - (geo.bmin + geo.bmax) / 2) * (f.bmax - f.bmin) / np.maximum(geo.bmax - geo.bmin, 1e-6)
    _, j = f.tree.query(q)
    return PointResult(name, f.samples[j].copy(), 0.3, "nearest surface (feature not found)", False)
