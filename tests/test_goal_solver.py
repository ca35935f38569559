"""The goal-pose solver (planning/goal_solver.py) with the relational constraints of planning/constraints.py.

Every success is checked with an independent forward kinematics: the returned joints go into a fresh MjData,
and the hand point / axis are read off the wrist-yaw frame with the hand annotations (objects/hands.py),
not from the solver's own numbers.
"""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from humanoidgen.objects.library import add_object
from humanoidgen.objects.hands import hand_axes, hand_points
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.constraints import Const, Constraint, ConstraintError
from humanoidgen.planning.goal_solver import GoalSolver
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.layout import ARM_JOINTS, HAND_BASE_ON_WRIST_POS, WRIST_BODY
from humanoidgen.sim.scene import SceneBuilder

EE = "r_hand_base_link"
GRASP = "grasp_point_base_right_hand"
PALM = "palm_center_right_hand"
GRASP_AXIS = "right_grasp_axis"
FINGERS_AXIS = "right_grasp_wrist_2_palm_axis"
DOWN = np.array([0.0, 0.0, -1.0])


class Setup:
    def __init__(self, builder: SceneBuilder) -> None:
        self.scene = builder.build()
        self.model = self.scene.model
        self.env = HumanoidEnv(self.scene)
        self.kin = Kinematics(self.model)
        self.kin.sync(self.env.data.qpos)
        self.cw = CollisionWorld(self.kin)
        self.solver = GoalSolver(self.kin, self.cw)
        self.q0 = self.env.arm_qpos("right")

    def solve(self, constraints, **kw):
        return self.solver.solve("right", constraints, self.q0, self.q0, **kw)

    def fk(self, q: np.ndarray, side: str = "right") -> tuple[np.ndarray, np.ndarray]:
        """Wrist-yaw frame at arm joints `q`, from a fresh MjData (everything else as in the simulation now)."""
        d = mujoco.MjData(self.model)
        d.qpos[:] = self.env.data.qpos
        for name, v in zip(ARM_JOINTS[side], q):
            d.qpos[self.model.jnt_qposadr[self.model.joint(name).id]] = v
        mujoco.mj_kinematics(self.model, d)
        b = self.model.body(WRIST_BODY[side]).id
        return d.xpos[b].copy(), d.xmat[b].reshape(3, 3).copy()

    def hand_point(self, q: np.ndarray, name: str) -> np.ndarray:
        p, R = self.fk(q)
        return p + R @ hand_points("right")[name]

    def hand_axis(self, q: np.ndarray, name: str) -> np.ndarray:
        return self.fk(q)[1] @ hand_axes("right")[name]

    # constraint shorthands (hand elements read off the simulation now, as the planner API does)
    def p2p(self, target, point=GRASP, cls=Constraint, **kw):
        return cls(self.env, "point2point", EE, hand_key_point=get_point_in_env(self.env, point),
                   object_key_point=target, **kw)

    def parallel(self, target=DOWN, axis=GRASP_AXIS, cls=Constraint, **kw):
        return cls(self.env, "parallel", EE, hand_axis=get_axis_in_env(self.env, axis), object_axis=target, **kw)


def angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1.0, 1.0))))


def line_distance(p: np.ndarray, origin: np.ndarray, direction: np.ndarray) -> float:
    u = direction / np.linalg.norm(direction)
    r = p - origin
    return float(np.linalg.norm(r - (r @ u) * u))


@pytest.fixture(scope="module")
def empty() -> Setup:
    return Setup(SceneBuilder())


@pytest.fixture(scope="module")
def air_cube() -> Setup:
    """A 4 cm cube hanging in the air above the right hand's range (the simulation is never stepped)."""
    b = SceneBuilder()
    add_object(b, "cube", 0, pos=(-0.33, -0.15, 0.15))
    return Setup(b)


# -- hard point2point + parallel ----------------------------------------------------------------------------
def test_point_and_palm_down_reached_to_2mm_1deg(empty: Setup):
    rng = np.random.default_rng(7)
    for _ in range(5):
        target = np.array([rng.uniform(-0.40, -0.28), rng.uniform(-0.30, -0.05), rng.uniform(0.08, 0.12)])
        r = empty.solve([empty.p2p(target), empty.parallel()])
        assert r.success, f"target {target}: {r.message()}"
        assert r.q is not None and r.q.shape == (7,)
        arm = empty.kin.arms["right"]
        assert np.all(r.q >= arm.lo - 1e-9) and np.all(r.q <= arm.hi + 1e-9)
        err = np.linalg.norm(empty.hand_point(r.q, GRASP) - target)
        ang = angle_deg(empty.hand_axis(r.q, GRASP_AXIS), DOWN)
        assert err < 2e-3, f"target {target}: grasp point {err * 1000:.2f} mm off"
        assert ang < 1.0, f"target {target}: palm {ang:.2f} deg from straight down"
        # the reported end-effector position is the hand base at the solution
        wp, wR = empty.fk(r.q)
        np.testing.assert_allclose(r.ee_pos, wp + wR @ np.asarray(HAND_BASE_ON_WRIST_POS), atol=1e-6)


