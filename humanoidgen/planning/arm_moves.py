"""How the planner moves an arm: plans (screw motion, straight approach, sampled detour, part following),
timing, and the check that two arms moving at once keep apart. A mixin of HumanoidMotionPlanner."""

from __future__ import annotations

import time
from contextlib import nullcontext

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.approach import APPROACH_DISTANCES, WRAP_TOUCH, Approaches  # noqa: F401 (re-exported)
from humanoidgen.planning.feedback import motion_advice
from humanoidgen.planning import placing, shared_hold
from humanoidgen.planning.approach import PRE_POSE_TURN_DEG
from humanoidgen.planning.drop_in import DROP_HIGHER_M, drop_in, object_geoms
from humanoidgen.planning.goal_targets import pose_within
from humanoidgen.planning.hand_ops import contents, finger_contacts, is_held
from humanoidgen.planning.motion import (
    JointPath,
    MotionError,
    plan_arm_motion,
    time_dense_path,
)
from humanoidgen.planning.part_grip import FOLLOW_ENOUGH, PartFollowing  # noqa: F401 (FOLLOW_ENOUGH re-exported)
from humanoidgen.planning.part_joint import follow_articulation, follow_openness
from humanoidgen.planning.paths import time_parametrize
from humanoidgen.planning.poses import Pose
from humanoidgen.planning import regrip
from humanoidgen.planning.finger_room import OPEN_CLEARANCE_M, FingerRoom, finger_sweep_clearance
from humanoidgen.sim.action import ARM_SLICE, HAND_SLICE
from humanoidgen.sim.geometry import mat_to_quat, rotation_angle
from humanoidgen.sim.layout import SIDES, Side
from humanoidgen.sim.scene import SceneObject

RETREAT_DISTANCE = 0.10  # after letting go, the hand backs out along its approach axis this far
FOLLOW_TOL = 0.05  # openness: a part this near the asked openness after a move got there
FOLLOW_RETRY = 0.3  # a part that moved at least this share of the way but stopped short is pushed again, once
HAND_MOTION_TIME = 0.5  # seconds to change the fingers' posture on the way (as planner.HAND_MOTION_TIME)
CARRY_LIMITS = {"v_max": 0.6, "a_max": 1.5}  # joint speed (rad/s) and acceleration with an object in the hand
# A carried object that stands on something (or is within this of it) and is to be turned more than this is first
# lifted straight up this far: turned where it stands, its lower edge drags on the support and twists it out of a
# pinch.
LIFT_BEFORE_TURN_DEG = 20.0
LIFT_BEFORE_TURN_M = 0.05
RISE_FIRST_M = 0.06  # an empty hand boxed in beside an object rises this much before planning its way out


def _with_hand(arm: np.ndarray, hand: np.ndarray) -> np.ndarray:
    """Arm samples (n, 7) with the hand's targets (6,) on every row: (n, 13)."""
    return np.hstack([arm, np.repeat(hand[None], len(arm), 0)])


