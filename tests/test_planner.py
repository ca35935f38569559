"""The planner API end to end: scripts written against it pick, place, pull and move both arms."""

import mujoco
import numpy as np
import pytest

from humanoidgen.planning import approach
from humanoidgen.objects.library import add_object
from humanoidgen.objects.describe import openness
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.planner import PlanningError
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.scene import SceneBuilder

from plan_runs import task_planner  # noqa: E402


def pick_and_place(planner):
    """Right hand pinches cube 0 and puts it on cube 1 (as an LLM would write it)."""
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="cube", obj_id=0)
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="target", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="move", hand_name="right",
                                     relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0, 0, 0.045]))
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
    planner.open_hand("right")


def cube_on_cube(env) -> bool:
    top, bottom = env.object_pose("cube_0")[0], env.object_pose("cube_1")[0]
    return np.linalg.norm(top[:2] - bottom[:2]) < 0.02 and abs(top[2] - bottom[2] - 0.04) < 0.006


def test_pick_and_place_succeeds_on_randomized_placements():
    rng = np.random.default_rng(0)
    successes, failures = 0, []
    for trial in range(10):
        b = SceneBuilder()
        add_object(b, "cube", 0, pos=(rng.uniform(-0.37, -0.31), rng.uniform(-0.24, -0.14)))
        add_object(b, "cube", 1, pos=(rng.uniform(-0.33, -0.29), rng.uniform(-0.06, 0.0)))
        env = HumanoidEnv(b.build())
        planner = task_planner(env, seed=trial)
        try:
            pick_and_place(planner)
            ok = cube_on_cube(env)
        except PlanningError as exc:
            ok, failures = False, failures + [str(exc)]
        successes += ok
        if ok:
            assert "released cube 0 and it stayed on cube 1" in planner.events
    assert successes >= 9, failures


@pytest.fixture(scope="module")
def two_cubes():
    b = SceneBuilder()
    add_object(b, "cube", 0, pos=(-0.34, -0.18))
    add_object(b, "cube", 1, pos=(-0.30, -0.02))
    return b.build()


def test_held_cube_keeps_its_pose_in_the_hand_and_is_placed_by_its_centre(two_cubes):
    env = HumanoidEnv(two_cubes)
    planner = task_planner(env)
    planner.hand_pre_pinch("right")
    _, pose = planner.generate_end_effector_pose(
        planner.generate_constraints("cube", 0, "pinch", "right"), "right")
    planner.move_to_pose_with_screw(pose, "right")
    planner.hand_pinch("right", "cube", 0)
    p_hand, R_hand = env.hand_pose("right")
    rel0 = R_hand.T @ (env.object_pose("cube_0")[0] - p_hand)
    # Place by a point2point constraint on the cube's own centre.
    target = np.array([-0.36, -0.10, 0.12])
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "center", "cube", 0), object_key_point=target)]
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
    p_hand, R_hand = env.hand_pose("right")
    rel1 = R_hand.T @ (env.object_pose("cube_0")[0] - p_hand)
    assert np.linalg.norm(rel1 - rel0) < 0.005
    assert np.linalg.norm(env.object_pose("cube_0")[0] - target) < 0.015


def test_pulling_the_drawer_to_openness_one():
    b = SceneBuilder()
    add_object(b, "drawer", 0, pos=(-0.18, 0.20))
    env = HumanoidEnv(b.build())
    planner = task_planner(env)
    drawer = env.scene.object("drawer", 0)
    planner.hand_pre_grasp("left")
    _, pose = planner.generate_end_effector_pose(planner.generate_constraints("drawer", 0, "grasp", "left"), "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
    c = planner.generate_constraints("drawer", 0, "grasp", "left", openness=1)
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="drawer", object_id=0)
    assert openness(env.model, env.data, drawer) >= 0.95
    assert "grasped drawer 0 with the left hand" in planner.events


def _arm_arm_contacts(env) -> int:
    m, d = env.model, env.data
    def side_of(g):
        name = m.body(m.geom_bodyid[g]).name
        return "left" if name.startswith(("left_", "L_")) else "right" if name.startswith(("right_", "R_")) else None
    return sum(1 for c in d.contact[: d.ncon] if {side_of(c.geom1), side_of(c.geom2)} == {"left", "right"})


def test_both_arms_move_at_once_without_touching(empty_scene):
    env = HumanoidEnv(empty_scene)
    contacts = []
    planner = task_planner(env, on_step=lambda a: contacts.append(_arm_arm_contacts(env)))
    poses = []
    for side, y in (("left", 0.15), ("right", -0.15)):
        c = [Constraint(planner.env, "point2point", f"{side[0]}_hand_base_link",
                        hand_key_point=get_point_in_env(planner.env, f"grasp_point_base_{side}_hand"),
                        object_key_point=[-0.36, y, 0.12]),
             Constraint(planner.env, "parallel", f"{side[0]}_hand_base_link",
                        hand_axis=get_axis_in_env(planner.env, f"{side}_grasp_axis"), object_axis=[0, 0, -1])]
        poses.append(planner.generate_end_effector_pose(c, side)[1])
    planner.move_to_pose_with_screw(poses, "all", attach_obj=[False, False])
    assert max(contacts) == 0
    for side, pose in zip(("left", "right"), poses):
        assert np.linalg.norm(env.hand_pose(side)[0] - pose.p) < 0.02


