"""Arm motions: a straight SE(3) (screw) motion tracked by IK, checked against collisions on the MuJoCo
model; where it collides or leaves the joint limits, an OMPL RRT-Connect path in joint space. Paths are
timed within velocity and acceleration limits; path constraints are held at every waypoint of a screw motion.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.planning.paths import is_valid, plan_rrt_connect, segment_valid, straight_path
from humanoidgen.planning.poses import screw_interpolate
from humanoidgen.sim.geometry import rotation_angle, rotation_error
from humanoidgen.sim.layout import Side

ROT_WEIGHT = 0.2  # metres per radian when tracking poses


@dataclass
class JointPath:
    """A joint-space path for one arm, and how it was made."""

    waypoints: np.ndarray  # (n, 7)
    method: str  # "screw", "rrt_connect" or "direct"
    reason: str = ""


class MotionError(RuntimeError):
    pass


def track_poses(kin: Kinematics, side: Side, q_start: np.ndarray, poses: list[tuple[np.ndarray, np.ndarray]],
                path_constraints: list[Constraint] = (), iters: int = 30, tol: float = 5e-4) -> tuple[np.ndarray, str]:
    """Follow end-effector poses with damped least squares from `q_start`; path constraints as extra rows.

    Returns (waypoints (n, 7), "") or (partial waypoints, reason) when a pose cannot be tracked.
    """
    arm = kin.arms[side]
    base = kin.data.qpos.copy()
    q = np.array(q_start, float)
    out = []
    reason = ""
    for k, (p_t, R_t) in enumerate(poses):
        for _ in range(iters):
            kin.set_arm(side, q)
            kin.forward()
            p, R = kin.ee_pose(side)
            e = np.concatenate([p_t - p, ROT_WEIGHT * rotation_error(R, R_t)])
            J = np.vstack([kin.point_jacobian(side, p), ROT_WEIGHT * kin.rotation_jacobian(side)])
            rows_e, rows_J = [e], [J]
            for c in path_constraints:
                v, Jc = c.evaluate(kin)
                lo, hi = c.bounds()
                target = np.clip(v, lo, hi)
                rows_e.append(target - v)
                rows_J.append(Jc)
            E, JJ = np.concatenate(rows_e), np.vstack(rows_J)
            if np.linalg.norm(e) < tol and all(c.violation(kin) < 2e-3 for c in path_constraints):
                break
            dq = JJ.T @ np.linalg.solve(JJ @ JJ.T + 1e-4 * np.eye(len(E)), E)
            # A joint at its limit that the step pushes further out would only be clipped back, and the step
            # would stall there (a goal boxed in by limits): drop it from this step so the others take over.
            blocked = ((q <= arm.lo + 1e-6) & (dq < 0)) | ((q >= arm.hi - 1e-6) & (dq > 0))
            if blocked.any():
                JJ = JJ.copy()
                JJ[:, blocked] = 0.0
                dq = JJ.T @ np.linalg.solve(JJ @ JJ.T + 1e-4 * np.eye(len(E)), E)
            q = q + np.clip(dq, -0.1, 0.1)
            if np.any(q < arm.lo - 1e-6) or np.any(q > arm.hi + 1e-6):
                q = np.clip(q, arm.lo, arm.hi)
        kin.set_arm(side, q)
        kin.forward()
        p, R = kin.ee_pose(side)
        pos_err = np.linalg.norm(p_t - p)
        rot_err = np.linalg.norm(rotation_error(R, R_t))
        if pos_err > 5e-3 or rot_err > np.radians(3):
            reason = (f"the straight motion leaves the arm's reach or joint limits at {100 * (k + 1) / len(poses):.0f}% "
                      f"of the way ({pos_err * 1000:.0f} mm, {np.degrees(rot_err):.0f} deg off)")
            break
        bad = [c.describe(kin) for c in path_constraints if c.violation(kin) >= 2e-3]
        if bad:
            reason = f"path constraint violated at {100 * (k + 1) / len(poses):.0f}% of the way: {'; '.join(bad)}"
            break
        out.append(q.copy())
    kin.data.qpos[:] = base
    kin.forward()
    return np.array(out).reshape(-1, 7), reason


def plan_arm_motion(kin: Kinematics, cw: CollisionWorld, side: Side, q_start: np.ndarray,
                    target: tuple[np.ndarray, np.ndarray], q_goal: np.ndarray | None = None,
                    path_constraints: list[Constraint] = (), allow_sampling: bool = True,
                    seed: int = 0, time_limit: float = 4.0, keep_posture: bool = False) -> JointPath:
    """Screw motion to `target` (p, R); if it collides or fails, RRT-Connect to `q_goal` (no path constraints).

    Without `q_goal`, the end of the tracked screw motion serves as the sampling planner's goal. With
    `keep_posture`, a screw motion that ends at the pose in another arm posture than `q_goal` (a joint more than
    LANDING_MAX_RAD off) is tried last: a sampled path to `q_goal` first."""
    kin.set_arm(side, q_start)
    kin.forward()
    p0, R0 = kin.ee_pose(side)
    poses = screw_interpolate(p0, R0, target[0], target[1])
    waypoints, reason = track_poses(kin, side, q_start, poses, path_constraints)
    if reason and q_goal is not None and len(waypoints) >= len(poses) - 1:
        # Only the very end could not be tracked (the damped steps stall a hair short of a goal boxed in by the path
        # constraints or the joint limits); the goal solver's configuration is that end: land on it in joint space.
        landing = joint_landing(kin, side, waypoints[-1] if len(waypoints) else q_start, q_goal, path_constraints)
        if landing is not None:
            waypoints, reason = np.vstack([waypoints.reshape(-1, 7), landing]), ""
    if not reason and q_goal is None:
        q_goal = waypoints[-1]  # the tracked end is a valid goal for the sampling planner too
    ends = [q for q in (q_start, q_goal, waypoints[-1] if len(waypoints) else None) if q is not None]
    # The screw motion keeps the arm's posture family: after a lid lifted by its tab and let go, it reached the
    # pre-push pose with the elbow and wrist turned over (third joint 2.3 rad, the solver's goal -0.2), and the
    # push's stages tracked from there pushed the lid "from 0.00 to 0.00" (contract open_box_hard/grasp_lift_flip
    # seeds 2, 3); in the goal's posture it flipped open.
    elsewhere = keep_posture and not reason and np.max(np.abs(waypoints[-1] - q_goal)) > LANDING_MAX_RAD
    with cw.held_touch_only(held_touches(kin, cw, side, ends)):
        if elsewhere:
            try:
                return _checked_path(kin, cw, side, q_start, q_goal, waypoints, "the straight motion ends in another "
                                     "arm posture than the goal's", path_constraints, allow_sampling, seed, time_limit)
            except MotionError:
                pass  # no way keeps to it: the pose in the posture the screw motion reaches, as before
        return _checked_path(kin, cw, side, q_start, q_goal, waypoints, reason, path_constraints, allow_sampling,
                             seed, time_limit)


def _checked_path(kin: Kinematics, cw: CollisionWorld, side: Side, q_start: np.ndarray, q_goal: np.ndarray | None,
                  waypoints: np.ndarray, reason: str, path_constraints, allow_sampling: bool, seed: int,
                  time_limit: float) -> JointPath:
    """The tracked screw motion if it is collision-free, else a sampled path (plan_arm_motion's second half)."""
    if not reason:
        if q_goal is not None and np.max(np.abs(waypoints[-1] - q_goal)) < 0.3:
            waypoints = np.vstack([waypoints, q_goal])  # land exactly on the solver's configuration
        path = np.vstack([q_start, waypoints])
        collision = first_collision(kin, cw, side, path)
        if collision is None:
            return JointPath(path, "screw")
        reason = f"the straight motion collides at waypoint {collision} of {len(path)}"
    if path_constraints:
        raise MotionError(f"{reason}; no sampled path is tried because the move has path constraints")
    if not allow_sampling or q_goal is None:
        raise MotionError(reason)
    # Relaxed for a start in contact, but a goal deep in something is no goal: the whole path would be let
    # through it as deep (a pre-approach pose 44 mm into an open drawer's wall took the wrist through it). And
    # relaxed only for what the arm touches at its start or goal: relaxed for everything, a path from a hand beside
    # an open drawer to a goal 5 mm into the drawer swung the left hand 3 mm into the right elbow, and the
    # simulated arm, cutting the corner, struck it (handover_and_storage, seed 4).
    clearance = min(start_clearance(kin, cw, side, q_start),
                    start_clearance(kin, cw, side, q_goal, -GOAL_PENETRATION_M))
    touched = touched_at(kin, cw, side, (q_start, q_goal)) if clearance < MOTION_CLEARANCE else set()
    result = None
    with cw.touch_only(side, touched, MOTION_CLEARANCE - clearance):
        if (carry := carried_turn_check(kin, side, q_start, q_goal)) is not None:
            result = plan_rrt_connect(kin, cw, side, q_start, q_goal, time_limit=time_limit / 2, seed=seed,
                                      clearance=MOTION_CLEARANCE, state_ok=carry)
        if result is None or not result.ok:  # no way that keeps it so: any collision-free way
            result = plan_rrt_connect(kin, cw, side, q_start, q_goal, time_limit=time_limit, seed=seed,
                                      clearance=MOTION_CLEARANCE)
    if not result.ok:
        raise MotionError(f"{reason}; the sampling planner found no path either: {result.reason}")
    return JointPath(result.path, "rrt_connect", reason)


def held_touches(kin: Kinematics, cw: CollisionWorld, side: Side, qs) -> frozenset[int] | None:
    """What the object `side` holds may touch on its way (its slack, `CollisionWorld.held_slack`): the obstacles
    it is near at any of `qs` (the path's start and goal: what it is lifted from, what it is set down on); None
    (everything, as before) when the hand holds nothing."""
    if side not in kin.attached:
        return None
    base = kin.data.qpos.copy()
    near: set[int] = set()
    try:
        for q in qs:
            kin.set_arm(side, q)
            kin.forward()
            near |= cw.held_near(side, MOTION_CLEARANCE + cw.held_slack)
    finally:
        kin.data.qpos[:] = base
        kin.forward()
    return frozenset(near)


# A carried object's orientation on a sampled path stays this near the shortest turn from its start to its goal
# orientation: swung about freely, a block held by one end slides out of the fingers.
CARRY_TURN_SLACK = np.radians(15.0)


def carried_turn_check(kin: Kinematics, side: Side, q_start: np.ndarray, q_goal: np.ndarray):
    """A state check for the sampling planner: the object `side` carries turns at most CARRY_TURN_SLACK more than
    the way from its start to its goal orientation (angle to start + angle to goal <= their angle + 2 slack);
    None when the hand carries nothing."""
    if side not in kin.attached:
        return None
    body = kin.attached[side][0]
    saved = kin.arm_q(side)

    def orientation(q: np.ndarray) -> np.ndarray:
        kin.set_arm(side, q)
        kin.forward()
        return kin.data.xmat[body].reshape(3, 3).copy()

    R0, R1 = orientation(q_start), orientation(q_goal)
    kin.set_arm(side, saved)
    kin.forward()
    budget = rotation_angle(R0, R1) + 2 * CARRY_TURN_SLACK

    def ok(k: Kinematics) -> bool:
        R = k.data.xmat[body].reshape(3, 3)
        return bool(rotation_angle(R, R0) + rotation_angle(R, R1) <= budget)

    return ok


LANDING_MAX_RAD = 0.3  # a joint-space landing on the goal covers at most this much per joint
LANDING_STEPS = 6
LANDING_AXIS_TOL = np.radians(1.0)  # an axis path constraint may sag this much on the short landing (tracking: 0.1 deg)
LANDING_AXIS_MAX = np.radians(5.0)


def joint_landing(kin: Kinematics, side: Side, q_from: np.ndarray, q_goal: np.ndarray,
                  path_constraints: list[Constraint] = ()) -> np.ndarray | None:
    """Joint-space waypoints from `q_from` to `q_goal` (a short way) that keep the path constraints, or None.

    An axis constraint may sag LANDING_AXIS_TOL on the way, or as far as the goal itself misses it (up to
    LANDING_AXIS_MAX): a held object that turned a little in the hand since the plan read its axis makes the goal
    and the path constraint disagree by that much, and the goal is where the plan asked to go."""
    if np.max(np.abs(np.asarray(q_goal) - q_from)) > LANDING_MAX_RAD:
        return None
    base = kin.data.qpos.copy()
    steps = [q_from + (q_goal - q_from) * t for t in np.linspace(0.0, 1.0, LANDING_STEPS + 1)[1:]]
    try:
        kin.set_arm(side, q_goal)
        kin.forward()
        tols = [max(LANDING_AXIS_TOL, min(c.violation(kin) + 1e-3, LANDING_AXIS_MAX))
                if c.type in ("parallel", "angle") else 2e-3 for c in path_constraints]
        for q in steps:
            kin.set_arm(side, q)
            kin.forward()
            if any(c.violation(kin) > tol for c, tol in zip(path_constraints, tols)):
                return None
    finally:
        kin.data.qpos[:] = base
        kin.forward()
    return np.array(steps)


# The arm keeps this far from obstacles along a path (the simulated arm cuts corners a little); a held object
# may touch (CollisionWorld.held_slack). A motion that starts closer than this, say from a grasp, may leave
# but not get any closer.
MOTION_CLEARANCE = 0.004
GOAL_PENETRATION_M = 0.01  # a goal or a pre-approach pose may touch something this deep, not deeper (an open
# thumb 7 mm into the drawer front it comes in to grasp is such a touch; 44 mm into a wall is not)


def start_clearance(kin: Kinematics, cw: CollisionWorld, side: Side, q: np.ndarray,
                    floor: float | None = None) -> float:
    """The clearance a path from (or to) `q` must keep: MOTION_CLEARANCE, or less if `q` is closer than that
    (a hand that starts touching something must be able to leave it), but not below `floor`."""
    base = kin.data.qpos.copy()
    kin.set_arm(side, q)
    kin.forward()
    d, _ = cw.min_distance((side,))
    kin.data.qpos[:] = base
    kin.forward()
    clearance = min(MOTION_CLEARANCE, d - 1e-4)
    return clearance if floor is None else max(clearance, floor)


def touched_at(kin: Kinematics, cw: CollisionWorld, side: Side, qs) -> set[int]:
    """The obstacles (`contact_pairs`' owner bodies) closer than MOTION_CLEARANCE to `side` at any of `qs`."""
    base = kin.data.qpos.copy()
    out: set[int] = set()
    try:
        for q in qs:
            kin.set_arm(side, q)
            kin.forward()
            out |= {b2 for _, b2, _ in cw.contact_pairs((side,), MOTION_CLEARANCE)}
    finally:
        kin.data.qpos[:] = base
        kin.forward()
    return out


def first_collision(kin: Kinematics, cw: CollisionWorld, side: Side, path: np.ndarray,
                    clearance: float | None = None, start_is_goal: bool = False) -> int | None:
    """Index of the first waypoint whose segment comes closer than `clearance` (default: `start_clearance`;
    `start_is_goal`: path[0] is a pose chosen to go to, not where the arm is, so it may only touch)."""
    base = kin.data.qpos.copy()
    if clearance is None:
        clearance = start_clearance(kin, cw, side, path[0], -GOAL_PENETRATION_M if start_is_goal else None)
    try:
        for i in range(1, len(path)):
            if not segment_valid(kin, cw, side, path[i - 1], path[i], clearance=clearance):
                return i
        return None
    finally:
        kin.data.qpos[:] = base
        kin.forward()


def densify(path: np.ndarray, max_step: float = 0.02) -> np.ndarray:
    out = [path[0]]
    for a, b in zip(path[:-1], path[1:]):
        out.extend(straight_path(a, b, max_step)[1:])
    return np.array(out)


__all__ = ["JointPath", "MotionError", "track_poses", "plan_arm_motion", "densify", "is_valid"]


def time_dense_path(path: np.ndarray, dt: float, v_max: float = 1.0, a_max: float = 3.0) -> np.ndarray:
    """Samples every `dt` along a dense, smooth path with one trapezoidal profile over its whole length.

    Unlike `paths.time_parametrize` (rest at every corner, right for the few sharp corners of a sampled path),
    a screw motion's waypoints bend only slightly, so the arm keeps moving through them. Length is measured
    with the largest joint change, so no joint exceeds `v_max` and `a_max` along straight stretches.
    """
    if len(path) < 2:
        return np.array(path)
    seg = np.max(np.abs(np.diff(path, axis=0)), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    L = s[-1]
    if L < 1e-9:
        return path[-1:].copy()
    t_acc = v_max / a_max
    if a_max * t_acc**2 > L:  # triangle profile: never reaches v_max
        t_acc = np.sqrt(L / a_max)
        v_peak = a_max * t_acc
        T = 2 * t_acc
    else:
        v_peak = v_max
        T = 2 * t_acc + (L - a_max * t_acc**2) / v_max
    n = max(1, int(np.ceil(T / dt)))
    t = np.linspace(dt, n * dt, n) * (T / (n * dt))
    sv = np.where(t < t_acc, 0.5 * a_max * t**2,
                  np.where(t > T - t_acc, L - 0.5 * a_max * (T - t) ** 2, 0.5 * a_max * t_acc**2 + v_peak * (t - t_acc)))
    sv = np.clip(sv, 0, L)
    return np.stack([np.interp(sv, s, path[:, j]) for j in range(path.shape[1])], axis=1)
