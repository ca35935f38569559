"""The Unitree H1-2 upper body with two Inspire hands, built with MjSpec from the upstream MJCF.

What changes against upstream, and why:
- the floating base, the legs and the torso are welded: the robot stands at a table and only its arms move;
- the upstream torque motors are replaced by position actuators on the 14 arm joints and the 12 actuated
  hand joints (the 26-D action), with gains sized to each joint's torque limit;
- each hand's follower joints are tied to their driver by equality constraints read from the URDF's mimic tags;
- arms and hands get gravity compensation, as the real robot's low-level controller provides it;
- a site per hand marks the end-effector frame the planner API names (`l_hand_base_link`, `r_hand_base_link`).
- visual geoms draw decimated copies of the meshes (`sim.meshes`); meshes no geom uses then are dropped.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from humanoidgen.sim.meshes import DEFAULT_MAX_FACES, visual_mesh
from humanoidgen.sim.layout import (
    ARM_JOINTS,
    HAND_BASE_FRAME,
    HAND_BASE_ON_WRIST_POS,
    HAND_BASE_ON_WRIST_QUAT,
    HAND_JOINTS,
    HAND_PREFIX,
    ROBOT_BASE_POS,
    SIDES,
    WRIST_BODY,
    arm_bodies,
)

# Position gains (N·m/rad) by joint group; damping is set for a well-damped response with the armature below.
ARM_KP = {"shoulder": 400.0, "elbow": 250.0, "wrist": 80.0}
ARM_KV_RATIO = 0.1  # kv = ratio * kp
ARM_ARMATURE = 0.02
HAND_KP = 3.0
HAND_KV = 0.05
HAND_ARMATURE = 0.0005
HAND_DAMPING = 0.02


@dataclass(frozen=True)
class Mimic:
    """follower = multiplier * driver + offset (URDF <mimic>)."""

    follower: str
    driver: str
    multiplier: float
    offset: float


def read_mimics(urdf_path: Path) -> list[Mimic]:
    """Read every <mimic> tag of a URDF."""
    root = ET.parse(urdf_path).getroot()
    mimics = []
    for joint in root.iter("joint"):
        tag = joint.find("mimic")
        if tag is not None:
            mimics.append(
                Mimic(
                    follower=joint.attrib["name"],
                    driver=tag.attrib["joint"],
                    multiplier=float(tag.attrib.get("multiplier", 1.0)),
                    offset=float(tag.attrib.get("offset", 0.0)),
                )
            )
    return mimics


def _arm_kp(joint: str) -> float:
    for key, kp in ARM_KP.items():
        if key in joint:
            return kp
    raise KeyError(joint)


def driver_ctrl_range(spec: mujoco.MjSpec, driver: str, mimics: list[Mimic]) -> tuple[float, float]:
    """The driver's range, narrowed so that no follower is pushed past its own joint limit."""
    lo, hi = spec.joint(driver).range
    for m in mimics:
        if m.driver != driver:
            continue
        flo, fhi = spec.joint(m.follower).range
        a, b = sorted(((flo - m.offset) / m.multiplier, (fhi - m.offset) / m.multiplier))
        lo, hi = max(lo, a), min(hi, b)
    return float(lo), float(hi)


def _weld_everything_but_arms(spec: mujoco.MjSpec) -> None:
    movable = {j for side in SIDES for j in ARM_JOINTS[side]}
    movable |= {j.name for j in spec.joints if j.name[:2] in ("L_", "R_")}
    for joint in list(spec.joints):
        if joint.name not in movable:
            spec.delete(joint)


def _disable_static_collisions(spec: mujoco.MjSpec) -> None:
    """Legs and pelvis can never touch anything the arms reach; keep them out of collision detection."""
    for name in ("left_hip_yaw_link", "right_hip_yaw_link"):
        for geom in spec.body(name).find_all(mujoco.mjtObj.mjOBJ_GEOM):
            geom.contype = 0
            geom.conaffinity = 0
    for geom in spec.body("pelvis").geoms:
        geom.contype = 0
        geom.conaffinity = 0


