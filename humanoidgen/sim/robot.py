"""The robot at its table, built with MjSpec from the upstream MJCF as its robot file says (default: the Unitree
H1-2 with two Inspire hands, `robots/h1_2_inspire/robot.yaml`).

What changes against upstream, and why:
- the joints the file's `weld` lists are deleted (the floating base, the legs and the torso): the robot stands at a
  table and only its arms move;
- the upstream torque motors are replaced by position actuators on the arm joints and the hands' actuated
  joints (the action), with the gains of the robot file (`arms`) and the hand file (`actuators`);
- each hand's follower joints are tied to their driver by equality constraints read from the URDF's mimic tags;
- arms and hands get gravity compensation, as the real robot's low-level controller provides it;
- a site per hand marks the end-effector frame the planner API names (`hands.<side>.frame`).
- visual geoms draw decimated copies of the meshes (`sim.meshes`); meshes no geom uses then are dropped.
"""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np

from humanoidgen.robots import Robot
from humanoidgen.robots.assemble import mesh_file, mimic_urdf, model_dir, model_spec
from humanoidgen.robots.mimic import Mimic, read_mimics  # noqa: F401 - re-exported
from humanoidgen.sim.layout import ROBOT, SIDES
from humanoidgen.sim.meshes import DEFAULT_MAX_FACES, visual_mesh


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


def _weld(spec: mujoco.MjSpec, robot: Robot) -> None:
    welded = set(robot.data.weld)
    for joint in list(spec.joints):
        if joint.name in welded:
            spec.delete(joint)


def _disable_static_collisions(spec: mujoco.MjSpec, robot: Robot) -> None:
    """Bodies that can never touch anything the arms reach (legs, pelvis): out of collision detection."""
    for name in robot.data.no_collision.subtrees:
        for geom in spec.body(name).find_all(mujoco.mjtObj.mjOBJ_GEOM):
            geom.contype = 0
            geom.conaffinity = 0
    for name in robot.data.no_collision.bodies:
        for geom in spec.body(name).geoms:
            geom.contype = 0
            geom.conaffinity = 0


def _add_actuators(spec: mujoco.MjSpec, mimics: list[Mimic], robot: Robot) -> None:
    for act in list(spec.actuators):
        spec.delete(act)
    arm, hand = robot.data.arm_actuators, robot.hand.data.actuators
    for side in SIDES:
        for entry in robot.data.arms[side]:
            name, kp = entry.joint, entry.kp
            joint = spec.joint(name)
            joint.armature = arm.armature
            act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            act.set_to_position(kp=kp, kv=arm.kv_ratio * kp)
            act.ctrlrange = joint.range
            act.ctrllimited = True
            act.forcerange = joint.actfrcrange if entry.force is None else (-entry.force, entry.force)
            act.forcelimited = True
        for name in robot.hand_joints[side]:
            act = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            act.set_to_position(kp=hand.kp, kv=hand.kv)
            act.ctrlrange = driver_ctrl_range(spec, name, mimics)
            act.ctrllimited = True
            act.forcerange = spec.joint(name).actfrcrange
            act.forcelimited = True
    for joint in spec.joints:
        if robot.is_hand_name(joint.name):
            joint.armature = hand.armature
            joint.damping[0] = hand.damping  # MuJoCo 4 keeps polynomial damping coefficients


def _add_mimic_equalities(spec: mujoco.MjSpec, mimics: list[Mimic]) -> None:
    for m in mimics:
        eq = spec.add_equality()
        eq.type = mujoco.mjtEq.mjEQ_JOINT
        eq.objtype = mujoco.mjtObj.mjOBJ_JOINT
        eq.name1 = m.follower
        eq.name2 = m.driver
        eq.data[:5] = [m.offset, m.multiplier, 0.0, 0.0, 0.0]
        eq.solref = [0.005, 1.0]


def _add_hand_frames(spec: mujoco.MjSpec, robot: Robot) -> None:
    base = robot.data.hands.hand_base
    for side in SIDES:
        spec.body(robot.hand_mount(side)).add_site(
            name=robot.hand_frame(side),
            pos=base.pos,
            quat=base.quat,
            size=[0.005, 0.005, 0.005],
            group=5,
        )


def _enable_gravity_compensation(spec: mujoco.MjSpec, robot: Robot) -> None:
    for side in SIDES:
        for body in robot.arm_links[side]:
            spec.body(body).gravcomp = 1.0
    for body in spec.bodies:
        if robot.is_hand_name(body.name):
            body.gravcomp = 1.0


