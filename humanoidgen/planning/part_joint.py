"""Which joint a hand on an articulated part moves, and how far along it that joint is.

Most articulated objects have one moving part (a drawer, a lid), whose joint is the object's openness. A part
with a joint of its own on top of that (a safe's knob, on its door: `ObjectAnnotations.part_articulations`) is
moved by its own joint: a grip on a knob point turned "to openness 0.75" turns the knob, not the door. The
planner's follow records (`Generated.follow` / `grip_part`) carry that articulation, and these helpers read it.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.objects.schema import Articulation
from humanoidgen.sim.scene import SceneObject


@dataclass
class PartFollow:
    """How a hand is on an articulated part: the part's body and the joint that moves it, the object, that
    joint's articulation, and for a move the joint value to take it to (`q_target`) and the annotated point the
    hand is on (`part_point`); the axis a holding grip may roll about on the way, how far (`roll_deg`), and the
    axis the hand came onto a hooked handle along (`unhook_axis`); for a press to a force,
    that force (`force`, N; `q_target` is then the deepest the press may go). A grip not yet moving the part
    (`Generated.grip_part`) has no `q_target`."""

    body: str
    joint: str
    obj: tuple[str, int]
    articulation: Articulation | None = None
    q_target: float | None = None
    part_point: str | None = None
    grip_axis: str | None = None
    roll_deg: float = 0.0
    unhook_axis: str | None = None
    force: float | None = None  # a press to a force (N): the move stops when the finger pushes the part this hard


def point_articulation(obj: SceneObject, point: str) -> Articulation | None:
    """The articulation that moves an annotated point of `obj` (None for an object without a moving part)."""
    ann = obj.annotations
    if ann is None or ann.articulation is None:
        return None
    return ann.articulation_for(ann.point(point).part)


def grip_joint(gen) -> str | None:
    """The joint of the articulated part a generated grip takes (its `grip_part` record), else None."""
    part = getattr(gen, "grip_part", None)
    return part.joint if part else None


def follow_articulation(env, follow: PartFollow) -> Articulation:
    """The articulation a follow (or grip_part) record moves: its own, else the object's main one."""
    art = follow.articulation
    return art if art is not None else env.scene.object(*follow.obj).annotations.articulation


def follow_openness(env, follow: PartFollow, data: mujoco.MjData | None = None) -> float:
    """That joint's openness now (in `data`, default the simulation's), clipped to [0, 1]."""
    d = env.data if data is None else data
    q = float(d.qpos[env.model.jnt_qposadr[env.model.joint(follow.joint).id]])
    return follow_articulation(env, follow).openness_of(q)


def point_motion(env, follow: PartFollow, step: float) -> np.ndarray:
    """Unit direction the followed part point (`part_point`) moves in as its joint goes from its openness now by
    `step` (kept within [0, 1]); zeros where it does not move."""
    obj = env.scene.object(*follow.obj)
    now = follow_openness(env, follow)
    p0, p1 = (get_point_in_env(env, follow.part_point, obj.type_name, obj.obj_id, openness=float(np.clip(o, 0, 1)))
              for o in (now, now + step))
    v = p1 - p0
    n = float(np.linalg.norm(v))
    return np.zeros(3) if n < 1e-6 else v / n


def hinge_line(model: mujoco.MjModel, data: mujoco.MjData, joint: str) -> tuple[np.ndarray, np.ndarray] | None:
    """A hinge joint's axis (unit, world frame) and a point on it, where the kinematics in `data` have the part
    now; None for a joint that is not a hinge (a drawer's slide)."""
    jid = model.joint(joint).id
    if model.jnt_type[jid] != mujoco.mjtJoint.mjJNT_HINGE:
        return None
    body = model.jnt_bodyid[jid]
    R = data.xmat[body].reshape(3, 3)
    hinge = R @ model.jnt_axis[jid]
    return hinge / np.linalg.norm(hinge), data.xpos[body] + R @ model.jnt_pos[jid]


def rolls_about_joint(model: mujoco.MjModel, data: mujoco.MjData, joint: str, axis: np.ndarray,
                      centre: np.ndarray, tol_m: float = 0.015, tol_deg: float = 10.0) -> bool:
    """Whether a grip's roll axis (through `centre`) is the part's own hinge axis: a pinched knob. Rolling the
    grip about it would only undo the part's turn, so such a grip does not roll."""
    line = hinge_line(model, data, joint)
    if line is None:
        return False
    hinge, anchor = line
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    if abs(float(a @ hinge)) < np.cos(np.radians(tol_deg)):
        return False
    off = np.asarray(centre, float) - anchor
    return float(np.linalg.norm(off - (off @ hinge) * hinge)) < tol_m


def hinge_through(model: mujoco.MjModel, data: mujoco.MjData, joint: str, point: np.ndarray,
                  within_m: float = 0.05) -> bool:
    """Whether the hinge of `joint` passes within `within_m` of `point` (a hand's grip point): a knob turned by
    the fingers on its fin, not a lid or a door held far from its hinge. False for a slide."""
    line = hinge_line(model, data, joint)
    if line is None:
        return False
    hinge, anchor = line
    off = np.asarray(point, float) - anchor
    return float(np.linalg.norm(off - (off @ hinge) * hinge)) < within_m


def hinge_through_hold(env, side: str, grip: str | None, joint: str) -> bool:
    """Whether the hinge of `joint` passes near `side`'s grip point of its grip now ("pinch", else the grasp's):
    a part turned about an axis through the fingers' hold (a knob by its fin)."""
    from humanoidgen.objects.hands import hand_points
    from humanoidgen.objects.queries import wrist_point_in_env

    kind = "pinch" if grip == "pinch" else "grasp"
    point = wrist_point_in_env(env, side, hand_points(side)[f"{kind}_point_base_{side}_hand"])
    return hinge_through(env.model, env.data, joint, point)


def moving_bodies(model: mujoco.MjModel, joint: str) -> set[int]:
    """The bodies that `joint` moves: its own and all below it (a knob on a door moves only the knob)."""
    top = int(model.jnt_bodyid[model.joint(joint).id])
    out = set()
    for b in range(model.nbody):
        x = b
        while x > 0 and x != top:
            x = int(model.body_parentid[x])
        if x == top:
            out.add(b)
    return out


def part_stays(env, joint: str, q: float) -> bool:
    """Would an articulated part left alone at joint value `q` stay there (its joint friction holds its weight)?"""
    m = env.model
    jid = m.joint(joint).id
    d = mujoco.MjData(m)
    d.qpos[:] = env.data.qpos
    d.qpos[m.jnt_qposadr[jid]] = q
    mujoco.mj_forward(m, d)
    dof = m.jnt_dofadr[jid]
    return bool(abs(d.qfrc_bias[dof]) <= m.dof_frictionloss[dof])


def stays_now(env, follow: PartFollow) -> bool:
    """Would the part `follow` moves stay where it is now if let go (`part_stays` at its joint's value now)?"""
    m = env.model
    return part_stays(env, follow.joint, float(env.data.qpos[m.jnt_qposadr[m.joint(follow.joint).id]]))
