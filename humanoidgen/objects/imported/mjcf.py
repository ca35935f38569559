"""MJCF (a MuJoCo model of one object): its bodies with mesh or primitive geoms become links, its hinge and
slide joints the links' joints (compiled by MuJoCo, so includes, defaults and mesh scales are MuJoCo's)."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import trimesh

from humanoidgen.objects.imported.formats import ImportError_, SourceJoint, SourceLink, SourceModel


class MjcfFormat:
    name = "MJCF"
    suffixes = (".xml", ".mjcf")

    def load(self, path: Path) -> SourceModel:
        try:
            model = mujoco.MjModel.from_xml_path(str(path))
        except ValueError as exc:
            raise ImportError_(f"{path}: MuJoCo cannot load it: {' '.join(str(exc).split())[:160]}") from None
        data = mujoco.MjData(model)
        mujoco.mj_forward(model, data)
        links: list[SourceLink] = []
        names: dict[int, str] = {}
        frame: dict[int, int] = {}  # body -> the body whose frame its link uses (a welded body: its link's)
        for b in range(1, model.nbody):
            mesh = _body_mesh(model, b)
            jnt = [j for j in range(model.njnt) if model.jnt_bodyid[j] == b
                   and int(model.jnt_type[j]) in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))]
            parent = int(model.body_parentid[b])
            pname = names.get(parent)
            # Frames are taken relative to the link's own body, not the parent body: a body welded in between
            # may be turned (LIBERO's short cabinet turns its case by a quaternion, the drawers with it).
            if not jnt and pname is not None:  # welded: part of its parent's link
                mesh.apply_transform(_rel(model, data, frame[parent], b))
                owner = next(l for l in links if l.name == pname)
                owner.mesh = trimesh.util.concatenate([owner.mesh, mesh])
                names[b], frame[b] = pname, frame[parent]
                continue
            name = model.body(b).name or f"body{b}"
            joint = None
            if jnt:
                j = jnt[0]
                kind = "hinge" if int(model.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_HINGE) else "slide"
                lo, hi = model.jnt_range[j] if model.jnt_limited[j] else (0.0, 1.57 if kind == "hinge" else 0.2)
                joint = SourceJoint(model.joint(j).name or f"joint{j}", kind, tuple(model.jnt_axis[j]), float(lo),
                                    float(hi))
            T = _rel(model, data, frame[parent], b) if pname is not None else _world(data, b)
            links.append(SourceLink(name, mesh, pname, T, joint))
            names[b], frame[b] = name, b
        if not links or not any(l.joint for l in links):
            raise ImportError_(f"{path}: the MJCF has no hinge or slide joint: import a rigid mesh instead")
        return SourceModel([l for l in links if len(l.mesh.faces) or l.joint])


def _world(data, b) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = data.xmat[b].reshape(3, 3)
    T[:3, 3] = data.xpos[b]
    return T


def _rel(model, data, parent: int, b: int) -> np.ndarray:
    return np.linalg.inv(_world(data, parent)) @ _world(data, b)


def _body_mesh(model: mujoco.MjModel, b: int) -> trimesh.Trimesh:
    """The body's look: its visual geoms (no contacts) where it has some, else every visible geom."""
    mine = [g for g in range(model.ngeom) if model.geom_bodyid[g] == b]
    visual = [g for g in mine if model.geom_contype[g] == 0 and model.geom_conaffinity[g] == 0
              and int(model.geom_type[g]) == int(mujoco.mjtGeom.mjGEOM_MESH)]
    parts = []
    for g in visual or mine:
        if model.geom_rgba[g][3] == 0 and not visual:
            continue
        T = np.eye(4)
        q = model.geom_quat[g]
        mat = np.zeros(9)
        mujoco.mju_quat2Mat(mat, q)
        T[:3, :3] = mat.reshape(3, 3)
        T[:3, 3] = model.geom_pos[g]
        t, s = model.geom_type[g], model.geom_size[g]
        t = int(t)
        if t == int(mujoco.mjtGeom.mjGEOM_MESH):
            mid = model.geom_dataid[g]
            va, vn = model.mesh_vertadr[mid], model.mesh_vertnum[mid]
            fa, fn = model.mesh_faceadr[mid], model.mesh_facenum[mid]
            m = trimesh.Trimesh(model.mesh_vert[va:va + vn].copy(), model.mesh_face[fa:fa + fn].copy(), process=False)
        elif t == int(mujoco.mjtGeom.mjGEOM_BOX):
            m = trimesh.creation.box(extents=2 * s)
        elif t == int(mujoco.mjtGeom.mjGEOM_CYLINDER):
            m = trimesh.creation.cylinder(radius=s[0], height=2 * s[1], sections=32)
        elif t == int(mujoco.mjtGeom.mjGEOM_CAPSULE):
            m = trimesh.creation.capsule(radius=s[0], height=2 * s[1])
        elif t == int(mujoco.mjtGeom.mjGEOM_SPHERE):
            m = trimesh.creation.icosphere(radius=s[0], subdivisions=2)
        else:
            continue
        m.apply_transform(T)
        parts.append(m)
    return trimesh.util.concatenate(parts) if parts else trimesh.Trimesh()