def _exclude_finger_self_contacts(spec: mujoco.MjSpec, robot: Robot) -> None:
    """Neighbouring fingers of one hand sit millimetres apart; their convex hulls overlap when curled.

    The thumb keeps its contacts with the fingers (pinch and grasp need them); only finger-finger pairs of the
    hand's parallel fingers (on different fingers), and each of their links with the palm, are excluded, and
    the thumb's links with the palm.
    """
    fingers = robot.hand.data.fingers
    for side in SIDES:
        palm = robot.hand_mount(side)
        links = [(f, robot.hand_link(side, link)) for f in robot.hand.data.parallel_fingers for link in fingers[f]]
        for i, (fa, a) in enumerate(links):
            spec.add_exclude(bodyname1=palm, bodyname2=a)
            for fb, b in links[i + 1 :]:
                if fa != fb:
                    spec.add_exclude(bodyname1=a, bodyname2=b)
        for link in fingers[robot.hand.data.thumb]:
            spec.add_exclude(bodyname1=palm, bodyname2=robot.hand_link(side, link))


ROBOT_COLLISION_GROUP = 3  # hidden in renders: cameras draw the visual meshes only
ROBOT_VISUAL_GROUP = 1  # the upstream MJCF's visual meshes


def _split_visual_and_collision(spec: mujoco.MjSpec, robot_dir: Path, max_faces: int) -> None:
    """Visual geoms get decimated copies of their meshes, in the robot's visual group; collision geoms keep the
    originals, out of sight."""
    files = {m.name: mesh_file(spec, robot_dir, m) for m in spec.meshes}
    made: set[str] = set()
    for geom in spec.geoms:
        if geom.type != mujoco.mjtGeom.mjGEOM_MESH:
            continue
        if geom.contype == 0 and geom.conaffinity == 0:
            light = f"{geom.meshname}_visual"
            if light not in made:
                verts, faces = visual_mesh(files[geom.meshname], max_faces)
                spec.add_mesh(name=light, uservert=verts.ravel().tolist(), userface=faces.ravel().tolist())
                made.add(light)
            geom.meshname = light
            if geom.group not in (0, ROBOT_VISUAL_GROUP):  # an upstream visual group of its own (the G1's 2)
                geom.group = ROBOT_VISUAL_GROUP  # what `hide_robot` hides
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


def cache_visual_meshes(assets_root: Path, max_faces: int, robot: Robot = ROBOT) -> None:
    """Decimate (and cache on disk) the robot's visual meshes at `max_faces`, so that a process that cannot
    write, the locked plan worker, later finds them there instead of decimating them in memory each time."""
    robot_dir = model_dir(assets_root, robot)
    spec = model_spec(assets_root, robot)
    files = {m.name: mesh_file(spec, robot_dir, m) for m in spec.meshes}
    for name in sorted({g.meshname for g in spec.geoms if g.type == mujoco.mjtGeom.mjGEOM_MESH
                        and g.contype == 0 and g.conaffinity == 0}):
        visual_mesh(files[name], max_faces)


def build_robot_spec(assets_root: Path, visual_max_faces: int = DEFAULT_MAX_FACES, robot: Robot = ROBOT
                     ) -> mujoco.MjSpec:
    """Load the robot's upstream MJCF and turn it into the table-top robot described in the module docstring."""
    robot_dir = model_dir(assets_root, robot)
    spec = model_spec(assets_root, robot)
    urdf = mimic_urdf(assets_root, robot)
    mimics = read_mimics(urdf) if urdf is not None else []
    for sensor in list(spec.sensors):  # the IMU's noise would make runs depend on the RNG
        spec.delete(sensor)
    spec.body(robot.data.stand.root_body).pos = np.array(robot.data.stand.base_pos)
    _weld(spec, robot)
    _disable_static_collisions(spec, robot)
    _add_actuators(spec, mimics, robot)
    _add_mimic_equalities(spec, mimics)
    _add_hand_frames(spec, robot)
    _enable_gravity_compensation(spec, robot)
    _exclude_finger_self_contacts(spec, robot)
    _split_visual_and_collision(spec, robot_dir, visual_max_faces)
    _drop_unused_meshes(spec)
    return spec


def foot_height(model: mujoco.MjModel, data: mujoco.MjData, robot: Robot = ROBOT) -> float:
    """Lowest point of the robot's feet, for placing the floor under them."""
    zs = []
    for name in robot.data.stand.feet:
        bid = model.body(name).id
        zs.append(data.xpos[bid][2])
    return float(np.min(zs))
