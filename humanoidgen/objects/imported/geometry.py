"""Checks and normalisation of an imported mesh: what makes it unusable (no faces, not finite, flat, open,
absurd size), and the turn and scale that put it in the family's canonical frame (metres, z up)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import trimesh

from humanoidgen.objects.imported.formats import ImportError_

UpAxis = Literal["x", "y", "z", "-x", "-y", "-z"]
# An object on the table is between these sizes (largest extent, m): past them the units are wrong.
MIN_SIZE, MAX_SIZE = 0.01, 1.5


@dataclass(frozen=True)
class Units:
    """How to scale a file's coordinates to metres: `scale` times, or to a largest extent of `size` m; then, with
    `fit` (lo, hi), into that range of largest extents (the family's: `sizing.family_size_range`)."""

    scale: float | None = None
    size: float | None = None
    fit: tuple[float, float] | None = None


def fit_factor(largest: float, fit: tuple[float, float] | None) -> float:
    """The factor that brings a largest extent of `largest` m into the range `fit` (1 inside it, or without one)."""
    if fit is None or largest <= 0.0:
        return 1.0
    return min(max(largest, fit[0]), fit[1]) / largest


def up_rotation(up: UpAxis) -> np.ndarray:
    """The 3x3 rotation that turns the file's `up` axis into +z."""
    sign = -1.0 if up.startswith("-") else 1.0
    v = sign * np.eye(3)["xyz".index(up[-1])]
    z = np.array([0.0, 0.0, 1.0])
    if np.allclose(v, z):
        return np.eye(3)
    if np.allclose(v, -z):
        return np.diag([1.0, -1.0, -1.0])
    axis = np.cross(v, z)
    axis /= np.linalg.norm(axis)
    return trimesh.transformations.rotation_matrix(np.pi / 2, axis)[:3, :3]


def check_mesh(mesh: trimesh.Trimesh, where: str, allow_open: bool) -> None:
    """One-line errors for a mesh nothing can be made of."""
    if len(mesh.faces) == 0 or len(mesh.vertices) < 4:
        raise ImportError_(f"{where}: the mesh has no faces")
    if not np.isfinite(mesh.vertices).all():
        raise ImportError_(f"{where}: the mesh has vertices that are not finite numbers")
    ext = mesh.extents
    if np.min(ext) <= 1e-4 * max(np.max(ext), 1e-12) or mesh.area <= 0.0:
        raise ImportError_(f"{where}: the mesh is flat or degenerate (extents {_fmt(ext)}): no solid to grasp")
    if not allow_open:
        merged = trimesh.Trimesh(mesh.vertices, mesh.faces, process=True)
        merged.merge_vertices(merge_tex=True, merge_norm=True)
        if not merged.is_watertight:
            open_edges = len(trimesh.grouping.group_rows(merged.edges_sorted, require_count=1))
            raise ImportError_(f"{where}: the mesh is not watertight ({open_edges} open edges, "
                               f"{'manifold' if merged.is_winding_consistent else 'non-manifold'}); repair it, "
                               "or pass --allow-open to import it as a surface")


def to_metres(mesh: trimesh.Trimesh, units: Units, where: str) -> float:
    """The factor that brings the mesh to metres; errors for a size no table object has."""
    largest = float(np.max(mesh.extents))
    if units.size is not None:
        factor = units.size / largest
    else:
        factor = units.scale if units.scale is not None else 1.0
    size = largest * factor
    if not MIN_SIZE <= size <= MAX_SIZE:
        hint = ("pass --scale 0.001 for millimetres, 0.01 for centimetres, or --size METRES"
                if size > MAX_SIZE else "pass --scale or --size METRES")
        raise ImportError_(f"{where}: the object would be {size:.3g} m across (allowed {MIN_SIZE}-{MAX_SIZE} m): "
                           f"wrong units? {hint}")
    return factor


def _fmt(v) -> str:
    return "[" + ", ".join(f"{x:.4g}" for x in v) + "]"
