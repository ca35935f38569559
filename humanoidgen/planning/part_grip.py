"""Following a held articulated part with the grip's own freedom.

A hand that holds a drawer's handle bar or a lid's tab does not have to keep the orientation it had when it
closed: the grip can roll about the bar (the operation's parallel axis, through the grip point) without letting
go (the part turns in the fingers). `track_rolling` tracks the part's path with that roll as one more variable,
limited (per grip, the follow's "roll_deg") and costlier than the joints' own motion, so it turns only where the
arm alone does not keep up; the arm then keeps its reach over more of the part's arc (an arm stretched toward a
drawer's closed position runs out of wrist range long before it runs out of reach).

This stage (follow a part; functions of a PlanningContext) builds the part's path, tracks it, and scores a grasp posture by how
much of the part's arc it can reach (`arc_span`, used when choosing among grasp postures).
"""

from __future__ import annotations

from dataclasses import replace

import mujoco
import numpy as np

from humanoidgen.objects.hands import hand_points
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.planning.motion import ROT_WEIGHT, MotionError, track_poses
from humanoidgen.planning.part_joint import PartFollow, follow_articulation, follow_openness, rolls_about_joint
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.regrip_request import SHUT, STOP_SHORT_OF_SHUT, request
from humanoidgen.sim.geometry import axis_angle_mat, rotation_error
from humanoidgen.sim.layout import Side
from humanoidgen.planning.context import PlanningContext

ROLL_LIMIT_DEG = 90.0  # by default the grip may roll (the part pivot in it) this far about the handle's axis
FOLLOW_ENOUGH = 0.9  # a part followed this much of the way, where the arm's reach ends, is followed enough
# ... and a part the hand holds: from a grip the rest is left to the next step (a push, or gravity for a lid let
# go low), while a fingertip push short of the end may still be done from a freshly solved goal (the fallbacks).
FOLLOW_ENOUGH_HELD = 0.85
# A held part's grip that slid or turned this far on it is taken back to how it closed.
ANCHOR_MIN_M, ANCHOR_MAX_M = 0.003, 0.04
ANCHOR_MIN_DEG, ANCHOR_MAX_DEG = 2.0, 35.0
ROLL_COST = 0.3  # the roll column is scaled by this: a step turns the roll ~1/ROLL_COST^2 less than a joint


def track_rolling(kin: Kinematics, side: Side, q_start: np.ndarray, poses: list, axes: list, centres: list,
                  limit_deg: float | None = None, iters: int = 40,
                  tol: float = 5e-4) -> tuple[np.ndarray, np.ndarray, str]:
    """Like motion.track_poses, but pose k may be turned by an angle about axes[k] through centres[k].

    Returns (waypoints (n, 7), roll angles (n,), "") or the partial path and a reason where it stops."""
    arm = kin.arms[side]
    base = kin.data.qpos.copy()
    q = np.array(q_start, float)
    theta = 0.0
    lim = np.radians(ROLL_LIMIT_DEG if limit_deg is None else limit_deg)
    out, rolls, reason = [], [], ""
    for k, ((p_t, R_t), a, c) in enumerate(zip(poses, axes, centres)):
        a = np.asarray(a, float) / np.linalg.norm(a)
        for _ in range(iters):
            Rr = axis_angle_mat(a, theta)
            pt, Rt = c + Rr @ (p_t - c), Rr @ R_t
            kin.set_arm(side, q)
            kin.forward()
            p, R = kin.ee_pose(side)
            e = np.concatenate([pt - p, ROT_WEIGHT * rotation_error(R, Rt)])
            if np.linalg.norm(e) < tol:
                break
            J = np.vstack([kin.point_jacobian(side, p), ROT_WEIGHT * kin.rotation_jacobian(side)])
            g = np.concatenate([np.cross(a, pt - c), ROT_WEIGHT * a])  # d(target)/d(theta)
            # The roll costs more than the joints' motion (its column scaled down), so it turns only where the
            # arm alone does not keep up.
            A = np.hstack([J, -ROLL_COST * g[:, None]])
            dx = A.T @ np.linalg.solve(A @ A.T + 1e-4 * np.eye(6), e)
            # As track_poses: a joint at its limit that the step pushes further out is dropped from the step.
            blocked = ((q <= arm.lo + 1e-6) & (dx[:7] < 0)) | ((q >= arm.hi - 1e-6) & (dx[:7] > 0))
            if blocked.any():
                A[:, np.flatnonzero(blocked)] = 0.0
                dx = A.T @ np.linalg.solve(A @ A.T + 1e-4 * np.eye(6), e)
            q = np.clip(q + np.clip(dx[:7], -0.1, 0.1), arm.lo, arm.hi)
            theta = float(np.clip(theta + np.clip(ROLL_COST * dx[7], -0.1, 0.1), -lim, lim))
        Rr = axis_angle_mat(a, theta)
        pt, Rt = c + Rr @ (p_t - c), Rr @ R_t
        kin.set_arm(side, q)
        kin.forward()
        p, R = kin.ee_pose(side)
        pos_err = np.linalg.norm(pt - p)
        if pos_err > 5e-3 or np.linalg.norm(rotation_error(R, Rt)) > np.radians(3):
            reason = (f"the straight motion leaves the arm's reach or joint limits at {100 * (k + 1) / len(poses):.0f}% "
                      f"of the way ({pos_err * 1000:.0f} mm off, the grip rolled {np.degrees(theta):.0f} deg)")
            break
        out.append(q.copy())
        rolls.append(theta)
    kin.data.qpos[:] = base
    kin.forward()
    return np.array(out).reshape(-1, 7), np.array(rolls), reason



