"""An imported model in a scene: its links as bodies (the root is the object's body), its joints, a visual
mesh per link (textured where the file was) and its convex collision parts, hidden like the robot's."""

from __future__ import annotations

import mujoco
import numpy as np

from humanoidgen.objects.family_data import material
from humanoidgen.objects.imported.model_file import ImportedModel

COLLISION_GROUP = 3  # hidden in renders, as the robot's collision meshes (sim/robot.py)
TEXTURE_FILE = "texture.png"


def build_imported(spec: mujoco.MjSpec, body: mujoco.MjsBody, model: ImportedModel) -> None:
    """Fill `body` (placed, named "<family>_<obj_id>") with the model's links, joints and geoms."""
    arrays = model.meshes()
    info = model.info
    friction = list(material(info.material))
    bodies = {}
    mat = _material(spec, body.name, model)
    for link in info.links:
        if link.parent is None:
            b = body
        else:
            b = bodies[link.parent].add_body(name=f"{body.name}_{link.name}", pos=list(link.pos),
                                             quat=list(link.quat))
            # The object's parts never touch each other: their convex parts overlap where the meshes are concave
            # (a drawer in its case, drawers side by side), and MuJoCo does not filter a child of a body fixed to
            # the world by itself.
            for other in bodies.values():
                spec.add_exclude(bodyname1=other.name, bodyname2=b.name)
        bodies[link.name] = b
        if link.joint is not None:
            j = link.joint
            b.add_joint(name=f"{body.name}_{j.name}", type=mujoco.mjtJoint.mjJNT_SLIDE if j.kind == "slide"
                        else mujoco.mjtJoint.mjJNT_HINGE, axis=list(j.axis), range=list(j.range),
                        limited=mujoco.mjtLimited.mjLIMITED_TRUE, damping=j.damping, frictionloss=j.frictionloss,
                        armature=0.005)
        vis = f"{body.name}_{link.name}_vis"
        kw = {}
        if link.textured and f"{link.name}_uv" in arrays:
            uv = arrays[f"{link.name}_uv"].astype(float)
            # MuJoCo's image rows run top down; a mesh file's v runs bottom up (as MuJoCo's own OBJ reader flips)
            kw["usertexcoord"] = np.column_stack([uv[:, 0], 1.0 - uv[:, 1]]).ravel().tolist()
        spec.add_mesh(name=vis, uservert=arrays[f"{link.name}_v"].ravel().tolist(),
                      userface=arrays[f"{link.name}_f"].ravel().tolist(), **kw)
        vkw = {"material": mat} if (mat and link.textured) else {"rgba": list(info.rgba)}
        b.add_geom(name=vis, type=mujoco.mjtGeom.mjGEOM_MESH, meshname=vis, contype=0, conaffinity=0,
                   density=0.0, **vkw)
        vols = [_volume(arrays[f"{link.name}_c{k}_v"], arrays[f"{link.name}_c{k}_f"])
                for k in range(link.collision_parts)]
        total = sum(vols) or 1.0
        for k in range(link.collision_parts):
            name = f"{body.name}_{link.name}_c{k}"
            spec.add_mesh(name=name, uservert=arrays[f"{link.name}_c{k}_v"].ravel().tolist(),
                          userface=arrays[f"{link.name}_c{k}_f"].ravel().tolist())
            b.add_geom(name=name, type=mujoco.mjtGeom.mjGEOM_MESH, meshname=name, group=COLLISION_GROUP,
                       mass=max(link.mass * vols[k] / total, 1e-4), friction=friction, condim=4,
                       rgba=[0.5, 0.5, 0.5, 1.0])


def _material(spec: mujoco.MjSpec, prefix: str, model: ImportedModel) -> str | None:
    path = model.folder / TEXTURE_FILE
    if not path.is_file():
        return None
    tex = spec.add_texture(name=f"{prefix}_tex", type=mujoco.mjtTexture.mjTEXTURE_2D, file=str(path.resolve()))
    mat = spec.add_material(name=f"{prefix}_mat", rgba=[1, 1, 1, 1])
    textures = [""] * 10
    textures[int(mujoco.mjtTextureRole.mjTEXROLE_RGB)] = tex.name
    mat.textures = textures
    return mat.name


def _volume(v: np.ndarray, f: np.ndarray) -> float:
    tri = v[f]
    return abs(float(np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum()) / 6.0)
