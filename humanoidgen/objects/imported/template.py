"""A family's annotated template as a surface: the primitives of its model type_id 0 (objects/rigid.py) as one
triangle mesh, and ray casts against a triangle mesh (numpy, no spatial index: a few rays per point)."""

from __future__ import annotations

import numpy as np
import trimesh

from humanoidgen.objects.rigid import Geometry, Prim
from humanoidgen.sim.geometry import quat_to_mat


def prims_mesh(prims: list[Prim]) -> trimesh.Trimesh:
    """The primitives' surfaces as one mesh (a soup: overlapping parts are not merged)."""
    parts = []
    for p in prims:
        tf = np.eye(4)
        tf[:3, :3] = quat_to_mat(p.quat)
        tf[:3, 3] = p.pos
        if p.kind == "box":
            parts.append(trimesh.creation.box(extents=2.0 * np.asarray(p.size), transform=tf))
        else:
            parts.append(trimesh.creation.cylinder(radius=p.size[0], height=2.0 * p.size[1], sections=48,
                                                   transform=tf))
    return trimesh.util.concatenate(parts)


def template_mesh(geo: Geometry) -> trimesh.Trimesh:
    return prims_mesh(geo.prims)


def ray_hits(triangles: np.ndarray, origin: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """Distances along the ray (origin + t * direction, t > 0) at which it crosses the triangles (sorted)."""
    v0, v1, v2 = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    e1, e2 = v1 - v0, v2 - v0
    p = np.cross(direction, e2)
    det = np.einsum("ij,ij->i", e1, p)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - v0
    u = np.einsum("ij,ij->i", s, p) * inv
    q = np.cross(s, e1)
    v = (q @ direction) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-9)
    return np.sort(t[hit])
