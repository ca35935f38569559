"""How the planner moves an arm: plans (screw motion, straight approach, sampled detour, part following),
timing, and the check that two arms moving at once keep apart. A mixin of HumanoidMotionPlanner."""

from __future__ import annotations

import time

import mujoco
import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.planning.hand_ops import contents
from humanoidgen.planning.motion import (
    JointPath,
    MotionError,
    first_collision,
    plan_arm_motion,
    time_dense_path,
    track_poses,
)
from humanoidgen.planning.paths import time_parametrize
from humanoidgen.planning.poses import Pose, screw_interpolate
from humanoidgen.sim.action import ARM_SLICE, HAND_SLICE
from humanoidgen.sim.layout import SIDES, Side
from humanoidgen.sim.scene import SceneObject

# Grasps and pinches come in straight along the approach axis over the first of these that fits (metres).
APPROACH_DISTANCES = (0.08, 0.05, 0.03)
WRAP_TOUCH = 0.003  # how far the open hand may press into a body it comes to wrap (m)
RETREAT_DISTANCE = 0.10  # after letting go, the hand backs out along its approach axis this far


class PlanningError(RuntimeError):
    """A planner call that could not do its job; `call` and `reason` go back to the plan's author."""

    def __init__(self, call: str, reason: str) -> None:
        super().__init__(f"{call}: {reason}")
        self.call = call
        self.reason = reason


