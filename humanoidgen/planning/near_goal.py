"""A carried object's goal near the arm's posture.

The goal solver's cost pulls toward the arm's nominal posture, and its first seed that succeeds wins, so a goal
for a carried object can land on another branch of the arm's inverse kinematics: the same hand pose, or one the
plan's constraints leave as free, reached with the shoulder and elbow turned through 150-200 deg. Moving there
swings the object through a wide arc. Measured on a corpus plan that tips a cup over a bowl in stages (cup_pour_easy,
seed 3): the 40 -> 80 deg stage turned the shoulder's yaw 157 deg and the elbow's roll 179 deg, and the two cubes
inside were thrown 52 cm. So where a carried goal turns some joint more than FAR_JOINT_DEG, the constraints are
solved again from seeds about the arm's posture, with the cost pulling toward that posture, and the first goal
that turns no joint that far is taken.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.planning.goal_solver import GoalResult, GoalSolver
from humanoidgen.sim.layout import Side

FAR_JOINT_DEG = 90.0  # a carried goal turning a joint this far is looked at again
NEAR_SEEDS = 8  # solver seeds about the arm's posture: the posture itself, then perturbed ones
NEAR_SPREAD_RAD = 0.3  # the perturbation's standard deviation per joint


def joint_turn(q_from: np.ndarray, q_to: np.ndarray) -> float:
    """The largest single-joint change between two arm postures (rad)."""
    return float(np.max(np.abs(np.asarray(q_to) - np.asarray(q_from))))


def nearer_goal(solver: GoalSolver, side: Side, constraints: list, q_now: np.ndarray, found: GoalResult,
                seed: int = 0) -> GoalResult | None:
    """A goal meeting `constraints` that turns no joint FAR_JOINT_DEG from `q_now`, where `found` does; None where
    `found` is near already or no nearer goal turns up."""
    limit = np.radians(FAR_JOINT_DEG)
    if joint_turn(q_now, found.q) < limit:
        return None
    arm = solver.kin.arms[side]
    rng = np.random.default_rng(seed)
    for k in range(NEAR_SEEDS):
        start = q_now if k == 0 else q_now + rng.normal(0.0, NEAR_SPREAD_RAD, len(q_now))
        result = solver.solve(side, list(constraints), np.clip(start, arm.lo, arm.hi), q_now, max_seeds=1)
        if result.success and joint_turn(q_now, result.q) < limit:
            return result
    return None