def follow_enough(ctx: PlanningContext, side: Side) -> float:
    return FOLLOW_ENOUGH_HELD if ctx.hands[side].held is not None else FOLLOW_ENOUGH

def part_path_poses(ctx: PlanningContext, side: Side, f: PartFollow, held: bool | None = None) -> tuple[list, np.ndarray, float]:
    """The hand's poses along an articulated part's joint path to f.q_target, keeping the hand where it
    is on the part now: (poses, joint values of the part at each, the part's joint value now).

    A hand holding the part turns with it. A fingertip pushing it (nothing held) only keeps its tip on the
    same spot of the part and its orientation as it is: it presses, it has no grip to turn with, and a
    wrist turned the whole way a lid swings soon runs out of its joint range."""
    m, d = ctx.env.model, ctx.kin.data
    jid = m.joint(f.joint).id
    adr = m.jnt_qposadr[jid]
    part_body = m.jnt_bodyid[jid]
    q_now = float(ctx.env.data.qpos[adr])
    slide = m.jnt_type[jid] == mujoco.mjtJoint.mjJNT_SLIDE
    # Aim a little past the target along the joint, even past its end stop: the arm lags a loaded part by
    # about that much, and the stop itself holds the part (forward kinematics ignores joint limits).
    overshoot = 0.01 if slide else 0.05
    q_end = float(f.q_target + np.sign(f.q_target - q_now) * overshoot)
    p_hand, R_hand = ctx.kin.ee_pose(side)
    part_p, part_R = d.xpos[part_body].copy(), d.xmat[part_body].reshape(3, 3).copy()
    rel_p, rel_R = part_R.T @ (p_hand - part_p), part_R.T @ R_hand
    poses = []
    base = d.qpos.copy()
    n = max(2, int(np.ceil(abs(f.q_target - q_now) / (0.01 if slide else 0.03))))
    q_steps = np.linspace(q_now, q_end, n + 1)[1:]
    pushing = ctx.hands[side].held is None if held is None else not held
    tip_local = hand_points(side)[f"press_point_base_{side}_hand"]  # in the wrist frame
    wrist = ctx.kin.arms[side].wrist
    wp, wR = d.xpos[wrist].copy(), d.xmat[wrist].reshape(3, 3).copy()
    tip = wp + wR @ tip_local
    rel_tip = part_R.T @ (tip - part_p)
    back = None if pushing else slid_since_grip(ctx, side, part_body, rel_p, rel_R)
    for k, qj in enumerate(q_steps):
        d.qpos[adr] = qj
        mujoco.mj_kinematics(m, d)
        pp, pR = d.xpos[part_body], d.xmat[part_body].reshape(3, 3)
        if pushing:
            poses.append((p_hand + (pp + pR @ rel_tip - tip), R_hand))
        elif back is None:
            poses.append((pp + pR @ rel_p, pR @ rel_R))
        else:
            # A hand that slid along the part or turned on it since it closed goes back to how it closed, over
            # the path's first half: a lid's tab lowered in stages slid 15 mm a stage out of the fingers until they
            # lost it; a knob's fin turned 90 deg in one move slid 15 mm toward the axis, the hand 20 deg ahead.
            t = min(1.0, (k + 1) / max(1, len(q_steps) // 2))
            R_t = axis_angle_mat(back[1], t * np.linalg.norm(back[1])) @ rel_R if np.linalg.norm(back[1]) > 1e-9 \
                else rel_R
            poses.append((pp + pR @ (rel_p + t * back[0]), pR @ R_t))
    d.qpos[:] = base
    ctx.kin.forward()
    return poses, q_steps, q_now

def slid_since_grip(ctx: PlanningContext, side: Side, part_body: int, rel_p: np.ndarray,
                    rel_R: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """How far the hand is from where it closed on the part it holds, in the part body's frame: (the point's offset
    back there, the axis-angle vector that turns the hand's rotation back there), where it slid or turned at least
    ANCHOR_MIN_M / ANCHOR_MIN_DEG and at most ANCHOR_MAX_M / ANCHOR_MAX_DEG (more: it holds it another way now);
    else None."""
    hand = ctx.hands[side]
    anchor = hand.grip_anchor
    if hand.held is None or anchor is None or anchor[0] != hand.held.body or part_body not in anchor[1]:
        return None
    p0, R0 = anchor[1][part_body]
    back, turn = p0 - rel_p, rotation_error(rel_R, R0)  # turn: in the part's frame, from now to then
    off, deg = float(np.linalg.norm(back)), float(np.degrees(np.linalg.norm(turn)))
    if off > ANCHOR_MAX_M or deg > ANCHOR_MAX_DEG or (off < ANCHOR_MIN_M and deg < ANCHOR_MIN_DEG):
        return None
    return back, turn


def grip_roll_frames(ctx: PlanningContext, side: Side, f: PartFollow, q_steps: np.ndarray, held: bool | None = None,
                      kind: str | None = None) -> tuple[list, list] | None:
    """For a hand holding the part by a grip that may roll (f.grip_axis): the roll axis and its centre
    (the hand's grip point at the kinematic state now, carried with the part) at each joint value of the
    path; None otherwise."""
    holding = ctx.hands[side].held is not None if held is None else held
    if not holding or not f.grip_axis or not f.roll_deg:
        return None
    from humanoidgen.objects.queries import get_axis_in_env

    m, d = ctx.env.model, ctx.kin.data
    jid = m.joint(f.joint).id
    adr, body = m.jnt_qposadr[jid], m.jnt_bodyid[jid]
    obj = ctx.env.scene.object(*f.obj)
    kind = kind or ("pinch" if ctx.hands[side].grip == "pinch" else "grasp")
    wrist = ctx.kin.arms[side].wrist
    centre = d.xpos[wrist] + d.xmat[wrist].reshape(3, 3) @ hand_points(side)[f"{kind}_point_base_{side}_hand"]
    axis = get_axis_in_env(ctx.env, f.grip_axis, obj_type=obj.type_name, obj_id=obj.obj_id)
    if rolls_about_joint(m, d, f.joint, axis, centre):
        return None
    R0, p0 = d.xmat[body].reshape(3, 3).copy(), d.xpos[body].copy()
    c_local, a_local = R0.T @ (centre - p0), R0.T @ axis
    base = d.qpos.copy()
    axes, centres = [], []
    for qj in q_steps:
        d.qpos[adr] = qj
        mujoco.mj_kinematics(m, d)
        R, p = d.xmat[body].reshape(3, 3), d.xpos[body]
        axes.append(R @ a_local)
        centres.append(p + R @ c_local)
    d.qpos[:] = base
    ctx.kin.forward()
    return axes, centres

def track_part(ctx: PlanningContext, side: Side, q0: np.ndarray, f: PartFollow, held: bool | None = None,
                kind: str | None = None) -> tuple[np.ndarray, np.ndarray, float, str]:
    """The arm's path along the part's joint path from q0 (the kinematic state is at q0): (waypoints, the
    part's joint value at each pose, its value now, why the path stops short or ""). A holding grip may roll
    about the handle on the way: the wrist need not keep its grasp-time orientation, and it keeps its reach
    over more of the arc. `held`/`kind`: as if the hand held the part with that grip (default: as it is)."""
    poses, q_steps, q_now = part_path_poses(ctx, side, f, held)
    rolling = grip_roll_frames(ctx, side, f, q_steps, held, kind)
    if rolling is None:
        path, reason = track_poses(ctx.kin, side, q0, poses)
    else:
        path, _, reason = track_rolling(ctx.kin, side, q0, poses, *rolling, limit_deg=f.roll_deg)
    return path, q_steps, q_now, reason

def arc_span(ctx: PlanningContext, side: Side, part: PartFollow, q: np.ndarray, kind: str = "grasp") -> float:
    """How much of its openness range a part could be moved with the hand gripping it at arm posture q:
    the openness interval reachable toward closed and toward open, as a share of the way to each end,
    summed (2.0: the whole arc both ways). For choosing among grasp postures: a grasp of a part is nearly
    always followed by moving it, and the arm cannot change posture family while it holds it."""
    art = follow_articulation(ctx.env, part)  # the gripped part's own joint (a knob's, on a door)
    now = follow_openness(ctx.env, part)
    ctx.kin.sync(ctx.env.data.qpos)
    total = 0.0
    try:
        for end in (0.0, 1.0):
            if abs(end - now) < 0.05:
                total += 1.0
                continue
            ctx.kin.set_arm(side, q)
            ctx.kin.forward()
            f = replace(part, q_target=art.joint_position(end))
            path, q_steps, q_now, reason = track_part(ctx, side, q, f, held=True, kind=kind)
            if not reason:
                total += 1.0
            elif len(path):
                total += abs(q_steps[len(path) - 1] - q_now) / abs(f.q_target - q_now)
    finally:
        ctx.kin.sync(ctx.env.data.qpos)
    return total

def follow_part(ctx: PlanningContext, side: Side, q0: np.ndarray, target: Pose) -> np.ndarray:
    """Track the hand along an articulated part's joint path (a drawer slides, a lid turns)."""
    stop_short_of_shut(ctx, side, target)
    f = target.follow
    path, q_steps, q_now, reason = track_part(ctx, side, q0, f)
    if not reason:
        return np.vstack([q0, path])
    # Where the arm's reach ends within the last tenth of the way, go that far and say so: whether that is
    # enough is for the task to judge.
    way = abs(f.q_target - q_now)
    reached = abs(q_steps[len(path) - 1] - q_now) if len(path) else 0.0
    if len(path) and reached >= follow_enough(ctx, side) * way:
        if reached < 0.995 * way:
            ctx.events.append(f"followed {f.obj[0]} {f.obj[1]} {100 * reached / way:.0f}% of the way: "
                               f"the {side} arm's reach ends there")
        return np.vstack([q0, path])
    if target.joint_q is not None:
        # The solver's goal may sit in another arm posture family: track backward from it to the start and
        # use that path if it ends where the arm is now.
        start = (ctx.kin.ee_pose(side),)
        poses = part_path_poses(ctx, side, f)[0]
        back, back_reason = track_poses(ctx.kin, side, target.joint_q, poses[-2::-1] + [start[0]])
        if not back_reason and np.max(np.abs(back[-1] - q0)) < 0.15:
            return np.vstack([q0, back[::-1][1:], target.joint_q])
    if regrip_from_here(ctx, side, target, float(q_steps[len(path) - 1]) if len(path) else float(q_now)):
        return np.vstack([q0, path]) if len(path) else np.vstack([q0, q0])
    raise MotionError(f"following {f.body}'s joint: {reason}")

def stop_short_of_shut(ctx: PlanningContext, side: Side, target: Pose) -> None:
    """A hinged plate (a lid, a screen) held by its edge and to be shut: the fingers around the edge would end
    shut in under it (a thumb between screen and base; every way of letting go then dragged it open again, to
    0.28-0.48). Where the task has a fingertip push that shuts it, the hand takes it to STOP_SHORT_OF_SHUT,
    lets go there and the part falls or is pushed shut (recoveries/grip_again)."""
    f = target.follow
    if target.regrip is not None or ctx.regrips_left <= 0 or ctx.hands[side].held is None:
        return
    m = ctx.env.model
    if m.jnt_type[m.joint(f.joint).id] != mujoco.mjtJoint.mjJNT_HINGE:
        return  # a drawer's handle is outside it: nothing gets shut in
    art = follow_articulation(ctx.env, f)
    wanted, now = art.openness_of(f.q_target), follow_openness(ctx.env, f)
    obj = ctx.env.scene.object(*f.obj)
    targets = ctx.targets
    push = targets.push(obj.type_name, obj.obj_id) if targets is not None else None
    if wanted > SHUT or now <= STOP_SHORT_OF_SHUT or push is None or push.spec.push.to > SHUT:
        return
    target.regrip = request(f, wanted, ctx.hands[side].grip, STOP_SHORT_OF_SHUT, optional=False,
                            why=f"{obj.type_name} {obj.obj_id} is to be shut: the {side} hand takes it to "
                                f"openness {STOP_SHORT_OF_SHUT:g}, not shut in its fingers")
    target.follow = replace(f, q_target=art.joint_position(STOP_SHORT_OF_SHUT))

def regrip_from_here(ctx: PlanningContext, side: Side, target: Pose, q_reached: float) -> bool:
    """Where following the part runs out of reach partway on a move planned to go all the way (the goal search
    tracks from the arm at solve time; the arm settled in the grip may run out sooner: open_laptop_hard's
    screen lifted in stages, at 50-75% of its last stage), make the move go as far as it gets and then let go
    and grip the part again (recoveries/grip_again.py), as a goal found partial does. Only for a held part that stays where
    it is let go, and while the move may still grip again; True where the target was changed so."""
    from humanoidgen.planning.part_joint import part_stays

    f = target.follow
    art = follow_articulation(ctx.env, f)
    if target.regrip is not None:  # the move lets go and grips again after this anyway: from wherever it ends
        target.regrip.reached = art.openness_of(q_reached)
    elif ctx.regrips_left <= 0 or ctx.hands[side].held is None or not part_stays(ctx.env, f.joint, q_reached):
        return False
    else:
        target.regrip = request(f, art.openness_of(f.q_target), ctx.hands[side].grip, art.openness_of(q_reached),
                                optional=False)
    target.follow = replace(f, q_target=q_reached)
    return True