class ArmMoves:
    """Arm motion planning for HumanoidMotionPlanner (uses its env, kin, collisions, holding, log, seed)."""

    def _retreat(self, side: Side, open_fingers: bool = False) -> None:
        """Back the hand out along its last approach axis (best effort: skipped if that way is blocked),
        optionally opening the fingers on the way."""
        axis = self.last_approach.get(side)
        if axis is None:
            if open_fingers:
                self._move_fingers((side,), "open")
            return
        self.kin.sync(self.env.data.qpos)
        p, R = self.kin.ee_pose(side)
        arm = self.kin.arms[side]
        try:
            path = plan_arm_motion(self.kin, self.collisions, side, np.clip(self.kin.arm_q(side), arm.lo, arm.hi),
                                   (p - RETREAT_DISTANCE * axis, R), allow_sampling=False)
        except MotionError:
            if open_fingers:
                self._move_fingers((side,), "open")
            return
        finally:
            self.kin.sync(self.env.data.qpos)
        samples = time_dense_path(path.waypoints, 1.0 / self.env.control_hz, v_max=0.3)
        if open_fingers:
            start, goal = self.action[HAND_SLICE[side]].copy(), np.array(HAND_POSTURES["open"])
            for k, q in enumerate(samples, 1):
                self.action[ARM_SLICE[side]] = q
                self.action[HAND_SLICE[side]] = start + (goal - start) * min(1.0, 2.0 * k / len(samples))
                self._step()
        else:
            self._run_arm_samples({side: samples})
        self.last_approach[side] = None

    def _coordinate_arms(self, samples: dict[Side, np.ndarray]) -> dict[Side, np.ndarray]:
        """Both arms move at once: check every control step for arm-arm contact; if they would touch, move
        them one after the other (left first, then right), and if that collides too, give up with a reason."""
        self.kin.sync(self.env.data.qpos)
        for side in SIDES:
            self._attach_held(side)

        def clear(left: np.ndarray, right: np.ndarray) -> bool:
            # Each arm's own path was checked against the scene when it was planned; here only arm vs arm.
            n = max(len(left), len(right))
            for k in range(0, n, 2):
                self.kin.set_arm("left", left[min(k, len(left) - 1)])
                self.kin.set_arm("right", right[min(k, len(right) - 1)])
                self.kin.forward()
                if self.collisions.arm_arm_distance() < 0.003:
                    return False
            return True

        try:
            left, right = samples["left"], samples["right"]
            if clear(left, right):
                return samples
            left_first = {"left": left, "right": np.vstack([np.repeat(right[:1], len(left), 0), right])}
            if clear(left_first["left"], left_first["right"]):
                self.log[-1].message = "moved the arms one after the other to keep them apart"
                return left_first
            raise PlanningError("move_to_pose_with_screw", "the two arms' motions would collide with each other")
        finally:
            self.kin.sync(self.env.data.qpos)

    def _carries(self, side: Side) -> bool:
        held = self.holding[side]
        return held is not None and (held.annotations is None or held.annotations.articulation is None)

    def _ignore_contents(self, side: Side) -> None:
        """What rests in a carried object travels with it: the planner does not avoid it (the caller restores
        the ignore list)."""
        if self._carries(side):
            for o in contents(self.env.scene, self.env.model, self.env.data, self.holding[side]):
                self.collisions.ignored_bodies.add(self.env.model.body(o.body).id)

    def _relative_to_hand(self, side: Side, obj: SceneObject) -> np.ndarray:
        p_hand, R_hand = self.env.hand_pose(side)
        return R_hand.T @ (self.env.object_pose(obj.body)[0] - p_hand)

    def _plan_side(self, side: Side, target: Pose, path_constraints: list = ()) -> np.ndarray:
        t0 = time.perf_counter()
        try:
            return self._plan_side_timed(side, target, path_constraints)
        finally:
            self.plan_seconds.append(time.perf_counter() - t0)

    def _plan_side_timed(self, side: Side, target: Pose, path_constraints: list) -> np.ndarray:
        self.kin.sync(self.env.data.qpos)
        ignored_before = set(self.collisions.ignored_bodies)
        held = self.holding[side]
        self._attach_held(side)
        if held is not None and held.annotations is not None and held.annotations.articulation is not None:
            self.collisions.ignored_bodies.add(self.env.model.body(held.body).id)  # the hand is on the part
        self._ignore_contents(side)
        # Contact can push a joint a hair past its limit (e.g. the wrist after a pinch); plan from inside them.
        arm = self.kin.arms[side]
        q0 = np.clip(self.kin.arm_q(side), arm.lo, arm.hi)
        dt = 1.0 / self.env.control_hz
        try:
            legs = []
            if target.follow is not None:
                try:
                    path = self._follow_part(side, q0, target)
                    return time_dense_path(path, dt, v_max=0.6, a_max=2.0)
                except MotionError:
                    # A fingertip pushing a part (nothing held) may instead go straight to the solved goal.
                    if self.holding[side] is not None or target.joint_q is None:
                        raise
                    target = Pose(target.p, target.q, joint_q=target.joint_q, side=side)
            if target.approach_axis is not None and target.joint_q is not None:
                # Come in straight along the approach axis: back out from the goal to find the pre-pose (same
                # arm posture family), get there any collision-free way, then move in along the line.
                approach, pre, reasons = self._straight_approach(side, target.joint_q, target.p, target.R,
                                                                 target.approach_axis, target.approach_object,
                                                                 wrap=target.posture == "wrap")
                if approach is None:
                    raise MotionError("no straight approach to the target (" + "; ".join(reasons) + ")")
                back = approach[::-1]
                legs.append(plan_arm_motion(self.kin, self.collisions, side, q0, pre, q_goal=back[-1], seed=self.seed))
                legs.append(JointPath(approach, "screw"))
            else:
                legs.append(plan_arm_motion(self.kin, self.collisions, side, q0, (target.p, target.R),
                                            q_goal=target.joint_q, path_constraints=path_constraints,
                                            seed=self.seed))
        except MotionError as exc:
            raise PlanningError("move_to_pose_with_screw", f"{side} arm: {exc}") from None
        finally:
            self.collisions.ignored_bodies = ignored_before
            self.kin.sync(self.env.data.qpos)
        out = []
        for leg in legs:
            if leg.method == "rrt_connect":
                out.append(time_parametrize(leg.waypoints, dt=dt)[1])
            else:
                # Gentler with something in the hand: a pinched object slips under hard accelerations.
                v, a = (0.6, 1.5) if self._carries(side) else (1.0, 3.0)
                out.append(time_dense_path(leg.waypoints, dt, v_max=v, a_max=a))
        return np.vstack(out)

    def _straight_approach(self, side: Side, q_goal: np.ndarray, p: np.ndarray, R: np.ndarray, axis: np.ndarray,
                           approach_object: str | None, distances: tuple[float, ...] = APPROACH_DISTANCES,
                           wrap: bool = False):
        """The straight approach into a goal along `axis`, over the first distance that fits: (joint path from the
        pre-pose to the goal, the pre-pose, reasons) or (None, None, reasons). The object being approached may be
        touched; everything else is avoided. For a wrap the open hand must not push into the (standing, round)
        object on the way either, beyond WRAP_TOUCH: a knocked-over bottle or cup cannot be wrapped."""
        ignored_before = set(self.collisions.ignored_bodies)
        if approach_object is not None:
            self.collisions.ignored_bodies.add(self.env.model.body(approach_object).id)
        reasons = []
        try:
            for distance in distances:  # a shorter straight approach where the long one won't fit
                pre = (p - distance * axis, R)
                back, reason = track_poses(self.kin, side, q_goal, screw_interpolate(p, R, *pre))
                if not reason:
                    approach = np.vstack([back[::-1], q_goal])
                    if first_collision(self.kin, self.collisions, side, approach) is None:
                        if not wrap or approach_object is None or self._wrap_clear(side, approach, approach_object):
                            return approach, pre, reasons
                        reason = f"the open hand would push into {approach_object} on the way in"
                    else:
                        reason = "the straight approach along the operation's axis collides"
                reasons.append(f"{distance * 100:.0f} cm: {reason}")
            return None, None, reasons
        finally:
            self.collisions.ignored_bodies = ignored_before

    def _wrap_clear(self, side: Side, approach: np.ndarray, body: str) -> bool:
        ignored = set(self.collisions.ignored_bodies)
        self.collisions.ignored_bodies.discard(self.env.model.body(body).id)
        try:
            return first_collision(self.kin, self.collisions, side, approach, clearance=-WRAP_TOUCH) is None
        finally:
            self.collisions.ignored_bodies = ignored

    def _approach_fits(self, side: Side, result, gen) -> bool:
        """Whether a solved grip can be approached straight along its axis (the shortest approach)."""
        if gen is None or gen.approach_axis is None or gen.follow is not None:
            return True
        self.kin.sync(self.env.data.qpos)
        self._attach_held(side)
        approach, _, _ = self._straight_approach(side, result.q, result.ee_pos, result.ee_mat, gen.approach_axis,
                                                 gen.approach_object, distances=APPROACH_DISTANCES[-1:],
                                                 wrap=gen.posture == "wrap")
        self.kin.sync(self.env.data.qpos)
        return approach is not None

    def _follow_part(self, side: Side, q0: np.ndarray, target: Pose) -> np.ndarray:
        """Track the hand along an articulated part's joint path (a drawer slides, a lid turns)."""
        f = target.follow
        m, d = self.env.model, self.kin.data
        jid = m.joint(f["joint"]).id
        adr = m.jnt_qposadr[jid]
        part_body = m.jnt_bodyid[jid]
        q_now = float(self.env.data.qpos[adr])
        # Aim a little past the target along the joint, even past its end stop: the arm lags a loaded part by
        # about that much, and the stop itself holds the part (forward kinematics ignores joint limits).
        overshoot = 0.01 if m.jnt_type[jid] == mujoco.mjtJoint.mjJNT_SLIDE else 0.05
        q_end = float(f["q_target"] + np.sign(f["q_target"] - q_now) * overshoot)
        p_hand, R_hand = self.kin.ee_pose(side)
        part_p, part_R = d.xpos[part_body].copy(), d.xmat[part_body].reshape(3, 3).copy()
        rel_p, rel_R = part_R.T @ (p_hand - part_p), part_R.T @ R_hand
        poses = []
        base = d.qpos.copy()
        n = max(2, int(np.ceil(abs(f["q_target"] - q_now) / (0.01 if m.jnt_type[jid] == mujoco.mjtJoint.mjJNT_SLIDE else 0.03))))
        q_steps = np.linspace(q_now, q_end, n + 1)[1:]
        for qj in q_steps:
            d.qpos[adr] = qj
            mujoco.mj_kinematics(m, d)
            pp, pR = d.xpos[part_body], d.xmat[part_body].reshape(3, 3)
            poses.append((pp + pR @ rel_p, pR @ rel_R))
        d.qpos[:] = base
        self.kin.forward()
        path, reason = track_poses(self.kin, side, q0, poses)
        if not reason:
            return np.vstack([q0, path])
        # Where the arm's reach ends within the last tenth of the way, go that far and say so: whether that is
        # enough is for the task to judge.
        way = abs(f["q_target"] - q_now)
        reached = abs(q_steps[len(path) - 1] - q_now) if len(path) else 0.0
        if len(path) and reached >= 0.9 * way:
            if reached < way:
                self.events.append(f"followed {f['obj'][0]} {f['obj'][1]} {100 * reached / way:.0f}% of the way: "
                                   f"the {side} arm's reach ends there")
            return np.vstack([q0, path])
        if target.joint_q is not None:
            # The solver's goal may sit in another arm posture family: track backward from it to the start and
            # use that path if it ends where the arm is now.
            start = (self.kin.ee_pose(side),)
            back, back_reason = track_poses(self.kin, side, target.joint_q, poses[-2::-1] + [start[0]])
            if not back_reason and np.max(np.abs(back[-1] - q0)) < 0.15:
                return np.vstack([q0, back[::-1][1:], target.joint_q])
        raise MotionError(f"following {f['body']}'s joint: {reason}")