def test_blocked_straight_motion_is_replaced_by_a_sampled_path():
    b = SceneBuilder()
    _, wall = b.add_object_body("wall", np.array([-0.38, -0.34, 0.15]), free=False)
    wall.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.18, 0.01, 0.15], rgba=[0.5, 0.5, 0.9, 1])
    env = HumanoidEnv(b.build())
    wall_id = env.model.body("wall_0").id
    touched = []

    def watch(_):
        m, d = env.model, env.data
        touched.append(any(wall_id in (m.geom_bodyid[c.geom1], m.geom_bodyid[c.geom2]) for c in d.contact[: d.ncon]))

    planner = task_planner(env, on_step=watch)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "grasp_point_base_right_hand"),
                    object_key_point=[-0.40, -0.45, 0.20])]
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    assert not any(touched)
    assert np.linalg.norm(env.hand_pose("right")[0] - pose.p) < 0.02


def test_failures_are_reported_as_data(two_cubes):
    env = HumanoidEnv(two_cubes)
    planner = task_planner(env)
    c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                    hand_key_point=get_point_in_env(planner.env, "grasp_point_base_right_hand"),
                    object_key_point=[0.4, -0.2, 0.1], name="reach far")]
    with pytest.raises(PlanningError) as exc:
        planner.generate_end_effector_pose(c, "right")
    assert exc.value.call == "generate_end_effector_pose" and "reach far" in exc.value.reason
    with pytest.raises(PlanningError, match="unknown action 'juggle'"):
        planner.generate_constraints("cube", 0, "juggle", "right")
    with pytest.raises(PlanningError, match=r"no object cube\[7\]"):
        planner.generate_constraints("cube", 7, "grasp", "right")
    with pytest.raises(PlanningError, match="does not hold cube 0"):
        planner.hand_grasp("right", "cube", 0)  # nothing in the hand
    assert [r.ok for r in planner.log] == [False, False, False, False]
    assert planner.log[-1].call == "hand_grasp"


def test_collision_ignore_list(two_cubes):
    env = HumanoidEnv(two_cubes)
    planner = task_planner(env)
    cube = env.model.body("cube_1").id
    planner.ignore_collision("cube", 1)
    assert cube in planner.ctx.collisions.ignored_bodies
    planner.restore_collision("cube", 1)
    assert cube not in planner.ctx.collisions.ignored_bodies


def test_path_constraints_hold_along_the_motion(empty_scene):
    env = HumanoidEnv(empty_scene)
    palm_angles = []
    planner = task_planner(env)

    def palm_down():
        return Constraint(planner.env, "parallel", "r_hand_base_link",
                          hand_axis=get_axis_in_env(planner.env, "right_grasp_axis"), object_axis=[0, 0, -1])

    def to(point):
        c = [Constraint(planner.env, "point2point", "r_hand_base_link",
                        hand_key_point=get_point_in_env(planner.env, "grasp_point_base_right_hand"),
                        object_key_point=point), palm_down()]
        return planner.generate_end_effector_pose(c, "right")[1]

    planner.move_to_pose_with_screw(to([-0.40, -0.25, 0.15]), "right")
    planner.on_step = lambda a: palm_angles.append(
        np.degrees(np.arccos(np.clip(-get_axis_in_env(env, "right_grasp_axis")[2], -1, 1))))
    planner.move_to_pose_with_screw(to([-0.32, -0.10, 0.10]), "right", path_constraints=[palm_down()])
    assert len(palm_angles) > 10
    assert max(palm_angles) < 4.0  # planned within 0.5 deg; the simulated arm lags a little


