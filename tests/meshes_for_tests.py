"""Small meshes made in the tests (no files from elsewhere): a mug (a revolved wall with a ring handle), a
bottle, a bowl, and a two-link URDF with a prismatic joint (a drawer in its case)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh


def mug(radius: float = 0.04, height: float = 0.095, wall: float = 0.005, handle: bool = True) -> trimesh.Trimesh:
    """A watertight mug, z up, its handle on +x (so an import has to turn it to the family's +y)."""
    r0, r1, b = radius - wall, radius, 0.008
    profile = np.array([[0.0, 0.0], [r1, 0.0], [r1, height], [r0, height], [r0, b], [0.0, b]])
    body = trimesh.creation.revolve(profile, sections=48)
    if not handle:
        return body
    ring = trimesh.creation.torus(major_radius=0.025, minor_radius=0.005, major_sections=32, minor_sections=12)
    ring.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [1, 0, 0]))
    ring.apply_translation([r1 + 0.012, 0.0, 0.55 * height])
    return trimesh.util.concatenate([body, ring])


def bottle(radius: float = 0.035, height: float = 0.22) -> trimesh.Trimesh:
    profile = np.array([[0.0, 0.0], [radius, 0.0], [radius, 0.65 * height], [0.013, 0.82 * height],
                        [0.013, height], [0.0, height]])
    return trimesh.creation.revolve(profile, sections=48)


def drawer_urdf(folder: Path, slide_axis: str = "-1 0 0") -> Path:
    """A case open toward -x and a drawer (with a bar handle) sliding out along -x; with `slide_axis`
    "0 1 0" the whole model is turned so that it slides out along +y."""
    folder.mkdir(parents=True, exist_ok=True)
    case = trimesh.util.concatenate([_box((0.30, 0.02, 0.20), (0, -0.14, 0)), _box((0.30, 0.02, 0.20), (0, 0.14, 0)),
                                     _box((0.30, 0.30, 0.02), (0, 0, 0.09)), _box((0.30, 0.30, 0.02), (0, 0, -0.09)),
                                     _box((0.02, 0.30, 0.20), (0.14, 0, 0))])
    drawer = trimesh.util.concatenate([_box((0.26, 0.25, 0.01), (0, 0, -0.07)),
                                       _box((0.02, 0.25, 0.15), (-0.135, 0, 0)),
                                       _box((0.02, 0.08, 0.02), (-0.16, 0, 0.02))])
    if slide_axis == "0 1 0":  # turned by -90 deg about z: -x becomes +y
        turn = trimesh.transformations.rotation_matrix(-np.pi / 2, [0, 0, 1])
        case.apply_transform(turn)
        drawer.apply_transform(turn)
    case.export(folder / "case.obj")
    drawer.export(folder / "drawer.obj")
    (folder / "mobility.urdf").write_text(f"""<?xml version="1.0"?>
<robot name="drawer">
  <link name="base"><visual><geometry><mesh filename="case.obj"/></geometry></visual></link>
  <link name="drawer_link"><visual><geometry><mesh filename="drawer.obj"/></geometry></visual></link>
  <joint name="slide" type="prismatic">
    <parent link="base"/><child link="drawer_link"/>
    <origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="{slide_axis}"/><limit lower="0" upper="0.2"/>
  </joint>
</robot>
""")
    return folder / "mobility.urdf"


def _box(extents, pos) -> trimesh.Trimesh:
    b = trimesh.creation.box(extents=extents)
    b.apply_translation(pos)
    return b
