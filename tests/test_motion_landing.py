"""The last stretch of a straight move lands on the goal solver's configuration in joint space when the damped
tracking stalls a hair short of it (planning/motion.py `joint_landing`), keeping the move's path constraints."""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.queries import get_axis_in_env
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.motion import LANDING_MAX_RAD, joint_landing
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.scene import SceneBuilder

from plan_runs import task_planner  # noqa: E402


def _turned(v: np.ndarray, deg: float) -> np.ndarray:
    perp = np.cross(v, [0.0, 0.0, 1.0] if abs(v[2]) < 0.9 else [1.0, 0.0, 0.0])
    perp /= np.linalg.norm(perp)
    a = np.radians(deg)
    return np.cos(a) * v + np.sin(a) * perp


def test_joint_landing_keeps_path_constraints_as_well_as_the_goal_does():
    env = HumanoidEnv(SceneBuilder().build())
    planner = task_planner(env)
    kin = planner.ctx.kin
    kin.sync(env.data.qpos)
    q0 = kin.arm_q("right").copy()
    palm = get_axis_in_env(env, "right_grasp_axis")

    def keep(deg: float) -> Constraint:
        return Constraint(env, "parallel", "r_hand_base_link", hand_axis=palm, object_axis=_turned(palm, deg))

    small = q0 + np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.01])
    path = joint_landing(kin, "right", q0, small, [keep(0.0)])
    assert path is not None and path.shape == (6, 7) and np.allclose(path[-1], small)
    assert np.allclose(kin.arm_q("right"), q0)  # the model is left as it was
    # the goal misses the constraint by 3 deg (an object turned in the hand): it may, by no more than that
    assert joint_landing(kin, "right", q0, q0, [keep(3.0)]) is not None
    assert joint_landing(kin, "right", q0, q0, [keep(8.0)]) is None
    # a turn of the wrist on the way breaks the constraint: no landing; nor over a long way
    assert joint_landing(kin, "right", q0, q0 + np.r_[np.zeros(6), 0.25], [keep(0.0)]) is None
    assert joint_landing(kin, "right", q0, q0 + np.r_[np.zeros(6), LANDING_MAX_RAD + 0.1]) is None