def _add_actuators(spec: mujoco.MjSpec, mimics: list[Mimic]) -> None:
    for act in list(spec.actuators):
        spec.delete(act)
    for side in SIDES:
        for name in ARM_JOINTS[side]:
            joint = spec.joint(name)
            kp = _arm_kp(name)
            joint.armature = ARM_ARMATURE
            act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            act.set_to_position(kp=kp, kv=ARM_KV_RATIO * kp)
            act.ctrlrange = joint.range
            act.ctrllimited = True
            act.forcerange = joint.actfrcrange
            act.forcelimited = True
        for name in HAND_JOINTS[side]:
            act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            act.set_to_position(kp=HAND_KP, kv=HAND_KV)
            act.ctrlrange = driver_ctrl_range(spec, name, mimics)
            act.ctrllimited = True
            act.forcerange = spec.joint(name).actfrcrange
            act.forcelimited = True
    for joint in spec.joints:
        if joint.name[:2] in ("L_", "R_"):
            joint.armature = HAND_ARMATURE
            joint.damping[0] = HAND_DAMPING  # MuJoCo 4 keeps polynomial damping coefficients


def _add_mimic_equalities(spec: mujoco.MjSpec, mimics: list[Mimic]) -> None:
    for m in mimics:
        eq = spec.add_equality()
        eq.type = mujoco.mjtEq.mjEQ_JOINT
        eq.objtype = mujoco.mjtObj.mjOBJ_JOINT
        eq.name1 = m.follower
        eq.name2 = m.driver
        eq.data[:5] = [m.offset, m.multiplier, 0.0, 0.0, 0.0]
        eq.solref = [0.005, 1.0]


def _add_hand_frames(spec: mujoco.MjSpec) -> None:
    for side in SIDES:
        spec.body(WRIST_BODY[side]).add_site(
            name=HAND_BASE_FRAME[side],
            pos=HAND_BASE_ON_WRIST_POS,
            quat=HAND_BASE_ON_WRIST_QUAT,
            size=[0.005, 0.005, 0.005],
            group=5,
        )


def _enable_gravity_compensation(spec: mujoco.MjSpec) -> None:
    for side in SIDES:
        for body in arm_bodies(side):
            spec.body(body).gravcomp = 1.0
    for body in spec.bodies:
        if body.name.startswith(tuple(f"{HAND_PREFIX[s]}_" for s in SIDES)):
            body.gravcomp = 1.0


def _exclude_finger_self_contacts(spec: mujoco.MjSpec) -> None:
    """Neighbouring fingers of one hand sit millimetres apart; their convex hulls overlap when curled.

    The thumb keeps its contacts with the fingers (pinch and grasp need them); only finger-finger pairs of the
    four parallel fingers, and each finger with the palm, are excluded.
    """
    for side in SIDES:
        p = HAND_PREFIX[side]
        palm = WRIST_BODY[side]
        fingers = ("index", "middle", "ring", "pinky")
        links = [f"{p}_{f}_{seg}" for f in fingers for seg in ("proximal", "intermediate")]
        for i, a in enumerate(links):
            spec.add_exclude(bodyname1=palm, bodyname2=a)
            for b in links[i + 1 :]:
                if a.split("_")[1] != b.split("_")[1]:
                    spec.add_exclude(bodyname1=a, bodyname2=b)
        for seg in ("proximal_base", "proximal", "intermediate", "distal"):
            spec.add_exclude(bodyname1=palm, bodyname2=f"{p}_thumb_{seg}")


ROBOT_COLLISION_GROUP = 3  # hidden in renders: cameras draw the visual meshes only
ROBOT_VISUAL_GROUP = 1  # the upstream MJCF's visual meshes


