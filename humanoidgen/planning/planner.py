"""The planner API that plan scripts (written by people or LLMs) call, as the paper's prompts use it.

    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="can", obj_id=0, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="can", obj_id=0)

Every call is recorded in `planner.log` (inputs, outcome, time) and notable outcomes in `planner.events`
("grasped can 0", "released cube 1 and it stayed on cube 0"). A call that cannot do its job raises
`PlanningError` with the call's name and the reason, so a script stops at the step that failed.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.planning import constraint_gen, grip_intent, handover, part_ajar, part_release, push_actions, regrip, shared_hold
from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.constraints import Const, Constraint, ConstraintError
from humanoidgen.planning.goal_solver import GoalResult, GoalSolver
from humanoidgen.planning.hand_ops import body_speed, finger_contacts, hand_touches, is_held, resting_on
from humanoidgen.planning.arm_moves import ArmMoves
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.goal_search import GoalSearch
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.regrip import MAX_REGRIPS
from humanoidgen.sim.action import ARM_SLICE, HAND_SLICE
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.layout import OTHER_SIDE, SIDES, Side
from humanoidgen.sim.scene import SceneObject

SLIP_LIMIT = {"pinch": 0.01, "grasp": 0.025}  # a held object moving more than this in the hand was lost (m)
HAND_MOTION_TIME = 0.5  # seconds to move the fingers between postures
SETTLE_TIME = 0.3


@dataclass
class CallRecord:
    call: str
    args: dict
    ok: bool
    message: str
    seconds: float
    sim_time: float


def _sides(hand_name: str) -> tuple[Side, ...]:
    if hand_name == "all":
        return SIDES
    if hand_name in SIDES:
        return (hand_name,)
    raise PlanningError("hand", f"hand_name must be 'left', 'right' or 'all', got {hand_name!r}")


def _summarize(value):
    if isinstance(value, np.ndarray):
        return np.round(value, 4).tolist()
    if isinstance(value, Pose):
        return {"p": np.round(value.p, 4).tolist(), "q": np.round(value.q, 4).tolist()}
    if isinstance(value, (list, tuple)):
        return [_summarize(v) for v in value]
    if isinstance(value, (Constraint, Const)):
        return value.name
    return value


def _logged(fn: Callable) -> Callable:
    @functools.wraps(fn)
    def wrapper(self: "HumanoidMotionPlanner", *args, **kwargs):
        t0, sim0 = time.perf_counter(), self.env.time
        record = CallRecord(fn.__name__, {"args": _summarize(list(args)), **{k: _summarize(v) for k, v in kwargs.items()}},
                            False, "", 0.0, 0.0)
        self.log.append(record)
        try:
            out = fn(self, *args, **kwargs)
            record.ok, record.message = True, record.message or "ok"
            return out
        except PlanningError as exc:
            record.message = exc.reason
            raise
        except (ConstraintError, constraint_gen.ConstraintGenerationError, KeyError, ValueError) as exc:
            record.message = str(exc).strip("'\"")
            raise PlanningError(fn.__name__, record.message) from None
        finally:
            record.seconds = time.perf_counter() - t0
            record.sim_time = self.env.time - sim0

    return wrapper


@dataclass
class HumanoidMotionPlanner(GoalSearch, ArmMoves):
    env: HumanoidEnv
    seed: int = 0
    on_step: Callable[[np.ndarray], None] | None = None  # called after every control step with the action
    events: list[str] = field(default_factory=list)
    log: list[CallRecord] = field(default_factory=list)
    plan_seconds: list[float] = field(default_factory=list)  # motion-planning time of each arm move
    last_approach: dict = field(default_factory=dict)  # side -> approach axis of the hand's last grasp/pinch
    grip: dict = field(default_factory=dict)  # side -> "grasp" or "pinch": how the held object is held
    closing: dict = field(default_factory=dict)  # side -> finger posture the next hand_grasp closes with
    wider_search: bool = True  # goal_search rungs 3-4 (fingers near the table, the wrist's freedom); off to compare
    part_moved: dict = field(default_factory=dict)  # side -> the follow dict of the part the hand last moved
    approach_used: dict = field(default_factory=dict)  # side -> direction the last grip came in along, if not its axis
    goal_moved: dict = field(default_factory=dict)  # side -> the pose a move went to instead of the one asked (drop_in)
    regripping: bool = False  # the hand lets go of a part to grip it again at once (planning/regrip.py)
    regrips_left: int = MAX_REGRIPS  # how many more times a held part may be let go and gripped again on one move

    def __post_init__(self) -> None:
        self.kin = Kinematics(self.env.model)
        self.env.kinematics = self.kin  # constraints anchor hand points with the planner's kinematics
        self.collisions = CollisionWorld(self.kin)
        self.solver = GoalSolver(self.kin, self.collisions, seed=self.seed)
        self.action = self.env.joint_positions()
        self.holding: dict[Side, SceneObject | None] = {s: None for s in SIDES}
        self.kin.sync(self.env.data.qpos)
        self.nominal = {s: self.env.init_action()[ARM_SLICE[s]] for s in SIDES}
        self.left_hand_init_pose = self._current_pose("left", q=self.nominal["left"])
        self.right_hand_init_pose = self._current_pose("right", q=self.nominal["right"])
        self.goal_results: list[GoalResult] = []

    # -- low level --------------------------------------------------------------------------------------
    def _current_pose(self, side: Side, q: np.ndarray | None = None) -> Pose:
        self.kin.sync(self.env.data.qpos)
        if q is not None:
            self.kin.set_arm(side, q)
            self.kin.forward()
        p, R = self.kin.ee_pose(side)
        joint_q = self.kin.arm_q(side)
        self.kin.sync(self.env.data.qpos)
        return Pose.from_mat(p, R, joint_q=joint_q, side=side)

    def _step(self) -> None:
        self.env.step(self.action)
        if self.on_step is not None:
            self.on_step(self.action.copy())

    def _run_arm_samples(self, samples: dict[Side, np.ndarray]) -> None:
        """Per control step, each side's row: 7 arm targets, or 7 arm and 6 finger targets."""
        n = max(len(s) for s in samples.values())
        for k in range(n):
            for side, s in samples.items():
                row = s[min(k, len(s) - 1)]
                self.action[ARM_SLICE[side]] = row[:7]
                if len(row) > 7:
                    self.action[HAND_SLICE[side]] = row[7:]
            self._step()

    def _settle(self, seconds: float = SETTLE_TIME) -> None:
        for _ in range(int(round(seconds * self.env.control_hz))):
            self._step()

    def _move_fingers(self, sides: tuple[Side, ...], posture: str, seconds: float = HAND_MOTION_TIME) -> None:
        start = {s: self.action[HAND_SLICE[s]].copy() for s in sides}
        goal = np.array(HAND_POSTURES[posture])
        n = max(1, int(round(seconds * self.env.control_hz)))
        for k in range(1, n + 1):
            for s in sides:
                self.action[HAND_SLICE[s]] = start[s] + (goal - start[s]) * k / n
            self._step()

    # -- hands ------------------------------------------------------------------------------------------
    @_logged
    def hand_pre_grasp(self, hand_name: str = "all") -> None:
        """Turn the thumb to face the fingers, ready to grasp. Call before moving to a grasp pose."""
        self._posture_with_room(_sides(hand_name), "pre_grasp")

    @_logged
    def hand_pre_pinch(self, hand_name: str = "all") -> None:
        """Oppose thumb and index and tuck the other fingers away, ready to pinch."""
        self._posture_with_room(_sides(hand_name), "pre_pinch")

    @_logged
    def hand_press(self, hand_name: str = "all") -> None:
        """Extend the index finger and curl the others, to press with the fingertip."""
        self._posture_with_room(_sides(hand_name), "press")

    def _close_on(self, side: Side, obj_type: str, obj_id: int, posture: str, verb: str) -> None:
        obj = self.env.scene.object(obj_type, obj_id)
        self._move_fingers((side,), posture, seconds=0.6)
        self._settle(0.3)
        touched = finger_contacts(self.env.model, self.env.data, side, obj.body)
        if not is_held(touched):
            if not touched:
                tip = (f"the hand is not at {obj_type} {obj_id}: check that the move before reached its grip pose, "
                       f"or that {obj_type} {obj_id} did not move away")
            elif "thumb" not in touched:
                other = "pinch" if verb == "grasp" else "grasp"
                tip = (f"the thumb does not reach it: the grip point is off for this part's shape; try "
                       f"action='{other}', another point= of its annotations, or finger_offset= (e.g. 0.02)")
            else:
                tip = "only the thumb touches it: the fingers close past it; try finger_offset=-0.01 or another point="
            raise PlanningError(
                f"hand_{verb}",
                f"the {side} hand closed but does not hold {obj_type} {obj_id} "
                f"(touching: {', '.join(sorted(touched)) or 'nothing'}; a hold needs the thumb against a finger): {tip}",
            )
        self.holding[side] = obj
        self.grip[side] = verb
        self.events.append(f"{'grasped' if verb == 'grasp' else 'pinched'} {obj_type} {obj_id} with the {side} hand")

    @_logged
    def hand_grasp(self, hand_name: str, grasp_object: str, obj_id: int = 0) -> None:
        """Close the whole hand on an object; succeeds only if the object is held between thumb and fingers."""
        for side in _sides(hand_name):
            # Round bodies are wrapped (hands.HAND_POSTURES["wrap"]) when the hand was moved to a wrap grasp.
            self._close_on(side, grasp_object, obj_id, self.closing.get(side) or "grasp", "grasp")

    @_logged
    def hand_pinch(self, hand_name: str, pinch_object: str, obj_id: int = 0) -> None:
        """Close thumb and index on a small object; succeeds only if it is held between them."""
        for side in _sides(hand_name):
            self._close_on(side, pinch_object, obj_id, "pinch", "pinch")

    @_logged
    def open_hand(self, hand_name: str = "all") -> None:
        """Open the fingers and, if they held something, back the hand out along the way it came in, so the
        fingers do not drag the object along on the next move. Where the released object came to rest is an
        event."""
        sides = _sides(hand_name)
        for s in sides:  # a hand-over: the other hand is to keep the object
            held, other = self.holding[s], OTHER_SIDE[s]
            if (held is not None and held.annotations is not None and held.annotations.articulation is None
                    and self.holding[other] is held and other not in sides):
                handover.secure_taker(self, s, held)
        released = [(s, self.holding[s]) for s in sides if self.holding[s] is not None]
        # Let go by loosening into the grip's "pre" posture (a small finger motion that does not sweep the
        # object), back out, and only then open fully.
        for s in sides:
            held = self.holding[s]
            if held is not None and held.annotations is not None and held.annotations.articulation is not None:
                # A hooked handle: back away while the fingers open, so they do not push the part back.
                self.holding[s] = None
                part_release.let_go(self, s, held, self.part_moved.pop(s, None))
                continue
            self._move_fingers((s,), f"pre_{self.grip[s]}" if held is not None else "open")
            self.holding[s] = None
            self.kin.detach(s)
        rigid = [(s, o) for s, o in released if o.annotations is None or o.annotations.articulation is None]
        if rigid:
            self._settle(0.3)
            backed = []
            for side, obj in rigid:
                axis = self.last_approach.get(side)
                self._retreat(side)
                backed.append((side, obj, None if axis is None else -np.asarray(axis, float)))
            self._open_clear_of(backed)
        if released:
            self._settle(0.2)
            for side, obj in released:
                if obj.annotations is not None and obj.annotations.articulation is not None:
                    self.events.append(f"released {obj.type_name} {obj.obj_id} from the {side} hand")
                    continue
                below = resting_on(self.env.scene, self.env.model, self.env.data, obj)
                moving = body_speed(self.env.model, self.env.data, obj.body) > 0.02
                where = " and ".join(below) if below else "nothing"
                state = "is still moving" if moving else f"stayed on {where}"
                self.events.append(f"released {obj.type_name} {obj.obj_id} and it {state}")

    # -- collisions -------------------------------------------------------------------------------------
    @_logged
    def ignore_collision(self, obj_name: str, obj_id: int = 0) -> None:
        """Let the hands touch this object (e.g. a drawer being pulled) until `restore_collision`."""
        self.collisions.ignored_bodies.add(self.env.model.body(self.env.scene.object(obj_name, obj_id).body).id)

    @_logged
    def restore_collision(self, obj_name: str | None = None, obj_id: int = 0) -> None:
        """Avoid this object again (all ignored objects when no name is given)."""
        if obj_name is None:
            self.collisions.ignored_bodies.clear()
        else:
            self.collisions.ignored_bodies.discard(self.env.model.body(self.env.scene.object(obj_name, obj_id).body).id)

    # -- constraints and goal poses ---------------------------------------------------------------------
    @_logged
    def generate_constraints(self, obj_name: str, obj_id: int = 0, action: str = "", hand_name: str = "right",
                             openness: float | None = None, relative_obj_name: str | None = None,
                             relative_obj_id: int | None = None, relative_p: np.ndarray | None = None,
                             point: str | None = None, finger_offset: float = 0.0) -> list:
        """Constraints for an action on an object, from its annotations and the task's targets (see the actions
        below). `hand_name` is "right" unless given (the paper's default); `obj_name` may be a type ("cube"
        with obj_id), a numbered name ("cube1") or an alias the scene lists.

        "target" ("target1", "target2") moves the object the hand holds to the target pose the task defines for
        it (the scene lists each object's targets); without one, "target" lifts it 10 cm (noted in the events).
        `point` picks one annotated point of a grasp/pinch (e.g. "rim"); by default the hand takes the most
        natural of the object's annotations and falls back to the others when that one cannot be reached.
        `finger_offset` (m) holds a grasp/pinch that much further out along the fingers (negative: deeper in the
        hand), e.g. 0.02 to pinch a 3 cm block with the index pad rather than around its corner."""
        if not action:
            raise PlanningError("generate_constraints", f"give action=, one of {', '.join(constraint_gen.ACTIONS)}")
        (side,) = _sides(hand_name) if hand_name != "all" else (None,)
        if side is None:
            raise PlanningError("generate_constraints", "hand_name must be 'left' or 'right' (one hand at a time)")
        request = (obj_name, obj_id, action, side, openness, relative_obj_name, relative_obj_id, relative_p, point,
                   finger_offset)
        gen = self._generate(request)
        if gen.notes:
            self.log[-1].message = "; ".join(gen.notes)
        return list(gen.constraints)

    def _generate(self, request: tuple) -> constraint_gen.Generated:
        self.kin.sync(self.env.data.qpos)
        gen = constraint_gen.generate(self.env, self.holding, *request)
        gen.request = request  # to generate them again where the scene changes before the solve (part_ajar)
        self.events.extend(gen.notes)  # fallbacks and mappings are feedback for the plan's author
        for c in gen.constraints:
            c.meta = gen  # the move needs the approach axis and the part to follow
        return gen

    @_logged
    def generate_end_effector_pose(self, constraints: list, hand_name: str) -> tuple[GoalResult, Pose]:
        """Solve for an arm configuration meeting the constraints; returns (result, target end-effector pose)."""
        (side,) = _sides(hand_name)
        if not constraints:
            raise PlanningError("generate_end_effector_pose", "no constraints given")
        try:
            result, pose = self._solve_grip_or_goal(list(constraints), side)
        except PlanningError as failure:
            gen = getattr(constraints[0], "meta", None)
            part = self._shut_grip_part(gen, side)
            if part is not None:
                # No room for the fingers on a shut part's inner face: lift it ajar, then grip it where it is now.
                part_ajar.lift_ajar(self, side, part)
                constraints = list(self._generate(gen.request).constraints)
                result, pose = self._solve_grip_or_goal(constraints, side)
            elif getattr(gen, "fallback", None) is not None and self.holding[side] is None:
                result, pose, constraints = self._solve_fallback(side, gen, failure)
            else:
                raise
        push_actions.mark(pose, constraints)  # target1/target2 on a part: the move does the push
        return result, pose

    def _solve_grip_or_goal(self, constraints: list, side: Side) -> tuple[GoalResult, Pose]:
        """A goal; for plan-written constraints that put a grip point on an object, solved as that grip
        (the object may be touched, the hand comes in along the grip's axis; see grip_intent)."""
        intent = grip_intent.infer(self.env, side, constraints, self.holding)
        if intent is None:
            return self._solve_goal(constraints, side)
        ways = [intent.first, *intent.first.alternatives]
        mine = {id(c): c for g in ways for c in g.constraints}
        try:
            for c in intent.first.constraints:  # the goal search reads the grip from the first constraint
                c.meta = intent.first
            result, pose = self._solve_goal(list(intent.first.constraints), side)
        finally:  # the plan's Constraint objects stay as the plan made them (it may use them again)
            for c in mine.values():
                c.__dict__.pop("meta", None)
        if (dz := intent.raised_by(result)) > 0.002:
            self.events.append(f"the {intent.operation} of {intent.obj.type_name} {intent.obj.obj_id} is taken "
                               f"{dz * 1000:.0f} mm higher than asked, at its annotated {intent.operation} height: at "
                               "the height asked the fingers would go into the table")
        return result, pose

    def _solve_fallback(self, side: Side, gen, failure: PlanningError) -> tuple[GoalResult, Pose, list]:
        """The grip's last resort (a grasp's: the object's pinch), with the hand set for it; the first grip's
        failure if that cannot be solved either."""
        fallback = gen.fallback
        for c in fallback.constraints:
            c.meta = fallback  # the move needs its approach axis and closing posture
        self._posture_with_room((side,), "pre_pinch")  # the goal is solved with the fingers as they come in
        try:
            result, pose = self._solve_goal(list(fallback.constraints), side)
        except PlanningError:
            raise failure from None
        reason = failure.reason
        if "in contact: " in reason:  # the deepest contact says why, e.g. "R_thumb_distal and table (33.2 mm deep)"
            reason = reason.split("in contact: ", 1)[1].split(")", 1)[0] + ")"
        obj = f"{gen.request[0]} {gen.request[1]}" if gen.request else "the object"
        self.events.append(f"a whole-hand grasp of {obj} does not fit ({reason[:120]}): the {side} hand pinches it "
                           "instead (set to pre_pinch; hand_grasp closes as a pinch)")
        return result, pose, list(fallback.constraints)

    def _shut_grip_part(self, gen, side: Side) -> SceneObject | None:
        """The object of a generated grasp/pinch on a part that lies shut and could be lifted ajar, else None."""
        request = getattr(gen, "request", None)
        if request is None or request[2] not in ("grasp", "pinch") or gen.grip_part is None:
            return None
        obj = self.env.scene.object(*gen.grip_part["obj"])
        return obj if self.holding[side] is None and part_ajar.lies_shut(self.env, obj) else None

    def _touched_by(self, gen) -> set[int]:
        """The body a grip, pinch or push is meant to touch (none for other constraints)."""
        if gen is None or gen.approach_object is None:
            return set()
        return {self.env.model.body(gen.approach_object).id}

    def _slipped(self, side: Side, obj: SceneObject, slip: float) -> str:
        """Why a carried object was lost, and what the plan could do instead (the message is the LLM's feedback)."""
        grip = self.grip.get(side, "pinch")
        touching = finger_contacts(self.env.model, self.env.data, side, obj.body)
        mass = float(self.env.model.body_subtreemass[self.env.model.body(obj.body).id])
        now = f"touching it now: {', '.join(sorted(touching))}" if touching else "no longer touching it"
        if grip == "pinch":
            advice = ("two fingertips did not hold it through the move: try action='grasp' (the whole hand), "
                      "a point= nearer its middle, or shorter moves")
        else:
            advice = "the grasp did not hold it through the move: try a point= nearer its middle, or shorter moves"
        return (f"{obj.type_name} {obj.obj_id} slipped {slip * 1000:.0f} mm in the {side} hand ({grip}, "
                f"{mass:.2f} kg; {now}): {advice}")

    def _stopped_short(self, side: Side, err: float) -> str:
        """Why the hand did not get there, for the plan's author: what it is pressing against, and what to try."""
        touches = hand_touches(self.env.scene, self.env.model, self.env.data, side)
        held = self.holding[side]
        if held is not None:
            touches.pop(f"{held.type_name} {held.obj_id}", None)
        msg = f"the {side} hand stopped {err * 1000:.0f} mm from its target"
        if touches:
            listed = ", ".join(f"{what} ({', '.join(sorted(parts))})" for what, parts in touches.items())
            return (msg + f", pressed against {listed}: the simulation does not let it through (ignore_collision only "
                    "stops the planner avoiding it). Aim short of that surface, move it out of the way first, or "
                    "push a part along the way it gives (generate_constraints with openness=)")
        return msg + (": the arm could not keep to the planned motion (a heavy load or a joint at its limit): "
                      "try a shorter move or a target nearer the robot")

    def _turned_approach(self, side: Side, target: Pose) -> np.ndarray | None:
        """The last approach axis turned as the hand turns on this move: the way out of a grip stays the way in
        relative to the hand (a block turned on its side for a hand-over is let go sideways, not up)."""
        axis = self.last_approach.get(side)
        if axis is None:
            return None
        return target.R @ self._current_pose(side).R.T @ axis

    def _attach_held(self, side: Side) -> None:
        held = self.holding[side]
        self.kin.detach(side)
        if held is not None and (held.annotations is None or held.annotations.articulation is None):
            if shared_hold.shared_object(self.holding) is held:
                # The other hand carries it too (planning knows it as one object in both hands); `side`, attached
                # last, places it while its own arm is planned.
                self.kin.attach(next(s for s in SIDES if s != side), held.body)
            self.kin.attach(side, held.body)

    # -- motion -----------------------------------------------------------------------------------------
    @_logged
    def move_to_pose_with_screw(self, pose, hand_name: str, attach_obj=False, object_name=None, object_id=0,
                                path_constraints: list | None = None) -> None:
        """Move the hand's end effector to `pose` (both hands: lists, index 0 left, 1 right).

        `path_constraints` (Constraint objects) hold at every waypoint, e.g. keep the palm facing down."""
        sides = _sides(hand_name)
        poses = list(pose) if hand_name == "all" else [pose]
        if len(poses) != len(sides):
            raise PlanningError("move_to_pose_with_screw", "with hand_name='all', give a list of two poses [left, right]")
        if len(sides) == 1 and getattr(poses[0], "push", None) is not None:
            return push_actions.execute(self, sides[0], poses[0])  # a task's push on a part (target1/target2)
        samples: dict[Side, np.ndarray] = {}
        targets: dict[Side, Pose] = {}
        for side, target in zip(sides, poses):
            if not isinstance(target, Pose):
                raise PlanningError("move_to_pose_with_screw", f"pose must be a Pose (from generate_end_effector_pose), got {type(target).__name__}")
            mine = [c for c in (path_constraints or []) if c.side == side]
            samples[side] = self._plan_side(side, target, mine)
            target = self.goal_moved.pop(side, target)
            used = self.approach_used.pop(side, None)  # another way in than the operation's axis
            self.last_approach[side] = (used if used is not None else target.approach_axis
                                        if target.approach_axis is not None else self._turned_approach(side, target))
            if target.follow is not None:
                self.part_moved[side] = target.follow  # how the hand is on the part it moves: how to let go
            self.closing[side] = target.posture
            targets[side] = target
        if len(sides) == 2:
            samples = self._coordinate_arms(samples)
        carried = {s: self._relative_to_hand(s, self.holding[s]) for s in sides if self._carries(s)}
        part_start = {s: self._part_openness(t) for s, t in targets.items() if t.follow is not None}
        self._run_arm_samples(samples)
        self._settle(0.2)
        for side, start in part_start.items():
            self._check_part_followed(side, targets[side], start)
        for side, target in targets.items():
            if target.regrip is not None:
                regrip.go_on(self, side, target.regrip)
        for side, target in targets.items():
            err = np.linalg.norm(self._current_pose(side).p - target.p)
            if err <= 0.02 or target.follow is not None:
                continue
            touching = target.approach_object is not None and finger_contacts(
                self.env.model, self.env.data, side, target.approach_object)
            if touching and err <= 0.05:  # the hand arrived against what it came to operate on
                self.log[-1].message = f"stopped {err * 1000:.0f} mm short, touching {target.approach_object}"
                continue
            raise PlanningError("move_to_pose_with_screw", self._stopped_short(side, err))
        for side, before in carried.items():
            slip = np.linalg.norm(self._relative_to_hand(side, self.holding[side]) - before)
            # A wrapped body may settle in the fist when turned (pouring) and still be held; a pinched one that
            # shifted as far is lost unless thumb and a finger still hold it (a block pinched by its end, carried up
            # over a drawer's wall, shifted 12 mm and was let go into the drawer all the same).
            obj = self.holding[side]
            if slip <= SLIP_LIMIT[self.grip.get(side, "pinch")] or (slip <= SLIP_LIMIT["grasp"] and is_held(
                    finger_contacts(self.env.model, self.env.data, side, obj.body))):
                if slip > SLIP_LIMIT["pinch"]:
                    self.events.append(f"{obj.type_name} {obj.obj_id} shifted {slip * 1000:.0f} mm in the {side} hand")
            else:
                self.holding[side] = None
                raise PlanningError("move_to_pose_with_screw", self._slipped(side, obj, slip))
