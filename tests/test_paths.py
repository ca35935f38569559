"""Joint-space paths: validity, RRT-Connect around a wall, determinism, timing."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from humanoidgen.planning.collision import CollisionWorld  # noqa: E402
from humanoidgen.planning.kinematics import Kinematics  # noqa: E402
from humanoidgen.planning.paths import (  # noqa: E402
    A_MAX,
    V_MAX,
    JointSpace,
    is_valid,
    plan_rrt_connect,
    segment_valid,
    straight_path,
    time_parametrize,
)
from humanoidgen.sim.env import INIT_ARM_QPOS, HumanoidEnv  # noqa: E402
from humanoidgen.sim.ik import AxisGoal, solve_arm_ik_restarts  # noqa: E402
from humanoidgen.sim.layout import HAND_BASE_ON_WRIST_POS  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402

# A thin wall standing on the table just outside the right hand (x -0.56..-0.20, y -0.35..-0.33, z 0..0.30).
WALL_POS = (-0.38, -0.34, 0.15)
WALL_HALF = (0.18, 0.01, 0.15)
GOAL_HAND_POS = (-0.45, -0.50, 0.20)  # beyond the wall
CHECK_STEP = 0.01  # rad: the independent check samples twice as densely as the planner


class World:
    def __init__(self) -> None:
        builder = SceneBuilder()
        _, body = builder.add_object_body("block", np.array(WALL_POS), free=False)
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=list(WALL_HALF), rgba=[0.3, 0.3, 0.8, 1.0])
        self.scene = builder.build()
        self.model = self.scene.model
        self.env = HumanoidEnv(self.scene)
        self.kin = Kinematics(self.model)
        self.kin.sync(self.env.data.qpos)
        self.cw = CollisionWorld(self.kin)
        self.wall_geom = int(np.flatnonzero(self.model.geom_bodyid == self.model.body("block_0").id)[0])
        self.right_geoms = set(self.cw.movers("right"))
        self.q_start = np.array(INIT_ARM_QPOS["right"])
        # Goal: the hand beyond the wall, turned as at the start.
        wR = self.kin.data.xmat[self.kin.arms["right"].wrist].reshape(3, 3).copy()
        axes = (AxisGoal(np.array([1.0, 0, 0]), wR[:, 0], 5.0), AxisGoal(np.array([0, 0, 1.0]), wR[:, 2], 5.0))
        ik = solve_arm_ik_restarts(self.model, self.kin.data, "right", np.array(HAND_BASE_ON_WRIST_POS),
                                   np.array(GOAL_HAND_POS), axes, seeds=[self.q_start])
        assert ik.converged
        self.q_goal = ik.qpos

    def wall_contacts(self, side_q: dict[str, np.ndarray]) -> int:
        """Independent check: the whole configuration in a fresh MjData, MuJoCo's own collision detection,
        count contacts between a right arm/hand geom and the wall."""
        data = mujoco.MjData(self.model)
        data.qpos[:] = self.env.data.qpos
        for side, q in side_q.items():
            data.qpos[self.kin.arms[side].qadr] = q
        mujoco.mj_forward(self.model, data)
        n = 0
        for c in data.contact[:data.ncon]:
            g = {int(c.geom1), int(c.geom2)}
            if self.wall_geom in g and g & self.right_geoms:
                n += 1
        return n


@pytest.fixture(scope="module")
def world() -> World:
    return World()


@pytest.fixture(scope="module")
def right_plan(world):
    return plan_rrt_connect(world.kin, world.cw, "right", world.q_start, world.q_goal, time_limit=5.0, seed=7)


def dense(path: np.ndarray, step: float) -> np.ndarray:
    return np.vstack([straight_path(a, b, step)[:-1] for a, b in zip(path[:-1], path[1:])] + [path[-1:]])


def test_joint_space_dims_and_limits(world):
    for which, dof in (("left", 7), ("right", 7), ("all", 14)):
        js = JointSpace.of(world.kin, which)
        assert js.dof == dof and js.lo.shape == js.hi.shape == (dof,) and np.all(js.lo < js.hi)
    js = JointSpace.of(world.kin, "all")
    np.testing.assert_array_equal(js.qadr[:7], world.kin.arms["left"].qadr)
    np.testing.assert_array_equal(js.hi[7:], world.kin.arms["right"].hi)
    with pytest.raises(ValueError):
        JointSpace.of(world.kin, "both")
    assert not is_valid(world.kin, world.cw, "right", js.hi[7:] + 0.1)  # beyond the limits


def test_start_goal_valid_straight_line_hits_wall(world):
    kin, cw = world.kin, world.cw
    assert is_valid(kin, cw, "right", world.q_start)
    assert is_valid(kin, cw, "right", world.q_goal)
    assert world.wall_contacts({"right": world.q_start}) == 0
    assert world.wall_contacts({"right": world.q_goal}) == 0
    assert not segment_valid(kin, cw, "right", world.q_start, world.q_goal)
    # MuJoCo itself sees the straight line going through the wall (the independent check can fail).
    line = straight_path(world.q_start, world.q_goal, CHECK_STEP)
    assert sum(world.wall_contacts({"right": q}) > 0 for q in line) > 0


def test_rrt_connect_detours_around_wall(world, right_plan):
    res = right_plan
    assert res.ok, res.reason
    assert res.reason == "planned"
    path = res.path
    assert path.shape[1] == 7 and len(path) >= 3
    np.testing.assert_array_equal(path[0], world.q_start)
    np.testing.assert_array_equal(path[-1], world.q_goal)
    js = JointSpace.of(world.kin, "right")
    for q in dense(path, CHECK_STEP):
        assert js.within_limits(q)
        assert is_valid(world.kin, world.cw, "right", q)
        assert world.wall_contacts({"right": q}) == 0
    print(f"right arm: {res.planning_time:.3f} s, {len(path)} waypoints")


def test_same_seed_same_path(world, right_plan):
    before = world.kin.data.qpos.copy()
    again = plan_rrt_connect(world.kin, world.cw, "right", world.q_start, world.q_goal, time_limit=5.0, seed=7)
    assert again.ok
    np.testing.assert_array_equal(world.kin.data.qpos, before)  # the scratch arm is put back where it was
    np.testing.assert_array_equal(again.path, right_plan.path)


def test_start_inside_wall_is_refused(world):
    line = straight_path(world.q_start, world.q_goal, CHECK_STEP)
    inside = next(q for q in line if world.wall_contacts({"right": q}) > 0)
    res = plan_rrt_connect(world.kin, world.cw, "right", inside, world.q_goal, time_limit=1.0)
    assert res.path is None and not res.ok
    assert res.reason.startswith("start invalid") and "block_0" in res.reason
    res = plan_rrt_connect(world.kin, world.cw, "right", world.q_start, inside, time_limit=1.0)
    assert res.path is None and res.reason.startswith("goal invalid")


def test_free_straight_line_is_direct(world):
    q1 = world.q_start + np.array([0.1, 0.05, 0, -0.1, 0, 0, 0])
    res = plan_rrt_connect(world.kin, world.cw, "right", world.q_start, q1)
    assert res.reason == "direct" and len(res.path) == 2


def test_time_parametrization_limits(right_plan):
    path, dt = right_plan.path, 0.02
    t, q = time_parametrize(path, dt=dt)
    assert t[0] == 0 and np.allclose(np.diff(t), dt)
    np.testing.assert_allclose(q[0], path[0])
    np.testing.assert_allclose(q[-1], path[-1])
    vel = np.diff(q, axis=0) / dt
    acc = np.diff(q, 2, axis=0) / dt ** 2
    assert np.abs(vel).max() <= V_MAX * 1.05
    assert np.abs(acc).max() <= A_MAX * 1.05
    assert np.abs(vel).max() >= V_MAX * 0.5  # it does move briskly, not crawl
    # At rest at both ends: the first and last steps are only what one period of acceleration allows.
    assert np.abs(vel[0]).max() <= A_MAX * dt and np.abs(vel[-1]).max() <= A_MAX * dt
    # Every waypoint is hit exactly (the arm stops at the corners).
    for w in path:
        assert np.min(np.abs(q - w).max(axis=1)) < 1e-9


def test_time_parametrization_per_joint_limits():
    path = np.array([[0.0, 0.0], [1.0, 0.2], [1.0, 2.0]])
    v, a, dt = np.array([0.5, 2.0]), np.array([1.0, 8.0]), 0.01
    t, q = time_parametrize(path, v, a, dt)
    vel, acc = np.diff(q, axis=0) / dt, np.diff(q, 2, axis=0) / dt ** 2
    assert np.all(np.abs(vel).max(axis=0) <= v * 1.05)
    assert np.all(np.abs(acc).max(axis=0) <= a * 1.05)
    # The first stretch is limited by joint 0: it reaches its speed limit, the other joint stays well below.
    assert np.abs(vel[:, 0]).max() >= 0.95 * v[0]
    t0, q0 = time_parametrize(path[:1])
    assert len(t0) == 1 and np.allclose(q0[0], path[0])


def test_both_arms_plan(world):
    kin, cw = world.kin, world.cw
    mirror = np.array([1, -1, -1, 1, -1, 1, -1])
    q_start = np.concatenate([np.array(INIT_ARM_QPOS["left"]), world.q_start])
    q_goal = np.concatenate([world.q_goal * mirror, world.q_goal])  # left mirrors right's move; no wall there
    assert is_valid(kin, cw, "all", q_start) and is_valid(kin, cw, "all", q_goal)
    res = plan_rrt_connect(kin, cw, "all", q_start, q_goal, time_limit=10.0, seed=3)
    assert res.ok, res.reason
    assert res.path.shape[1] == 14
    for q in dense(res.path, CHECK_STEP * 2):
        assert is_valid(kin, cw, "all", q)
        assert world.wall_contacts({"left": q[:7], "right": q[7:]}) == 0
    print(f"both arms: {res.planning_time:.3f} s, {len(res.path)} waypoints")


def test_both_arms_sees_arm_against_arm(world):
    """In "all" mode the two hands are obstacles to each other: bring the left hand onto the right one."""
    kin, cw, model = world.kin, world.cw, world.model
    kin.sync(world.env.data.qpos)
    right_hand = kin.ee_pose("right")[0]
    ik = solve_arm_ik_restarts(model, kin.data, "left", np.array(HAND_BASE_ON_WRIST_POS), right_hand,
                               seeds=[np.array(INIT_ARM_QPOS["left"])])
    q = np.concatenate([ik.qpos, world.q_start])
    assert ik.position_error < 0.03
    assert not is_valid(kin, cw, "all", q)
    kin.sync(world.env.data.qpos)
