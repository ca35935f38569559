"""The planner API that plan scripts (written by people or LLMs) call, as the paper's prompts use it.

    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="can", obj_id=0, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="can", obj_id=0)

Every call is recorded in `planner.log` (inputs, outcome, time) and notable outcomes in `planner.events`
("grasped can 0", "released cube 1 and it stayed on cube 0"). A call that cannot do its job raises
`PlanningError` with the call's name and the reason, so a script stops at the step that failed.

Rule: this module holds the paper's verbs only. Each verb checks its arguments, builds the stage's request and
runs the stage on the planning context (`context.PlanningContext`), whose pipeline (`pipeline.py`) holds the
recoveries; nothing here plans or steps the simulation itself.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable

import numpy as np

from humanoidgen.planning import constraint_gen, finger_room, goal_entry, grip, move, push_actions, release
from humanoidgen.planning.constraints import Const, Constraint, ConstraintError
from humanoidgen.planning.context import CallRecord, PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.goal_solver import GoalResult
from humanoidgen.planning.pipeline import BUDGETS, Pipeline
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.push_spec import TaskTargets
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.layout import ROBOT, SIDES, Side


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
        ctx = self.ctx
        t0, sim0 = time.perf_counter(), ctx.env.time
        record = CallRecord(fn.__name__, {"args": _summarize(list(args)), **{k: _summarize(v) for k, v in kwargs.items()}},
                            False, "", 0.0, 0.0)
        ctx.log.append(record)
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
            record.sim_time = ctx.env.time - sim0

    return wrapper


class HumanoidMotionPlanner:
    """The paper's planner API on one episode's simulation. `on_step(action)` is called after every control
    step (the recording); `targets`: the task's target poses and pushes (`push_spec.TaskTargets`: a task's scene
    has them as `scene.targets`), None where the task defines none; `wider_search=False` leaves out the goal
    search's last rungs (to compare)."""

    def __init__(self, env: HumanoidEnv, seed: int = 0, on_step: Callable[[np.ndarray], None] | None = None,
                 targets: TaskTargets | None = None, wider_search: bool = True) -> None:
        self.ctx = PlanningContext(env, seed=seed, on_step=on_step, targets=targets, wider_search=wider_search,
                                   pipeline=Pipeline(), regrips_left=BUDGETS.regrips)
        self.left_hand_init_pose = self.ctx.init_poses["left"]
        self.right_hand_init_pose = self.ctx.init_poses["right"]

    # What plans, the episode worker and the benches read: the context's, under the names the API has had.
    env = property(lambda self: self.ctx.env)
    seed = property(lambda self: self.ctx.seed)
    events = property(lambda self: self.ctx.events)
    log = property(lambda self: self.ctx.log)
    plan_seconds = property(lambda self: self.ctx.plan_seconds)
    goal_results = property(lambda self: self.ctx.goal_results)
    holding = property(lambda self: self.ctx.holding)

    @property
    def on_step(self) -> Callable[[np.ndarray], None] | None:
        return self.ctx.on_step

    @on_step.setter
    def on_step(self, hook: Callable[[np.ndarray], None] | None) -> None:
        self.ctx.on_step = hook

    # -- the robot's workspace ---------------------------------------------------------------------------
    def workspace_point(self, p) -> np.ndarray:
        """Where a position written for the reference workspace (the robot the task's plans were written for)
        lies for this robot: a hand-over spot, a height to lift to. Positions about reach, not about an object,
        so that one plan puts them where each robot's arms work; the reference robot gets `p` back unchanged."""
        try:
            return ROBOT.workspace.point(p)
        except ValueError as exc:
            raise PlanningError("workspace_point", str(exc)) from None

    # -- hands ------------------------------------------------------------------------------------------
    @_logged
    def hand_pre_grasp(self, hand_name: str = "all") -> None:
        """Turn the thumb to face the fingers, ready to grasp. Call before moving to a grasp pose."""
        finger_room.posture_with_room(self.ctx, _sides(hand_name), "pre_grasp")

    @_logged
    def hand_pre_pinch(self, hand_name: str = "all") -> None:
        """Oppose thumb and index and tuck the other fingers away, ready to pinch."""
        finger_room.posture_with_room(self.ctx, _sides(hand_name), "pre_pinch")

    @_logged
    def hand_press(self, hand_name: str = "all") -> None:
        """Extend the index finger and curl the others, to press with the fingertip."""
        finger_room.posture_with_room(self.ctx, _sides(hand_name), "press")

    @_logged
    def hand_grasp(self, hand_name: str, grasp_object: str, obj_id: int = 0) -> None:
        """Close the whole hand on an object; succeeds only if the object is held between thumb and fingers."""
        for side in _sides(hand_name):
            # Round bodies are wrapped (hands.HAND_POSTURES["wrap"]) when the hand was moved to a wrap grasp.
            grip.close_on(self.ctx, side, grasp_object, obj_id, self.ctx.hands[side].closing or "grasp", "grasp")

    @_logged
    def hand_pinch(self, hand_name: str, pinch_object: str, obj_id: int = 0) -> None:
        """Close thumb and index on a small object; succeeds only if it is held between them."""
        for side in _sides(hand_name):
            grip.close_on(self.ctx, side, pinch_object, obj_id, "pinch", "pinch")

    @_logged
    def open_hand(self, hand_name: str = "all") -> None:
        """Open the fingers and, if they held something, back the hand out along the way it came in, so the
        fingers do not drag the object along on the next move. Where the released object came to rest is an
        event."""
        release.open_hands(self.ctx, _sides(hand_name))

    # -- collisions -------------------------------------------------------------------------------------
    def _body_id(self, obj_name: str, obj_id: int) -> int:
        return self.ctx.env.model.body(self.ctx.env.scene.object(obj_name, obj_id).body).id

    @_logged
    def ignore_collision(self, obj_name: str, obj_id: int = 0) -> None:
        """Let the hands touch this object (e.g. a drawer being pulled) until `restore_collision`."""
        self.ctx.collisions.ignored_bodies.add(self._body_id(obj_name, obj_id))

    @_logged
    def restore_collision(self, obj_name: str | None = None, obj_id: int = 0) -> None:
        """Avoid this object again (all ignored objects when no name is given)."""
        if obj_name is None:
            self.ctx.collisions.ignored_bodies.clear()
        else:
            self.ctx.collisions.ignored_bodies.discard(self._body_id(obj_name, obj_id))

    # -- constraints and goal poses ---------------------------------------------------------------------
    @_logged
    def generate_constraints(self, obj_name: str, obj_id: int = 0, action: str = "", hand_name: str = "right",
                             openness: float | None = None, relative_obj_name: str | None = None,
                             relative_obj_id: int | None = None, relative_p: np.ndarray | None = None,
                             point: str | None = None, finger_offset: float = 0.0,
                             force: float | None = None) -> list:
        """Constraints for an action on an object, from its annotations and the task's targets (see the actions
        below). `hand_name` is "right" unless given (the paper's default); `obj_name` may be a type ("cube"
        with obj_id), a numbered name ("cube1") or an alias the scene lists.

        "target" ("target1", "target2") moves the object the hand holds to the target pose the task defines for
        it (the scene lists each object's targets); without one, "target" lifts it 10 cm (noted in the events).
        `point` picks one annotated point of a grasp/pinch (e.g. "rim"); by default the hand takes the most
        natural of the object's annotations and falls back to the others when that one cannot be reached.
        `finger_offset` (m) holds a grasp/pinch that much further out along the fingers (negative: deeper in the
        hand), e.g. 0.02 to pinch a 3 cm block with the index pad rather than around its corner.
        `force` (N, action="press" only): press until the fingertip pushes the part that hard (past the part's
        end stop if need be; with openness, no deeper than that)."""
        if not action:
            raise PlanningError("generate_constraints", f"give action=, one of {', '.join(constraint_gen.ACTIONS)}")
        (side,) = _sides(hand_name) if hand_name != "all" else (None,)
        if side is None:
            raise PlanningError("generate_constraints", "hand_name must be 'left' or 'right' (one hand at a time)")
        request = (obj_name, obj_id, action, side, openness, relative_obj_name, relative_obj_id, relative_p, point,
                   finger_offset, force)
        gen = goal_entry.generate(self.ctx, request)
        if gen.notes:
            self.ctx.log[-1].message = "; ".join(gen.notes)
        return list(gen.constraints)

    @_logged
    def generate_end_effector_pose(self, constraints: list, hand_name: str) -> tuple[GoalResult, Pose]:
        """Solve for an arm configuration meeting the constraints; returns (result, target end-effector pose)."""
        (side,) = _sides(hand_name)
        if not constraints:
            raise PlanningError("generate_end_effector_pose", "no constraints given")
        result, pose, constraints = goal_entry.goal(self.ctx, side, constraints)
        push_actions.mark(pose, constraints)  # target1/target2 on a part: the move does the push
        return result, pose

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
        move.move_hands(self.ctx, sides, poses, path_constraints, verbs=self)


__all__ = ["HumanoidMotionPlanner", "PlanningError"]  # PlanningError: plans and tests catch it from here
