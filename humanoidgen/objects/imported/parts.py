"""Importing an articulated model (URDF, MJCF) into a drawer, laptop or box family: its links put in the family's
canonical frame at the closed position, and the family's points found on its parts.

Frame: every link's mesh is taken to the root's frame at the joints' zero, scaled and turned up, then turned about
the vertical so that the main joint does what the family's does: a drawer slides out toward -x (the robot); a
lid (laptop, box) turns about an axis along y at the back (+x), its free edge at the front. The main joint is the
family's kind (prismatic for a drawer, revolute for a lid) whose part is largest; its closed end is the limit
where a drawer sits deepest / a lid lies lowest. Link bodies sit at their joint's anchor, unrotated, so a part's
axes are the family's.

Points (on the main part unless said): drawer: the handle is what stands out of the front panel (its centre,
top and bottom), front beside it on the panel, head on the panel at the handle's height, storage over the drawer's
inner bottom; laptop: screen_edge the middle of the lid's front edge, screen_grip 1.5 cm in from it, screen_back
on the lid's outer face near the edge, screen_center under the lid's middle, keyboard on the base; box:
lid_front the lid's front edge, lid_grip and lid_pinch the same (where a grasp or a pinch holds it: a real lid has
no tab), lid_top its outer face 1.5 cm in, storage over the base's inner bottom. A point whose feature is missing
(a drawer without a handle) takes the panel and is flagged (confidence 0.3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import trimesh

from humanoidgen.objects.imported import model_file as mf
from humanoidgen.objects.imported.collision import coarse, convex_parts
from humanoidgen.objects.imported.formats import ImportError_, SourceModel
from humanoidgen.objects.imported.geometry import fit_factor, to_metres, up_rotation
from humanoidgen.objects.imported.sizing import fit_note
from humanoidgen.objects.imported.template import ray_hits
from humanoidgen.objects.imported.transfer import LOW_CONFIDENCE, PointResult, TransferResult
from humanoidgen.objects.schema import Articulation, KeyPoint, ObjectAnnotations

MAIN_KIND = {"drawer": "slide", "laptop": "hinge", "box": "hinge"}
PART = {"drawer": "drawer", "laptop": "screen", "box": "lid"}
# A lid or screen turning less than this is a model in the wrong angle unit (an MJCF range of "0 1.7" is 1.7 deg) or
# one whose tasks cannot open it (the family's own turn 100-110 deg)
MIN_LID_TURN_DEG = 45.0


@dataclass
class _Link:
    name: str
    parent: str | None
    mesh: trimesh.Trimesh  # object frame at the zero position, later at the closed one
    anchor: np.ndarray = field(default_factory=lambda: np.zeros(3))  # the joint's point (object frame)
    axis: np.ndarray | None = None
    kind: str | None = None
    lo: float = 0.0
    hi: float = 0.0
    joint: str | None = None


def _move(mesh: trimesh.Trimesh, link: _Link, q: float) -> trimesh.Trimesh:
    m = mesh.copy()
    if link.kind == "slide":
        m.apply_translation(q * link.axis)
    elif link.kind == "hinge":
        m.apply_transform(trimesh.transformations.rotation_matrix(q, link.axis, link.anchor))
    return m


def _links(src: SourceModel, factor: float, R: np.ndarray) -> list[_Link]:
    world: dict[str, np.ndarray] = {}
    out = []
    for link in src.links:
        T = (world[link.parent] if link.parent else np.eye(4)) @ link.origin
        world[link.name] = T
        mesh = link.mesh.copy() if len(link.mesh.faces) else trimesh.Trimesh()
        if len(mesh.faces):
            mesh.apply_transform(T)
            mesh = trimesh.Trimesh(np.asarray(mesh.vertices) * factor @ R.T, mesh.faces, process=False)
        L = _Link(link.name, link.parent, mesh, (R @ T[:3, 3]) * factor)
        if link.joint is not None:
            L.axis = R @ (T[:3, :3] @ np.asarray(link.joint.axis, float))
            L.kind, L.joint = link.joint.kind, link.joint.name
            scale = factor if L.kind == "slide" else 1.0
            L.lo, L.hi = link.joint.lower * scale, link.joint.upper * scale
        out.append(L)
    return out


def _subtree(links: list[_Link], root: str) -> list[_Link]:
    names = {root}
    for l in links:
        if l.parent in names:
            names.add(l.name)
    return [l for l in links if l.name in names]


def import_articulated(src: SourceModel, req, name: str, type_id: int, path):
    family = req.family
    if family not in MAIN_KIND:
        raise ImportError_(f"articulated import knows the drawer, laptop and box families, not {family!r}")
    R_up = up_rotation(req.up or "z")
    allmesh = trimesh.util.concatenate([l.mesh for l in src.links if len(l.mesh.faces)])
    if len(allmesh.faces) == 0:
        raise ImportError_(f"{path}: the model has no mesh with faces")
    factor = to_metres(allmesh, req.units, str(path))
    links = _links(src, factor, R_up)
    placed = [l.mesh for l in links if len(l.mesh.faces)]
    fitted = fit_factor(float(np.max(trimesh.util.concatenate(placed).extents)), req.units.fit)
    if fitted != 1.0:  # into the family's size range, measured on the links placed at their joints' zero
        factor *= fitted
        links = _links(src, factor, R_up)
    movers = [l for l in links if l.kind == MAIN_KIND[family]]
    if not movers:
        raise ImportError_(f"{path}: family {family} needs a {'prismatic' if family == 'drawer' else 'revolute'} "
                           "joint; the model has none")

    def part_mesh(l: _Link) -> trimesh.Trimesh:
        ms = [x.mesh for x in _subtree(links, l.name) if len(x.mesh.faces)]
        return trimesh.util.concatenate(ms) if ms else trimesh.Trimesh()

    main = max(movers, key=lambda l: part_mesh(l).area if len(part_mesh(l).faces) else 0.0)
    turn = abs(main.hi - main.lo)
    if MAIN_KIND[family] == "hinge" and turn < math.radians(MIN_LID_TURN_DEG):
        hint = (' (an MJCF\'s angles are degrees unless <compiler angle="radian"/>)' if path.suffix.lower() in
                (".xml", ".mjcf") else "")
        raise ImportError_(f"{path}: joint {main.joint}: its {PART[family]} turns {math.degrees(turn):.1f} deg; a "
                           f"{family}'s opens at least {MIN_LID_TURN_DEG:.0f} deg{hint}")
    pm = part_mesh(main)
    if len(pm.faces) == 0:
        raise ImportError_(f"{path}: the moving part of joint {main.joint} has no mesh")
    # closed end: a drawer deepest (its centre farthest from the opening), a lid lowest
    ends = []
    for q in (main.lo, main.hi):
        c = _move(pm, main, q).centroid
        ends.append(c)
    if family == "drawer":
        # the opening direction: the way the part moves from its deepest end; deepest = nearest the body centre
        body_c = trimesh.util.concatenate([l.mesh for l in links if len(l.mesh.faces)]).bounding_box.centroid
        d = [np.linalg.norm((e - body_c)[:2]) for e in ends]
        closed, opened = (main.lo, main.hi) if d[0] <= d[1] else (main.hi, main.lo)
        out_dir = main.axis * np.sign(opened - closed)
        yaw = math.atan2(-out_dir[1], -out_dir[0])  # turn out_dir onto -x
    else:
        closed, opened = (main.lo, main.hi) if ends[0][2] <= ends[1][2] else (main.hi, main.lo)
        c_closed = _move(pm, main, closed).centroid
        free = c_closed - main.anchor
        free -= main.axis * (free @ main.axis)
        yaw = math.atan2(-free[1], -free[0])  # the free edge toward -x: the hinge at the back
    Rz = trimesh.transformations.rotation_matrix(-yaw, [0, 0, 1])
    for l in links:  # to the closed position, then turned
        if l in _subtree(links, main.name):
            l.mesh = _move(l.mesh, main, closed) if len(l.mesh.faces) else l.mesh
            if l is not main:
                l.anchor = _point_move(l.anchor, main, closed)
    for l in links:
        if len(l.mesh.faces):
            l.mesh.apply_transform(Rz)
        l.anchor = Rz[:3, :3] @ l.anchor
        if l.axis is not None:
            l.axis = Rz[:3, :3] @ l.axis
    lo, hi = trimesh.util.concatenate([l.mesh for l in links if len(l.mesh.faces)]).bounds
    ctr = (lo + hi) / 2
    for l in links:
        if len(l.mesh.faces):
            l.mesh.apply_translation(-ctr)
        l.anchor = l.anchor - ctr
    links[0].anchor = np.zeros(3)
    rel = (main.lo - closed, main.hi - closed)  # joint range measured from the closed position (q = 0 there)
    main_range = (min(rel), max(rel))
    results = _points(family, links, main, part_mesh(main), lo - ctr, hi - ctr)
    ann = _annotations(family, type_id, req.description or f"{name.replace('_', ' ')} (imported {path.name})",
                       results, main, links, opened - closed, lo - ctr, hi - ctr)
    arrays, link_files = _meshes(links, main, main_range, family, req.mass)
    info = mf.ImportedModelFile(
        import_rules=mf.IMPORT_RULES,
        family=family, name=name, type_id=type_id, description=ann.description,
        source=mf.SourceInfo(file=path.name, sha256=req.sha256 or _sha(path),
                             format=path.suffix.lower().lstrip("."),
                             package=req.package, licence=req.licence),
        scale=factor, fitted=fitted if req.units.fit is not None else None, up=req.up or "z", material="wood",
        rgba=(0.7, 0.6, 0.5, 1.0), links=link_files, articulation=ann.articulation)
    tr = TransferResult(np.eye(4), ann, results, 0.0, yaw)
    warnings = [f"{p.name}: confidence {p.confidence:.2f} ({p.rule}); check it, and fix it in {mf.OVERRIDE_FILE}"
                for p in results if p.confidence < LOW_CONFIDENCE]
    warnings += fit_note(fitted, family, req.units.fit)
    return info, ann, tr, arrays, warnings


def _point_move(p: np.ndarray, link: _Link, q: float) -> np.ndarray:
    if link.kind == "slide":
        return p + q * link.axis
    return trimesh.transformations.transform_points([p], trimesh.transformations.rotation_matrix(
        q, link.axis, link.anchor))[0]


def _sha(path) -> str:
    import hashlib

    return hashlib.sha256(path.read_bytes()).hexdigest()


def _points(family: str, links: list[_Link], main: _Link, pm: trimesh.Trimesh, lo, hi) -> list[PointResult]:
    s = np.asarray(trimesh.sample.sample_surface(pm, 6000, seed=0)[0])
    plo, phi = pm.bounds
    ymid, pts = (plo[1] + phi[1]) / 2, []

    def P(name, xyz, conf=0.9, rule="", found=True):
        pts.append(PointResult(name, np.asarray(xyz, float), conf, rule, found))

    if family == "drawer":
        front = s[s[:, 0] < plo[0] + 0.3 * (phi[0] - plo[0])]
        hist, edges = np.histogram(front[:, 0], bins=max(4, int(np.ptp(front[:, 0]) / 0.002) + 1))
        strong = np.flatnonzero(hist >= 0.5 * hist.max())  # the panel's faces (front and back): the front one
        x_panel = float(edges[strong[0]] + (edges[1] - edges[0]) / 2)
        handle = s[s[:, 0] < x_panel - 0.006]
        if len(handle) >= 15:
            bar = handle[handle[:, 0] <= np.percentile(handle[:, 0], 50)]
            c = np.array([np.median(bar[:, 0]), np.median(bar[:, 1]), np.median(bar[:, 2])])
            h = max((np.percentile(bar[:, 2], 95) - np.percentile(bar[:, 2], 5)) / 2, 0.004)
            P("handle", c, rule="what stands out of the front panel")
            P("handle_upper", c + [0, 0, h], rule="top of the handle")
            P("handle_lower", c - [0, 0, h], rule="bottom of the handle")
            half = (phi[1] - plo[1]) / 2
            side = 1.0 if c[1] <= ymid else -1.0
            P("front", [x_panel, c[1] + side * 0.5 * half, c[2]], rule="panel beside the handle")
            P("head", [x_panel, c[1], c[2]], rule="panel at the handle's height")
        else:
            z = phi[2] - 0.25 * (phi[2] - plo[2])
            c = np.array([x_panel - 0.01, ymid, z])
            for n, dz in (("handle", 0.0), ("handle_upper", 0.006), ("handle_lower", -0.006)):
                P(n, c + [0, 0, dz], 0.3, "no handle stands out: on the panel", False)
            P("front", [x_panel, ymid + 0.3 * (phi[1] - plo[1]), z], 0.6, "panel")
            P("head", [x_panel, ymid, z], 0.6, "panel")
        cx = (plo[0] + phi[0]) / 2
        hits = ray_hits(pm.triangles, np.array([cx, ymid, phi[2] + 0.01]), np.array([0, 0, -1.0]))
        if len(hits):
            P("storage", [cx, ymid, phi[2] + 0.01 - hits[0] + 0.02], rule="over the drawer's inner bottom")
        else:
            P("storage", [cx, ymid, (plo[2] + phi[2]) / 2], 0.3, "no inner bottom found", False)
    else:
        edge = np.array([plo[0], ymid, _rim_height(s, plo, phi, ymid)])
        if family == "laptop":
            P("screen_edge", edge, rule="middle of the lid's front edge")
            P("screen_grip", edge + [0.015, 0, 0], rule="1.5 cm in from the edge")
            P("screen_back", [plo[0] + 0.02, ymid, _outer_face(pm, plo[0] + 0.02, ymid, phi[2])],
              rule="lid's outer face near the edge")
            P("screen_center", [(plo[0] + phi[0]) / 2, ymid, plo[2]], rule="under the lid's middle")
            base = trimesh.util.concatenate([l.mesh for l in links if l.parent is None and len(l.mesh.faces)])
            bl, bh = base.bounds
            P("keyboard", [(bl[0] + bh[0]) / 2, (bl[1] + bh[1]) / 2, bh[2]], rule="top of the base")
        else:
            P("lid_front", edge, rule="the lid's front edge")
            P("lid_grip", edge, rule="the lid's front edge (no tab: a grasp holds the edge itself)")
            P("lid_pinch", edge, rule="the lid's front edge (no tab: a pinch holds the edge itself)")
            P("lid_top", [plo[0] + 0.015, ymid, _outer_face(pm, plo[0] + 0.015, ymid, phi[2])],
              rule="lid's outer face 1.5 cm in")
            base = trimesh.util.concatenate([l.mesh for l in links if l.parent is None and len(l.mesh.faces)])
            bl, bh = base.bounds
            c = (bl + bh) / 2
            hits = ray_hits(base.triangles, np.array([c[0], c[1], bh[2] + 0.01]), np.array([0, 0, -1.0]))
            z = bh[2] + 0.01 - hits[0] + 0.01 if len(hits) else c[2]
            P("storage", [c[0], c[1], z], 0.9 if len(hits) else 0.3, "over the base's inner bottom", bool(len(hits)))
    P("center", np.zeros(3), 1.0, "centre")
    return pts


def _rim_height(s: np.ndarray, plo, phi, ymid: float) -> float:
    """Height of the middle of the lid's front rim: the surface within 4 mm of its front-most extent around the
    middle of its width. Not the middle of the part's bounds: a lid with a handle on top (Meta-World's box) would
    put its front edge in the air above the lid."""
    half = (phi[1] - plo[1]) / 2
    rim = s[(s[:, 0] < plo[0] + 0.004) & (np.abs(s[:, 1] - ymid) < 0.5 * half)]
    if len(rim) < 5:
        rim = s[s[:, 0] < plo[0] + 0.004]
    if len(rim) < 5:
        return float((plo[2] + phi[2]) / 2)
    return float((np.percentile(rim[:, 2], 2) + np.percentile(rim[:, 2], 98)) / 2)


def _outer_face(pm: trimesh.Trimesh, x: float, y: float, top: float) -> float:
    """Height of the part's upper surface at (x, y), seen from above; the part's top where nothing is hit."""
    hits = ray_hits(pm.triangles, np.array([x, y, top + 0.01]), np.array([0, 0, -1.0]))
    return float(top + 0.01 - hits[0]) if len(hits) else float(top)


def _annotations(family, type_id, description, results, main: _Link, links, travel, lo, hi) -> ObjectAnnotations:
    from humanoidgen.objects import library

    tann = library.family(family).base.annotations(0)
    part = PART[family]
    on_part = {p.name for p in tann.points if p.part is not None}
    points = []
    for r in results:
        pos = r.position - main.anchor if r.name in on_part else r.position
        points.append(KeyPoint(name=r.name, position=tuple(round(float(v), 5) for v in pos),
                               part=part if r.name in on_part else None,
                               description=next((p.description for p in tann.points if p.name == r.name), "")))
    art = Articulation(joint=f"{part}_joint", closed=0.0, open=float(travel))
    return ObjectAnnotations(family=family, type_id=type_id, description=description,
                             bbox_min=tuple(float(v) for v in lo), bbox_max=tuple(float(v) for v in hi),
                             points=points, axes=tann.axes, operations=tann.operations, functions=tann.functions,
                             articulation=art)


def _dynamics(family: str) -> dict:
    """The family template's joint damping and friction loss (a part stays where a hand leaves it)."""
    from humanoidgen.objects import library

    p = library.family(family).base._model(0).params
    return dict(p["slide"] if family == "drawer" else p["hinge"])