def _split_visual_and_collision(spec: mujoco.MjSpec, robot_dir: Path, max_faces: int) -> None:
    """Visual geoms get decimated copies of their meshes; collision geoms keep the originals, out of sight."""
    files = {m.name: m.file for m in spec.meshes}
    made: set[str] = set()
    for geom in spec.geoms:
        if geom.type != mujoco.mjtGeom.mjGEOM_MESH:
            continue
        if geom.contype == 0 and geom.conaffinity == 0:
            light = f"{geom.meshname}_visual"
            if light not in made:
                verts, faces = visual_mesh(robot_dir / "meshes" / Path(files[geom.meshname]).name, max_faces)
                spec.add_mesh(name=light, uservert=verts.ravel().tolist(), userface=faces.ravel().tolist())
                made.add(light)
            geom.meshname = light
        else:
            geom.group = ROBOT_COLLISION_GROUP
    for geom in spec.geoms:  # the upstream primitive collision shapes (torso box, pelvis sphere, ...)
        if geom.type != mujoco.mjtGeom.mjGEOM_MESH and geom.contype != 0:
            geom.group = ROBOT_COLLISION_GROUP


def _drop_unused_meshes(spec: mujoco.MjSpec) -> None:
    """Delete the meshes no geom uses: the upstream meshes that only visual geoms used (they draw decimated
    copies now), 16 meshes and 177k faces that every compile processed for nothing (about 0.25 s of the
    first, cold compile of a process; 0.03 s of the later ones). Only the meshes' arrays and ids change; the
    physics is the same to the bit (tests/test_startup.py)."""
    used = {geom.meshname for geom in spec.geoms if geom.type == mujoco.mjtGeom.mjGEOM_MESH}
    for mesh in list(spec.meshes):
        if mesh.name not in used:
            spec.delete(mesh)


def cache_visual_meshes(assets_root: Path, max_faces: int) -> None:
    """Decimate (and cache on disk) the robot's visual meshes at `max_faces`, so that a process that cannot
    write, the locked plan worker, later finds them there instead of decimating them in memory each time."""
    robot_dir = Path(assets_root) / "h1_2"
    spec = mujoco.MjSpec.from_file(str(robot_dir / "h1_2.xml"))
    files = {m.name: m.file for m in spec.meshes}
    for name in sorted({g.meshname for g in spec.geoms if g.type == mujoco.mjtGeom.mjGEOM_MESH
                        and g.contype == 0 and g.conaffinity == 0}):
        visual_mesh(robot_dir / "meshes" / Path(files[name]).name, max_faces)


def build_robot_spec(assets_root: Path, visual_max_faces: int = DEFAULT_MAX_FACES) -> mujoco.MjSpec:
    """Load the upstream H1-2 MJCF and turn it into the table-top robot described in the module docstring."""
    robot_dir = Path(assets_root) / "h1_2"
    spec = mujoco.MjSpec.from_file(str(robot_dir / "h1_2.xml"))
    mimics = read_mimics(robot_dir / "h1_2.urdf")
    for sensor in list(spec.sensors):  # the IMU's noise would make runs depend on the RNG
        spec.delete(sensor)
    spec.body("pelvis").pos = ROBOT_BASE_POS
    _weld_everything_but_arms(spec)
    _disable_static_collisions(spec)
    _add_actuators(spec, mimics)
    _add_mimic_equalities(spec, mimics)
    _add_hand_frames(spec)
    _enable_gravity_compensation(spec)
    _exclude_finger_self_contacts(spec)
    _split_visual_and_collision(spec, robot_dir, visual_max_faces)
    _drop_unused_meshes(spec)
    return spec


def foot_height(model: mujoco.MjModel, data: mujoco.MjData) -> float:
    """Lowest point of the robot's feet, for placing the floor under them."""
    zs = []
    for name in ("left_ankle_roll_link", "right_ankle_roll_link"):
        bid = model.body(name).id
        zs.append(data.xpos[bid][2])
    return float(np.min(zs))
