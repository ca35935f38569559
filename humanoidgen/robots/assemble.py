"""A robot's model as MuJoCo reads it, before this project's changes (`sim.robot`): its upstream MJCF, and where
its robot file takes its hands from another robot's model (`hands.source`), those hands attached with
`mujoco.MjSpec` in place of its own.

Attaching the hands of the source model: on each side, every child body of the source's mount whose name is a
hand name (`<prefix>_...`), with its joints, geoms and the meshes they draw, is attached to this robot's mount at
the same pose; the hand meshes the source's mount itself carries (the palm) are drawn on this robot's mount at
the same pose. The source's couplings (its URDF's <mimic> tags) then couple the followers (`mimic_urdf`).
"""

from __future__ import annotations

from pathlib import Path

import mujoco

from humanoidgen.robots.loader import Robot
from humanoidgen.robots.schema import SIDE_NAMES

_MESH = mujoco.mjtGeom.mjGEOM_MESH
# Attached elements get this prefix (an empty one makes MuJoCo warn), removed again once they are in.
_TMP_PREFIX = "hgen_attach:"
_GEOM_FIELDS = ("type", "pos", "quat", "contype", "conaffinity", "group", "density", "rgba", "friction",
                "solref", "solimp", "condim", "priority", "margin", "gap")


def model_dir(assets_root: Path, robot: Robot) -> Path:
    return Path(assets_root) / robot.data.model.folder


def mjcf_path(assets_root: Path, robot: Robot) -> Path:
    return model_dir(assets_root, robot) / robot.data.model.mjcf


def mimic_urdf(assets_root: Path, robot: Robot) -> Path | None:
    """The URDF whose <mimic> tags couple the hands' followers: the hands' source's, else the robot's own."""
    if robot.hand.data.followers != "urdf_mimic":
        return None
    owner = robot.hand_source or robot
    urdf = owner.data.model.urdf
    return None if urdf is None else model_dir(assets_root, owner) / urdf


def mesh_file(spec: mujoco.MjSpec, model_folder: Path, mesh: mujoco.MjsMesh) -> Path:
    """The file a mesh of `spec` (read from `model_folder`) is drawn from: absolute ones are attached ones."""
    f = Path(mesh.file)
    return f if f.is_absolute() else model_folder / spec.meshdir / f


def model_spec(assets_root: Path, robot: Robot) -> mujoco.MjSpec:
    """The robot's model: its MJCF, with its hands taken from `hands.source`'s model where the file says so."""
    spec = mujoco.MjSpec.from_file(str(mjcf_path(assets_root, robot)))
    source = robot.hand_source
    if source is not None:
        _remove_own_hands(spec, robot)
        for side in SIDE_NAMES:
            _attach_hand(spec, robot, source, side, assets_root)
    return spec


def _remove_own_hands(spec: mujoco.MjSpec, robot: Robot) -> None:
    remove = robot.data.hands.source.remove  # type: ignore[union-attr]
    meshes = set(remove.meshes)
    for geom in list(spec.geoms):
        if geom.type == _MESH and geom.meshname in meshes:
            spec.delete(geom)
    for name in remove.meshes:
        spec.delete(spec.mesh(name))
    for name in remove.geoms:
        spec.delete(spec.geom(name))
    for name in remove.sites:
        spec.delete(spec.site(name))


def _attach_hand(spec: mujoco.MjSpec, robot: Robot, source: Robot, side: str, assets_root: Path) -> None:
    # A fresh copy of the source model per side, stripped to this hand's meshes: attaching copies every mesh
    # of the source, and two copies of one name (or a leg mesh named like this robot's) would clash.
    src_spec = model_spec(assets_root, source)
    folder = model_dir(assets_root, source)
    for mesh in src_spec.meshes:  # absolute: the attached meshes live in the source's folder
        mesh.file = str(mesh_file(src_spec, folder, mesh))
    src_mount = src_spec.body(source.hand_mount(side))
    bodies = [b for b in src_mount.bodies if robot.is_hand_name(b.name, side)]
    palm = [g for g in src_mount.geoms if g.type == _MESH and robot.is_hand_name(g.meshname, side)]
    keep = {g.meshname for g in palm}
    for b in bodies:
        keep |= {g.meshname for g in b.find_all(mujoco.mjtObj.mjOBJ_GEOM) if g.type == _MESH}
    for geom in list(src_spec.geoms):
        if geom.type == _MESH and geom.meshname not in keep:
            src_spec.delete(geom)
    for mesh in list(src_spec.meshes):
        if mesh.name not in keep:
            src_spec.delete(mesh)
    for element in (*src_spec.actuators, *src_spec.sensors, *src_spec.equalities):  # the build adds its own
        src_spec.delete(element)
    mount = spec.body(robot.hand_mount(side))
    for b in bodies:
        mount.add_frame().attach_body(b, _TMP_PREFIX, "")
    _drop_prefix(spec)
    for g in palm:
        mount.add_geom(meshname=g.meshname, **{k: getattr(g, k) for k in _GEOM_FIELDS})


def _drop_prefix(spec: mujoco.MjSpec) -> None:
    n = len(_TMP_PREFIX)
    for kind in ("bodies", "joints", "geoms", "meshes", "sites", "materials", "cameras", "lights"):
        for element in getattr(spec, kind):
            if element.name.startswith(_TMP_PREFIX):
                element.name = element.name[n:]
    for geom in spec.geoms:
        if geom.meshname.startswith(_TMP_PREFIX):
            geom.meshname = geom.meshname[n:]
        if geom.material.startswith(_TMP_PREFIX):
            geom.material = geom.material[n:]


def model_names(assets_root: Path, robot: Robot) -> tuple[list[str], list[str]]:
    """The joint and body names of the robot's model (its hands attached)."""
    spec = model_spec(assets_root, robot)
    return [j.name for j in spec.joints], [b.name for b in spec.bodies]


__all__ = ["mesh_file", "mimic_urdf", "model_dir", "model_names", "model_spec"]