def test_snapshot_restores_the_episode_exactly(two_cubes):
    from humanoidgen.planning.snapshot import Snapshot, restore_snapshot, take_snapshot

    env = HumanoidEnv(two_cubes)
    planner = task_planner(env)
    planner.hand_pre_pinch("right")
    _, pose = planner.generate_end_effector_pose(planner.generate_constraints("cube", 0, "pinch", "right"), "right")
    planner.move_to_pose_with_screw(pose, "right")
    planner.hand_pinch("right", "cube", 0)
    snap = Snapshot.from_dict(take_snapshot(planner.ctx).to_dict())  # through JSON-ready data, as the tree log stores it
    q_at_snap, cube_at_snap = env.data.qpos.copy(), env.object_pose("cube_0")[0]
    # Carry on: lift the cube, then go back to the snapshot.
    _, pose = planner.generate_end_effector_pose(planner.generate_constraints("cube", 0, "target", "right"), "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
    assert np.linalg.norm(env.object_pose("cube_0")[0] - cube_at_snap) > 0.05
    restore_snapshot(planner.ctx, snap)
    assert np.allclose(env.data.qpos, q_at_snap, atol=1e-6)
    assert planner.holding["right"].body == "cube_0"
    # And the restored episode continues like the original did.
    _, pose = planner.generate_end_effector_pose(planner.generate_constraints("cube", 0, "target", "right"), "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
    assert env.object_pose("cube_0")[0][2] > 0.1


def test_a_trial_records_nothing_and_leaves_the_planner_where_it_was_even_when_it_fails(cube_scene):
    from humanoidgen.planning.snapshot import trial

    env = HumanoidEnv(cube_scene)
    recorded = []
    planner = task_planner(env, on_step=recorded.append)
    planner.ctx.settle(0.2)
    hook, qpos, events = planner.on_step, env.data.qpos.copy(), list(planner.events)
    with pytest.raises(RuntimeError), trial(planner.ctx):
        planner.hand_pre_pinch("right")
        planner.events.append("tried")
        raise RuntimeError("the way out failed")
    assert np.array_equal(env.data.qpos, qpos) and planner.events == events
    assert planner.on_step is hook and len(recorded) == round(0.2 * env.control_hz)  # only the settle before


def test_grip_alternatives_and_choosing_an_annotated_point(two_cubes):
    env = HumanoidEnv(two_cubes)
    planner = task_planner(env)
    c = planner.generate_constraints("cube", 0, "grasp", "right")
    # The most natural grip comes first; the other ways to take it wait as alternatives.
    assert c[0].meta.alternatives and all(alt.constraints for alt in c[0].meta.alternatives)
    c = planner.generate_constraints("cube", 0, "pinch", "right", point="pinch")
    assert "pinch" in c[0].name
    with pytest.raises(PlanningError, match="no 'pinch' annotation at point 'rim'; points: pinch"):
        planner.generate_constraints("cube", 0, "pinch", "right", point="rim")


def test_finger_offset_moves_the_grip_point_along_the_fingers(two_cubes):
    env = HumanoidEnv(two_cubes)
    planner = task_planner(env)
    fingers = get_axis_in_env(env, "right_grasp_wrist_2_palm_axis")
    base = planner.generate_constraints("cube", 0, "pinch", "right")[0]
    out = planner.generate_constraints("cube", 0, "pinch", "right", finger_offset=0.02)[0]
    # The same object point; the hand point sits 2 cm further out along the fingers.
    assert np.allclose(base.object_key_point, out.object_key_point)
    shift = out.hand_key_point - base.hand_key_point
    assert np.allclose(shift, 0.02 * fingers, atol=1e-9)


def test_pushing_a_part_to_an_openness_rides_with_the_part():
    b = SceneBuilder()
    add_object(b, "drawer", 0, pos=(-0.08, 0.17))
    env = HumanoidEnv(b.build())
    planner = task_planner(env)
    reach = planner.generate_constraints("drawer", 0, "target1", "left")[0].meta
    push = planner.generate_constraints("drawer", 0, "target1", "left", openness=0)[0].meta
    assert reach.follow is None and reach.approach_axis is not None  # come in straight to the front
    assert push.follow is not None and push.follow.q_target == 0.0 and push.approach_axis is None
    # The fingertip may lean off the push direction (a cone), preferring to be along it.
    kinds = [(type(c).__name__, c.type) for c in push.constraints]
    assert ("Constraint", "angle") in kinds and ("Const", "parallel") in kinds


def test_a_wrap_approach_that_would_push_the_body_over_is_refused():
    b = SceneBuilder()
    add_object(b, "bottle", 1, pos=(-0.34, -0.20))
    env = HumanoidEnv(b.build())
    planner = task_planner(env)
    planner.hand_pre_grasp("right")
    for offset, fits in [(0.0, True), (-0.035, False)]:  # 3.5 cm deeper: the opposed thumb goes through the bottle
        c = planner.generate_constraints("bottle", 0, "grasp", "right", point="side_right", finger_offset=offset)
        gen = c[0].meta
        bottle = env.model.body("bottle_0").id
        planner.ctx.collisions.ignored_bodies.add(bottle)  # the hand is meant to touch what it grasps
        result = planner.ctx.solver.solve("right", list(gen.constraints), planner.ctx.kin.arm_q("right"), planner.ctx.nominal["right"])
        planner.ctx.collisions.ignored_bodies.discard(bottle)
        assert result.success and gen.posture == "wrap"
        assert approach.approach_fits(planner.ctx, "right", result, gen) is fits