def test_solver_leaves_scratch_state_and_env_alone(empty: Setup):
    qpos_kin, qpos_env = empty.kin.data.qpos.copy(), empty.env.data.qpos.copy()
    r = empty.solve([empty.p2p([-0.33, -0.15, 0.10]), empty.parallel()])
    assert r.success, r.message()
    np.testing.assert_array_equal(empty.kin.data.qpos, qpos_kin)
    np.testing.assert_array_equal(empty.env.data.qpos, qpos_env)


# -- soft constraints ------------------------------------------------------------------------------------
def test_soft_parallel_pulls_toward_its_target(empty: Setup):
    target = np.array([-0.34, -0.18, 0.10])
    alone = empty.solve([empty.p2p(target)])
    pulled = empty.solve([empty.p2p(target), empty.parallel(cls=Const, weight=5.0)])
    assert alone.success and pulled.success, (alone.message(), pulled.message())
    a_alone = angle_deg(empty.hand_axis(alone.q, GRASP_AXIS), DOWN)
    a_pulled = angle_deg(empty.hand_axis(pulled.q, GRASP_AXIS), DOWN)
    assert a_pulled < a_alone - 5.0, (a_alone, a_pulled)
    assert a_pulled < 10.0, a_pulled
    assert np.linalg.norm(empty.hand_point(pulled.q, GRASP) - target) < 2e-3


def test_soft_constraint_that_cannot_be_met_is_not_required(empty: Setup):
    target = np.array([-0.34, -0.18, 0.10])
    # Palm down (hard) makes the fingers horizontal; the soft wish for fingers pointing down cannot be met.
    r = empty.solve([empty.p2p(target), empty.parallel(),
                     empty.parallel(DOWN, axis=FINGERS_AXIS, cls=Const, weight=5.0)])
    assert r.success, r.message()
    assert np.linalg.norm(empty.hand_point(r.q, GRASP) - target) < 2e-3
    assert angle_deg(empty.hand_axis(r.q, GRASP_AXIS), DOWN) < 1.0
    assert angle_deg(empty.hand_axis(r.q, FINGERS_AXIS), DOWN) > 80.0


# -- the other relation types ------------------------------------------------------------------------------
def test_point2line(empty: Setup):
    origin, direction = np.array([-0.33, -0.15, 0.10]), np.array([1.0, 0.0, 0.0])
    c = Constraint(empty.env, "point2line", EE, hand_key_point=get_point_in_env(empty.env, GRASP),
                   object_key_point=origin, object_axis=direction)
    r = empty.solve([c, empty.parallel()])
    assert r.success, r.message()
    assert line_distance(empty.hand_point(r.q, GRASP), origin, direction) < 2e-3
    assert angle_deg(empty.hand_axis(r.q, GRASP_AXIS), DOWN) < 1.0


def test_point2line_distance_band(empty: Setup):
    origin, direction = np.array([-0.33, -0.15, 0.0]), np.array([0.0, 0.0, 1.0])
    c = Constraint(empty.env, "point2line", EE, hand_key_point=get_point_in_env(empty.env, GRASP),
                   object_key_point=origin, object_axis=direction, lower=0.04, upper=0.06)
    r = empty.solve([c, empty.parallel()])
    assert r.success, r.message()
    d = line_distance(empty.hand_point(r.q, GRASP), origin, direction)
    assert 0.04 - 2e-3 <= d <= 0.06 + 2e-3, d


def test_line2point(empty: Setup):
    obj = np.array([-0.33, -0.15, 0.0])
    line = Constraint(empty.env, "line2point", EE, hand_key_point=get_point_in_env(empty.env, GRASP),
                      hand_axis=get_axis_in_env(empty.env, GRASP_AXIS), object_key_point=obj)
    # ... with the grasp point 8-12 cm from the object point (point2point as a distance band)
    band = empty.p2p(obj, lower=0.08, upper=0.12)
    r = empty.solve([line, band])
    assert r.success, r.message()
    p, a = empty.hand_point(r.q, GRASP), empty.hand_axis(r.q, GRASP_AXIS)
    assert line_distance(obj, p, a) < 2e-3
    assert 0.08 - 2e-3 <= np.linalg.norm(p - obj) <= 0.12 + 2e-3


def test_angle(empty: Setup):
    lo, hi = np.radians(20.0), np.radians(30.0)
    c = Constraint(empty.env, "angle", EE, hand_axis=get_axis_in_env(empty.env, GRASP_AXIS), object_axis=DOWN,
                   lower=lo, upper=hi)
    target = np.array([-0.33, -0.15, 0.10])
    r = empty.solve([empty.p2p(target), c])
    assert r.success, r.message()
    ang = angle_deg(empty.hand_axis(r.q, GRASP_AXIS), DOWN)
    assert 20.0 - 1.0 <= ang <= 30.0 + 1.0, ang
    assert np.linalg.norm(empty.hand_point(r.q, GRASP) - target) < 2e-3