class ArmMoves(PartFollowing, Approaches, FingerRoom):
    """Arm motion planning for HumanoidMotionPlanner (uses its env, kin, collisions, holding, log, seed).

    A planned move is an (n, 13) array per arm: 7 arm joint targets and the hand's 6 finger targets per
    control step, so that the fingers can change on the way (open at the pre-pose before coming in)."""

    def _retreat(self, side: Side, open_fingers: bool = False) -> None:
        """Back the hand out along its last approach axis (best effort: skipped if that way is blocked),
        optionally opening the fingers on the way."""
        axis = self.last_approach.get(side)
        if axis is None:
            if open_fingers:
                self._move_fingers((side,), "open")
            return
        self.kin.sync(self.env.data.qpos)
        if open_fingers:
            # The fingers open on the way out: check the way with them open, or the closed fingers around a
            # handle would block every way back.
            self.kin.set_hand(side, np.array(HAND_POSTURES["open"]))
            self.kin.forward()
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
            # Unhook in place first: backing out with the fingers still around a handle drags the part after the
            # hand (a shut drawer pulled open again by ~7 mm).
            self._loosen_in_place(side)
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
        them one after the other (left first, then right), and if that collides too, give up with a reason.
        Arms carrying one object together move in step (shared_hold) and never one after the other."""
        self.kin.sync(self.env.data.qpos)
        for side in SIDES:
            self._attach_held(side)
        together = shared_hold.shared_object(self.holding) is not None
        if together:
            samples = shared_hold.in_step(self.kin, samples)
            self.kin.sync(self.env.data.qpos)

        def clear(left: np.ndarray, right: np.ndarray) -> bool:
            # Each arm's own path was checked against the scene when it was planned; here only arm vs arm.
            n = max(len(left), len(right))
            for k in range(0, n, 2):
                self.kin.set_arm("left", left[min(k, len(left) - 1), :7])
                self.kin.set_arm("right", right[min(k, len(right) - 1), :7])
                self.kin.forward()
                if self.collisions.arm_arm_distance() < 0.003:
                    return False
            return True

        try:
            left, right = samples["left"], samples["right"]
            if clear(left, right):
                return samples
            if together:
                raise PlanningError("move_to_pose_with_screw", "the two arms carrying "
                                    f"{self.holding['left'].type_name} {self.holding['left'].obj_id} together would "
                                    "collide with each other on the way")
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

    def _turns_standing_object(self, side: Side, target: Pose) -> bool:
        """Whether the hand carries an object that rests on something and the move turns it by more than
        LIFT_BEFORE_TURN_DEG."""
        if not self._carries(side) or placing.height_above_support(self.env, self.holding[side]) > LIFT_BEFORE_TURN_M:
            return False
        _, R_now = self.kin.ee_pose(side)
        return np.degrees(rotation_angle(R_now, target.R)) > LIFT_BEFORE_TURN_DEG

    def _plan_side(self, side: Side, target: Pose, path_constraints: list = ()) -> np.ndarray:
        t0 = time.perf_counter()
        self.goal_moved.pop(side, None)
        try:
            with self._touch_for(side, target):
                return self._plan_side_timed(side, target, path_constraints)
        finally:
            self.plan_seconds.append(time.perf_counter() - t0)

    def _touch_for(self, side: Side, target: Pose):
        """The fingers may come closer to the table on the way to a goal that was solved that way."""
        if not getattr(target, "finger_table_slack", 0.0):
            return nullcontext()
        table = self.collisions.body_geoms(self.env.model.body("table").id)
        return self.collisions.allow_touch(self.collisions.finger_geoms(side), table, target.finger_table_slack)

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
        hand = self.action[HAND_SLICE[side]].copy()
        try:
            legs: list[JointPath] = []
            posture = None
            if target.follow is None and self._turns_standing_object(side, target):
                try:
                    p_now, R_now = self.kin.ee_pose(side)
                    legs.append(plan_arm_motion(self.kin, self.collisions, side, q0,
                                                (p_now + np.array([0.0, 0.0, LIFT_BEFORE_TURN_M]), R_now),
                                                allow_sampling=False))
                    q0 = legs[-1].waypoints[-1]
                except MotionError:
                    pass  # no room straight above: turn it from where it is
            if target.follow is not None:
                try:
                    path = self._follow_part(side, q0, target)
                    return _with_hand(time_dense_path(path, dt, v_max=0.6, a_max=2.0), hand)
                except MotionError:
                    # A fingertip pushing a part (nothing held) may instead go straight to the solved goal.
                    if self.holding[side] is not None or target.joint_q is None:
                        raise
                    target = Pose(target.p, target.q, joint_q=target.joint_q, side=side)
            if target.approach_axis is not None and target.joint_q is not None:
                # Come in straight along the approach axis from a pre-pose reached any collision-free way.
                plan = self._plan_approach(side, q0, target)
                legs, posture = plan.legs, plan.posture
                if plan.axis is not None:
                    self.approach_used[side] = plan.axis  # the way back out after the grip
                if "solved" in plan.label or posture is not None or plan.axis is not None:  # not the way asked
                    self.events.append(f"the {side} hand came in {plan.label}"
                                       + (f" with the fingers {posture}" if posture else ""))
            else:
                legs += self._plain_move(side, q0, target, path_constraints)
        except MotionError as exc:
            advice = "" if "Suggestion" in str(exc) else motion_advice(str(exc))
            raise PlanningError("move_to_pose_with_screw",
                                f"{side} arm: {exc}" + (f". Suggestion: {advice}" if advice else "")) from None
        finally:
            self.collisions.ignored_bodies = ignored_before
            self.kin.sync(self.env.data.qpos)
        out = []
        # Gentler with something in the hand: a pinched object slips under hard accelerations (on a planned path
        # too: there the fastest profile swings a block held by its end out of the fingers).
        carrying = self._carries(side)
        for k, leg in enumerate(legs):
            if leg.method == "rrt_connect":
                samples = time_parametrize(leg.waypoints, dt=dt, **(CARRY_LIMITS if carrying else {}))[1]
            else:
                v, a = (CARRY_LIMITS["v_max"], CARRY_LIMITS["a_max"]) if carrying else (1.0, 3.0)
                samples = time_dense_path(leg.waypoints, dt, v_max=v, a_max=a)
            if k == len(legs) - 1 and posture is not None and len(legs) > 1:
                # Change the fingers at the pre-pose, arm still, before the last (straight) leg.
                goal = np.array(HAND_POSTURES[posture])
                n = max(1, int(round(HAND_MOTION_TIME * self.env.control_hz)))
                hold = np.repeat(out[-1][-1:, :7], n, 0) if out else np.repeat(samples[:1], n, 0)
                fingers = hand + (goal - hand) * (np.arange(1, n + 1) / n)[:, None]
                out.append(np.hstack([hold, fingers]))
                hand = goal
            out.append(_with_hand(samples, hand))
        return np.vstack(out)

    def _plain_move(self, side: Side, q0: np.ndarray, target: Pose, path_constraints: list) -> list[JointPath]:
        """A screw motion (or a sampled path) to the target; an empty hand boxed in where it is (just let go
        beside an object) rises straight up first and plans from there."""
        def plan(q: np.ndarray) -> JointPath:
            return plan_arm_motion(self.kin, self.collisions, side, q, (target.p, target.R), q_goal=target.joint_q,
                                   path_constraints=path_constraints, seed=self.seed)
        try:
            return [plan(q0)]
        except MotionError as exc:
            if path_constraints:
                raise
            if self.holding[side] is not None:
                legs = self._carry_into(side, q0, target) if self._carries(side) else None
                if legs is None:
                    raise
                return legs
            first = exc
        self.kin.set_arm(side, q0)
        self.kin.forward()
        p_now, R_now = self.kin.ee_pose(side)
        try:
            rise = plan_arm_motion(self.kin, self.collisions, side, q0,
                                   (p_now + np.array([0.0, 0.0, RISE_FIRST_M]), R_now), allow_sampling=False)
            legs = [rise, plan(rise.waypoints[-1])]
        except MotionError:
            raise first from None
        self.events.append(f"the {side} hand rose {RISE_FIRST_M * 100:.0f} cm first: the way from where it was "
                           "is blocked")
        return legs

    def _carry_into(self, side: Side, q0: np.ndarray, target: Pose) -> list[JointPath] | None:
        """A carried object's goal inside a deep container, out of the hand's way (`drop_in`): the object's centre
        straight above that goal, clear of the container's top, where letting go drops it in; None if that is not
        it. The hand keeps its present orientation if it can (a pinched block swung about slips), else takes the
        goal's."""
        held = self.holding[side]
        p_hand, R_hand = self.env.hand_pose(side)
        p_obj, R_obj = placing.object_pose(self.env, held)
        centre = target.p + target.R @ R_hand.T @ (p_obj - p_hand)  # where the plan puts the object's centre
        way = drop_in(self.env, held, centre, target.R @ R_hand.T @ R_obj)
        if way is None:
            return None
        what = f"{way.container.type_name} {way.container.obj_id}"
        # Hand orientations to try, where the hand goes with each for the object's centre to be at `centre`, and
        # how far up that goal moves with the object so turned (lowest first).
        hands = [(R, p, way.raises(held, centre, R @ R_hand.T @ R_obj))
                 for R, p in ((R_hand, centre - (p_obj - p_hand)), (target.R, target.p))]
        for k in range(len(DROP_HIGHER_M)):
            for R, p, raises in hands:
                goal = p + np.array([0.0, 0.0, raises[k]])
                solved = self.solver.solve(side, pose_within(side, goal, R, PRE_POSE_TURN_DEG,
                                                             f"{held.type_name} {held.obj_id} above {what}"),
                                           q0, self.nominal[side])
                if not solved.success or not self._opens_clear(side, solved.q, way.container):
                    continue
                try:
                    leg = plan_arm_motion(self.kin, self.collisions, side, q0, (solved.ee_pos, solved.ee_mat),
                                          q_goal=solved.q, seed=self.seed)
                except MotionError:
                    continue
                self.goal_moved[side] = Pose(solved.ee_pos, mat_to_quat(solved.ee_mat), joint_q=solved.q, side=side)
                rise = float(solved.ee_pos[2] - target.p[2])
                self.events.append(f"the {side} hand brought {held.type_name} {held.obj_id} {rise * 100:.0f} cm above "
                                   f"where asked, clear of {what}'s top: no way leads down between its walls; let go "
                                   "there, it drops in")
                return [leg]
        return None

    def _opens_clear(self, side: Side, q: np.ndarray, obj: SceneObject) -> bool:
        """Whether the hand, with the arm at `q`, can open its fingers fully without coming within
        OPEN_CLEARANCE_M of `obj`."""
        self.kin.set_arm(side, q)
        try:
            d, _ = finger_sweep_clearance(self.kin, self.collisions, side, self.action[HAND_SLICE[side]].copy(),
                                          np.array(HAND_POSTURES["open"]), object_geoms(self.env.model, obj))
        finally:
            self.kin.sync(self.env.data.qpos)
        return d >= OPEN_CLEARANCE_M

    def _part_openness(self, target: Pose) -> float | None:
        if target.follow is None:
            return None
        return follow_openness(self.env, target.follow)  # the followed joint's (a knob's own, on a door)

    def _check_part_followed(self, side: Side, target: Pose, start: float) -> None:
        """After a move that rides with a part: did the part get to the openness asked? One more push from where
        it stopped if it moved a good part of the way; a part that stays short is an error that says why (or an
        event, when it went most of the way)."""
        f = target.follow
        obj = self.env.scene.object(*f["obj"])
        wanted = follow_articulation(self.env, f).openness_of(f["q_target"])
        got = self._part_openness(target)
        way = wanted - start
        if abs(got - wanted) <= FOLLOW_TOL or abs(way) < 1e-6:
            return
        if (got - start) / way >= FOLLOW_RETRY:
            try:
                self._run_arm_samples({side: self._plan_side(side, target)})
                self._settle(0.2)
            except (MotionError, PlanningError):
                pass  # no way on from where the part stopped: it stays there, judged below as it is
            got = self._part_openness(target)
            if abs(got - wanted) <= FOLLOW_TOL:
                self.events.append(f"pushed {obj.type_name} {obj.obj_id} a second time to reach openness {round(wanted, 2):g}")
                return
        share = (got - start) / way
        label = f"{obj.type_name} {obj.obj_id}"
        to_shut = wanted <= regrip.SHUT < got and self.holding[side] is not None and target.regrip is None \
            and self.regrips_left > 0
        if share >= 0.5:
            self.events.append(f"{label} reached openness {got:.2f} of the {wanted:g} asked")
            if to_shut:
                # Short of shut, held: let go and push it shut where the task has a push (regrip.go_on), as
                # where the arm's reach ends; where that fails it stays here, as before.
                target.regrip = regrip.request(f, wanted, self.grip[side], got, optional=True,
                                               why=f"{label} stopped at openness {got:.2f} in the {side} hand")
            return
        shut_after = target.regrip is not None and target.regrip["openness"] <= regrip.SHUT  # part_grip stops short
        if to_shut or shut_after:
            # The grip came off (a lid's tab slips out of the fingers): let go and push it shut from here; where
            # neither the push nor a second grip gets it shut, the move fails as before.
            why = f"{label} stayed at openness {got:.2f}, the {side} hand's grip on it slipping"
            if shut_after:
                target.regrip.update(reached=got, why=why)
            else:
                target.regrip = regrip.request(f, wanted, self.grip[side], got, optional=False, why=why)
            return
        if self.holding[side] is not None:
            why = (f"the {side} hand's grip on it {'came off' if not self._holds(side, obj) else 'held, but the part did not follow'}: "
                   f"grasp it again and move it in smaller steps of openness")
        else:
            why = ("the fingertip did not carry it (it slid off or lost contact): put the fingertip where the part "
                   "has to give way (for a flip: under the edge, e.g. offset along the part's inner axis), push in "
                   "smaller steps with explicit Constraints, or grasp it and move it with openness=")
        raise PlanningError("move_to_pose_with_screw",
                            f"{label} is at openness {got:.2f} after the move, not the {round(wanted, 2):g} asked (it moved "
                            f"{max(share, 0.0) * 100:.0f}% of the way from {start:.2f}): {why}")

    def _holds(self, side: Side, obj: SceneObject) -> bool:
        return is_held(finger_contacts(self.env.model, self.env.data, side, obj.body))
