"""The planning context: one episode's planning state and the robot's commands, shared by stages and recoveries.

It holds the simulation (`env`), the planner's own kinematics and collision world on a scratch copy of the
model, the goal solver, the commanded action, each hand's typed state (`hand_state.HandState`), the events and
the call log, and the budgets recoveries draw on. Its methods are the low-level ones every stage needs: step
the simulation with the current command (each step goes to `on_step`, the recording), run planned samples,
move the fingers, settle, read poses. It knows no verb of the planner API and imports no stage or recovery:
stages (approach, transit, follow, goal, release) are functions of a context; the API object
(`planner.HumanoidMotionPlanner`) owns one.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.planning import shared_hold
from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.constraints import use_kinematics
from humanoidgen.planning.goal_solver import GoalResult, GoalSolver
from humanoidgen.planning.hand_ops import contents, finger_contacts, is_held, is_part
from humanoidgen.planning.hand_state import HandState
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.planning.poses import Pose
from humanoidgen.planning.push_spec import TaskTargets
from humanoidgen.sim.action import ARM_SLICE, HAND_SLICE
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.layout import SIDES, Side
from humanoidgen.sim.scene import SceneObject

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


@dataclass
class PlanningContext:
    env: HumanoidEnv
    seed: int = 0
    on_step: Callable[[np.ndarray], None] | None = None  # called after every control step with the action
    targets: TaskTargets | None = None  # the task's target poses and pushes (None: the task defines none)
    events: list[str] = field(default_factory=list)
    log: list[CallRecord] = field(default_factory=list)
    plan_seconds: list[float] = field(default_factory=list)  # motion-planning time of each arm move
    wider_search: bool = True  # goal search rungs 3-4 (fingers near the table, the wrist's freedom); off to compare
    regripping: bool = False  # the hand lets go of a part to grip it again at once (recoveries/regrip)
    # How many more times a held part may be let go and gripped again on one move: the pipeline's budget
    # (pipeline.BUDGETS), none without a pipeline.
    regrips_left: int = 0
    pipeline: Any = None  # pipeline.Pipeline: the recoveries (None: none, failures stand)

    def __post_init__(self) -> None:
        self.kin = Kinematics(self.env.model)
        use_kinematics(self.env, self.kin)  # constraints anchor hand points with the planner's kinematics
        self.collisions = CollisionWorld(self.kin)
        self.solver = GoalSolver(self.kin, self.collisions, seed=self.seed)
        self.action = self.env.joint_positions()
        self.hands: dict[Side, HandState] = {s: HandState() for s in SIDES}
        self.kin.sync(self.env.data.qpos)
        self.nominal = {s: self.env.init_action()[ARM_SLICE[s]] for s in SIDES}
        self.goal_results: list[GoalResult] = []
        self.init_poses = {s: self.current_pose(s, q=self.nominal[s]) for s in SIDES}  # where each hand starts

    # -- the pipeline, as the stages see it ---------------------------------------------------------------
    def recover(self, stage: str, request: Any, failure: Exception) -> Any:
        """The stage's answer from the first recovery for `failure`; re-raises it where none applies."""
        if self.pipeline is None:
            raise failure
        return self.pipeline.recover(self, stage, request, failure)

    def before(self, stage: str, request: Any) -> bool:
        return self.pipeline is not None and self.pipeline.before(self, stage, request)

    def after(self, stage: str, request: Any) -> None:
        if self.pipeline is not None:
            self.pipeline.after(self, stage, request)

    @property
    def holding(self) -> dict[Side, SceneObject | None]:
        """What each hand holds (a fresh dict: write `hands[side].held`)."""
        return {s: h.held for s, h in self.hands.items()}

    # -- commands ---------------------------------------------------------------------------------------
    def step(self) -> None:
        self.env.step(self.action)
        if self.on_step is not None:
            self.on_step(self.action.copy())

    def run_arm_samples(self, samples: dict[Side, np.ndarray], stop=None) -> None:
        """Per control step, each side's row: 7 arm targets, or 7 arm and 6 finger targets. `stop(ctx, side)`,
        asked after every step, ends a side's rows early: its targets stay as they were (a press to a force)."""
        n = max(len(s) for s in samples.values())
        stopped: set[Side] = set()
        for k in range(n):
            for side, s in samples.items():
                if side in stopped:
                    continue
                row = s[min(k, len(s) - 1)]
                self.action[ARM_SLICE[side]] = row[:7]
                if len(row) > 7:
                    self.action[HAND_SLICE[side]] = row[7:]
            self.step()
            if stop is not None:
                stopped |= {side for side in samples if side not in stopped and stop(self, side)}

    def settle(self, seconds: float = SETTLE_TIME) -> None:
        for _ in range(int(round(seconds * self.env.control_hz))):
            self.step()

    def move_fingers(self, sides: tuple[Side, ...], posture: str, seconds: float = HAND_MOTION_TIME) -> None:
        start = {s: self.action[HAND_SLICE[s]].copy() for s in sides}
        goal = np.array(HAND_POSTURES[posture])
        n = max(1, int(round(seconds * self.env.control_hz)))
        for k in range(1, n + 1):
            for s in sides:
                self.action[HAND_SLICE[s]] = start[s] + (goal - start[s]) * k / n
            self.step()

    # -- reading the state ------------------------------------------------------------------------------
    def current_pose(self, side: Side, q: np.ndarray | None = None) -> Pose:
        self.kin.sync(self.env.data.qpos)
        if q is not None:
            self.kin.set_arm(side, q)
            self.kin.forward()
        p, R = self.kin.ee_pose(side)
        joint_q = self.kin.arm_q(side)
        self.kin.sync(self.env.data.qpos)
        return Pose.from_mat(p, R, joint_q=joint_q, side=side)

    def carries(self, side: Side) -> bool:
        """Whether the hand holds a rigid object (one that moves with the hand, not a part it moves)."""
        held = self.hands[side].held
        return held is not None and not is_part(held)

    def holds(self, side: Side, obj: SceneObject) -> bool:
        return is_held(finger_contacts(self.env.model, self.env.data, side, obj.body))

    def relative_to_hand(self, side: Side, obj: SceneObject) -> np.ndarray:
        p_hand, R_hand = self.env.hand_pose(side)
        return R_hand.T @ (self.env.object_pose(obj.body)[0] - p_hand)

    def touched_by(self, gen) -> set[int]:
        """The body a grip, pinch or push is meant to touch (none for other constraints)."""
        if gen is None or gen.approach_object is None:
            return set()
        return {self.env.model.body(gen.approach_object).id}

    # -- the planner's model ----------------------------------------------------------------------------
    def attach_held(self, side: Side) -> None:
        held = self.hands[side].held
        self.kin.detach(side)
        if held is not None and not is_part(held):
            if shared_hold.shared_object(self.holding) is held:
                # The other hand carries it too (planning knows it as one object in both hands); `side`, attached
                # last, places it while its own arm is planned.
                self.kin.attach(next(s for s in SIDES if s != side), held.body)
            self.kin.attach(side, held.body)

    def ignore_contents(self, side: Side) -> None:
        """What rests in a carried object travels with it: the planner does not avoid it (the caller restores
        the ignore list)."""
        if self.carries(side):
            for o in contents(self.env.scene, self.env.model, self.env.data, self.hands[side].held):
                self.collisions.ignored_bodies.add(self.env.model.body(o.body).id)