# -- failures are data ---------------------------------------------------------------------------------------
def test_unreachable_target_is_reported_not_raised(empty: Setup):
    r = empty.solve([empty.p2p([0.5, -0.2, 0.1]), empty.parallel()])
    assert not r.success
    assert r.q is None
    assert any(v.startswith("point2point: hand point is") and v.endswith("mm from its target") for v in r.violations), \
        r.violations
    assert "point2point: hand point is" in r.message()
    # the distance reported is roughly how far the target lies beyond reach (well over half a metre)
    mm = float(next(v for v in r.violations if v.startswith("point2point")).split("is ")[1].split(" mm")[0])
    assert mm > 300.0, r.violations


def test_constraint_name_appears_in_the_violation(empty: Setup):
    c = empty.p2p([0.5, -0.2, 0.1], name="reach the far mug")
    r = empty.solve([c])
    assert not r.success
    assert any(v.startswith("reach the far mug: hand point is") for v in r.violations), r.violations


def test_target_inside_an_object_needs_that_object_ignored(air_cube: Setup):
    s = air_cube
    centre = get_point_in_env(s.env, "center", "cube", 0)
    np.testing.assert_allclose(centre, [-0.33, -0.15, 0.15], atol=1e-9)  # still in the air: never stepped
    cons = [s.p2p(centre, point=PALM), s.parallel()]
    cube = s.model.body("cube_0").id
    s.cw.ignored_bodies.discard(cube)
    try:
        r = s.solve(cons)
        assert not r.success
        msg = r.message()
        assert "collision" in msg and "cube_0" in msg, msg
        assert "table" not in msg, msg
        # without collision checking the same request is fine
        assert s.solve(cons, avoid_collisions=False).success
        s.cw.ignored_bodies.add(cube)
        r = s.solve(cons)
        assert r.success, r.message()
        assert np.linalg.norm(s.hand_point(r.q, PALM) - centre) < 2e-3
        assert angle_deg(s.hand_axis(r.q, GRASP_AXIS), DOWN) < 1.0
    finally:
        s.cw.ignored_bodies.discard(cube)


def test_hand_clear_of_the_object_is_not_a_collision(air_cube: Setup):
    # Grasp point at the cube centre: the cube sits between the open fingers and the palm, not in the hand.
    s = air_cube
    s.cw.ignored_bodies.clear()
    r = s.solve([s.p2p(s.env.data.xpos[s.model.body("cube_0").id].copy() + [0, 0, 0.08]), s.parallel()])
    assert r.success, r.message()
    assert r.min_clearance is not None and r.min_clearance >= s.solver.clearance - 1e-3


# -- malformed constraints -------------------------------------------------------------------------------------
def test_malformed_constraints_raise(empty: Setup):
    env = empty.env
    p, a = get_point_in_env(env, GRASP), get_axis_in_env(env, GRASP_AXIS)
    with pytest.raises(ConstraintError, match="unknown constraint type 'point2plane'.*point2point"):
        Constraint(env, "point2plane", EE, hand_key_point=p, object_key_point=p)
    with pytest.raises(ConstraintError, match="unknown end_effector_frame 'r_wrist'.*r_hand_base_link"):
        Constraint(env, "point2point", "r_wrist", hand_key_point=p, object_key_point=p)
    with pytest.raises(ConstraintError, match="parallel needs hand_axis"):
        Constraint(env, "parallel", EE, object_axis=DOWN)
    with pytest.raises(ConstraintError, match="parallel needs object_axis"):
        Constraint(env, "parallel", EE, hand_axis=a)
    with pytest.raises(ConstraintError, match="object_axis must not be the zero vector"):
        Constraint(env, "parallel", EE, hand_axis=a, object_axis=[0, 0, 0])
    with pytest.raises(ConstraintError, match="hand_axis must not be the zero vector"):
        Const(env, "angle", EE, hand_axis=[0, 0, 0], object_axis=DOWN, upper=0.3)
    with pytest.raises(ConstraintError, match="point2point needs hand_key_point and object_key_point"):
        Constraint(env, "point2point", EE, hand_key_point=p)
    with pytest.raises(ConstraintError, match="object_key_point must be a 3-vector"):
        Constraint(env, "point2point", EE, hand_key_point=p, object_key_point=[0.1, 0.2])
    with pytest.raises(ConstraintError, match="lower .* must not exceed upper"):
        Constraint(env, "angle", EE, hand_axis=a, object_axis=DOWN, lower=0.5, upper=0.2)


def test_constraint_on_the_other_hand_is_refused(empty: Setup):
    left = Constraint(empty.env, "point2point", "l_hand_base_link",
                      hand_key_point=get_point_in_env(empty.env, "grasp_point_base_left_hand"),
                      object_key_point=[-0.33, 0.15, 0.10])
    with pytest.raises(ValueError, match="left hand, not the right hand"):
        empty.solve([left])