def _meshes(links: list[_Link], main: _Link, main_range, family: str, mass: float | None):
    arrays, files = {}, []
    names = {l.name: PART[family] if l is main else f"l{k}" for k, l in enumerate(links)}
    dyn = _dynamics(family)
    kept = [l for l in links if len(l.mesh.faces) or l.kind]
    vols = {}
    for l in kept:
        key = names[l.name]
        if len(l.mesh.faces):
            local = l.mesh.copy()
            local.apply_translation(-l.anchor)
            parts = convex_parts(coarse(local))
            arrays[f"{key}_v"], arrays[f"{key}_f"] = (np.asarray(local.vertices, np.float32),
                                                      np.asarray(local.faces, np.int32))
        else:  # an empty link: a tiny hidden part so the body has mass
            parts = [trimesh.creation.box(extents=(0.01, 0.01, 0.01))]
            arrays[f"{key}_v"], arrays[f"{key}_f"] = (np.asarray(parts[0].vertices, np.float32),
                                                      np.asarray(parts[0].faces, np.int32))
        for k, p in enumerate(parts):
            arrays[f"{key}_c{k}_v"], arrays[f"{key}_c{k}_f"] = (np.asarray(p.vertices, np.float32),
                                                                np.asarray(p.faces, np.int32))
        vols[l.name] = (len(parts), sum(p.volume for p in parts))
    total = sum(v for _, v in vols.values()) or 1.0
    for l in kept:
        parent = l.parent
        while parent is not None and parent not in vols:
            parent = next(x.parent for x in links if x.name == parent)
        panchor = next(x.anchor for x in links if x.name == parent) if parent else np.zeros(3)
        joint = None
        if l.kind:
            rng = main_range if l is main else (min(l.lo, l.hi), max(l.lo, l.hi))
            jname = f"{PART[family]}_joint" if l is main else f"j_{names[l.name]}"
            joint = mf.JointFile(name=jname, kind=l.kind, axis=tuple(float(v) for v in l.axis),
                                 range=(float(rng[0]), float(rng[1])), damping=dyn["damping"],
                                 frictionloss=dyn["frictionloss"])
        m = (mass or 2.0) * vols[l.name][1] / total
        files.append(mf.LinkFile(name=names[l.name], parent=names[parent] if parent else None,
                                 pos=tuple(float(v) for v in (l.anchor - panchor)) if parent else (0.0, 0.0, 0.0),
                                 joint=joint, mass=float(np.clip(m, 0.02, 5.0)), collision_parts=vols[l.name][0]))
    return arrays, files
