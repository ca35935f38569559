"""URDF as PartNet-Mobility ships it (`mobility.urdf` beside its meshes): links with visual meshes, revolute,
continuous and prismatic joints (a joint's child link moves); fixed joints merge their child into the parent."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import trimesh

from humanoidgen.objects.imported.formats import ImportError_, SourceJoint, SourceLink, SourceModel

_KINDS = {"revolute": "hinge", "continuous": "hinge", "prismatic": "slide", "fixed": None}


def _origin(el) -> np.ndarray:
    T = np.eye(4)
    o = el.find("origin") if el is not None else None
    if o is not None:
        xyz = [float(v) for v in o.get("xyz", "0 0 0").split()]
        rpy = [float(v) for v in o.get("rpy", "0 0 0").split()]
        T = trimesh.transformations.euler_matrix(*rpy, axes="sxyz")
        T[:3, 3] = xyz
    return T


class UrdfFormat:
    name = "URDF"
    suffixes = (".urdf",)

    def load(self, path: Path) -> SourceModel:
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as exc:
            raise ImportError_(f"{path}: not valid XML ({exc})") from None
        if root.tag != "robot":
            raise ImportError_(f"{path}: not a URDF (the root element is <{root.tag}>, not <robot>)")
        meshes = {}
        for link in root.findall("link"):
            parts = []
            for vis in link.findall("visual") or link.findall("collision"):
                geom = vis.find("geometry/mesh")
                if geom is None:
                    continue
                file = (path.parent / geom.get("filename", "").replace("package://", "")).resolve()
                if not file.is_file():
                    raise ImportError_(f"{path}: link {link.get('name')}: mesh {geom.get('filename')} is missing")
                try:
                    m = trimesh.load(str(file), force="mesh", process=False)
                except Exception as exc:
                    raise ImportError_(f"{path}: mesh {file.name} cannot be read ({type(exc).__name__})") from None
                scale = [float(v) for v in geom.get("scale", "1 1 1").split()]
                m.apply_scale(scale)
                m.apply_transform(_origin(vis))
                parts.append(m)
            meshes[link.get("name")] = parts
        joints = {}
        for j in root.findall("joint"):
            kind = _KINDS.get(j.get("type"))
            if j.get("type") not in _KINDS:
                raise ImportError_(f"{path}: joint {j.get('name')}: type {j.get('type')!r} is not supported "
                                   "(revolute, continuous, prismatic, fixed)")
            lim = j.find("limit")
            lo = float(lim.get("lower", 0)) if lim is not None else 0.0
            hi = float(lim.get("upper", 0)) if lim is not None else 0.0
            if j.get("type") == "continuous" or hi <= lo:
                lo, hi = (0.0, math.pi / 2) if kind == "hinge" else (lo, hi)
            axis = np.array([float(v) for v in (j.find("axis").get("xyz") if j.find("axis") is not None
                                                else "1 0 0").split()])
            joints[j.find("child").get("link")] = (j.find("parent").get("link"), _origin(j), kind,
                                                   SourceJoint(j.get("name"), kind, tuple(axis / np.linalg.norm(axis)),
                                                               lo, hi) if kind else None)
        if not any(v[3] for v in joints.values()):
            raise ImportError_(f"{path}: the URDF has no revolute or prismatic joint: import a rigid mesh instead")
        return SourceModel(_merge_fixed(meshes, joints, path))


def _merge_fixed(meshes: dict, joints: dict, path: Path) -> list[SourceLink]:
    """Links in tree order, each child of a fixed joint merged into its parent (its meshes moved there)."""
    roots = [n for n in meshes if n not in joints]
    if len(roots) != 1:
        raise ImportError_(f"{path}: expected one root link, found {roots}")
    children: dict[str, list[str]] = {}
    for child, (parent, *_rest) in joints.items():
        children.setdefault(parent, []).append(child)
    links: list[SourceLink] = []
    owner: dict[str, tuple[str, np.ndarray]] = {}

    def visit(name: str, parent_link: str | None, T_in_owner: np.ndarray, joint, origin):
        if joint is None and parent_link is not None:  # fixed: belongs to the parent's link
            own, T = owner[parent_link]
            owner[name] = (own, T @ origin)
            target = next(l for l in links if l.name == own)
            for m in meshes[name]:
                mm = m.copy()
                mm.apply_transform(T @ origin)
                target.mesh = trimesh.util.concatenate([target.mesh, mm]) if len(target.mesh.faces) else mm
        else:
            parent_owner = owner[parent_link] if parent_link else (None, np.eye(4))
            full = parent_owner[1] @ origin if parent_link else np.eye(4)
            mesh = trimesh.util.concatenate(meshes[name]) if meshes[name] else trimesh.Trimesh()
            links.append(SourceLink(name, mesh, parent_owner[0], full, joint))
            owner[name] = (name, np.eye(4))
        for c in children.get(name, []):
            parent, origin_c, _kind, joint_c = joints[c]
            visit(c, name, None, joint_c, origin_c)

    visit(roots[0], None, np.eye(4), None, np.eye(4))
    return links
