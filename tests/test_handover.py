"""Hand-overs in mid-air and setting held objects down.

- A long block (3x3x8 cm) has a pinch at each end; a block the other hand holds is taken at the end farthest from
  that hand's grip, a block standing on the table never from below.
- A task target may turn the held object (`up`: where its own z axis points); the spec checks the direction.
- "move" sets a held object down just above what is under it (the release clearance), stands a tilted block back
  on an end, sets one tilted a little in the grip down level, and offers a cube's quarter-turned hand and a higher
  release as its alternatives.
- A hand that turned what it holds backs out of its grip along the turned approach when it lets go.
- One episode: the right hand presents the block in mid-air, the left takes it by the free end, the right lets go,
  the left stands it on the target cube.
"""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from pydantic import ValidationError

from humanoidgen.planning import execute
from humanoidgen.objects import library
from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.planning import constraint_gen, move_action, placing
from humanoidgen.tasks.predicates import Upright
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene
from humanoidgen.tasks.targets import TargetSpec
from plan_runs import run_plan, task_planner


@pytest.fixture(scope="module")
def handover_env():
    _, env = build_scene(load_task("block_handover"), 0)
    return env


def test_a_long_block_has_a_pinch_and_a_rest_at_each_end():
    block = library.annotations("cube", 4)
    pinches = {o.point: o.approach_axis for o in block.operations_of("pinch")}
    assert pinches == {"pinch": "down", "pinch_bottom": "z"}
    z = {p.name: p.position[2] for p in block.points}
    assert z["pinch"] > 0.02 and z["pinch_bottom"] < -0.02  # one near each end
    assert {(f.point, f.axis) for f in block.functions if f.function == "rest"} == {("base", "down"), ("support", "z")}
    cube = library.annotations("cube", 0)  # a cube is not a block: one pinch, no rest faces
    assert [o.point for o in cube.operations_of("pinch")] == ["pinch"]
    assert not [f for f in cube.functions if f.function == "rest"]


def test_the_pinch_of_a_held_block_takes_the_free_end(handover_env):
    env = handover_env
    # Standing on the table, the top comes first: the bottom end would be taken from below, through the table.
    ranked = constraint_gen._rank_operations(env, "right", "cube", 0, "pinch", None)
    assert ranked[0].point == "pinch"
    # Held by the other hand at its top: the far end comes first.
    top = get_point_in_env(env, "pinch", "cube", 0)
    ranked = constraint_gen._rank_operations(env, "left", "cube", 0, "pinch", None, other_grip=[top])
    assert ranked[0].point == "pinch_bottom"
    # And the same through the action, with the other hand's grip read from the holding dict.
    gen = constraint_gen.grasp_or_pinch(env, "left", "cube", 0, "pinch", None, holding={"right": None, "left": None})
    assert gen.constraints[0].name.endswith("cube 0 pinch")
    held = {"right": env.scene.object("cube", 0), "left": None}
    assert constraint_gen.other_hand_grip(env, held, "left", "cube", 0) is not None
    assert constraint_gen.other_hand_grip(env, held, "right", "cube", 0) is None  # its own grip is not "the other"


def test_a_target_may_turn_the_held_object():
    spec = TargetSpec.model_validate({"object": "cube[0]", "hand": "right", "pos": [-0.32, 0.0, 0.15], "up": [0, -2, 0]})
    assert spec.up == (0.0, -1.0, 0.0)
    assert "z axis turned to [0.0, -1.0, 0.0]" in spec.label()
    for bad in ([0, 0, 0], [1, 2], [float("nan"), 0, 1], "down"):
        with pytest.raises(ValidationError):
            TargetSpec.model_validate({"object": "cube[0]", "pos": [-0.32, 0.0, 0.15], "up": bad})
    targets = {(t.name, t.hand): t for t in load_task("block_handover").targets}
    assert targets[("target", "right")].up == (0.0, -1.0, 0.0) and targets[("target", "right")].pos[2] > 0.1


def test_release_lift_and_neighbours(handover_env):
    env = handover_env
    block = env.scene.object("cube", 0)
    R = np.eye(3)
    # At table height the goal is raised so that the block ends RELEASE_CLEARANCE_M above the table.
    goal, note = placing.release_lift(env, block, np.array([-0.30, 0.0, 0.04]), R)
    assert goal[2] == pytest.approx(0.04 + placing.RELEASE_CLEARANCE_M, abs=1e-6) and "raised" in note
    # Above the target cube: its top is the support.
    cube = get_point_in_env(env, "center", "cube", 1)
    goal, note = placing.release_lift(env, block, cube + [0, 0, 0.06], R)
    assert goal[2] == pytest.approx(cube[2] + 0.06 + placing.RELEASE_CLEARANCE_M, abs=1e-3) and "cube 1" in note
    # A little above it (2 cm): lowered to the clearance, set down rather than dropped.
    goal, note = placing.release_lift(env, block, cube + [0, 0, 0.08], R)
    assert goal[2] == pytest.approx(cube[2] + 0.06 + placing.RELEASE_CLEARANCE_M, abs=1e-3) and "lowered" in note
    # Held well above it (4 cm, past DROP_LIMIT_M): where the plan wants it, unchanged, no note.
    goal, note = placing.release_lift(env, block, cube + [0, 0, 0.10], R)
    assert note is None and goal[2] == pytest.approx(cube[2] + 0.10)
    # Beside the target cube, touching it: that cube is a neighbour, not a support.
    support, what = placing.support_below(env, block, cube + [0, -0.035, 0.04], R)
    assert what == "the table" and support == 0.0


def _turn_block(env, quat) -> None:
    bid = env.model.body("cube_0").id
    adr = env.model.jnt_qposadr[env.model.body_jntadr[bid]]
    env.data.qpos[adr + 3: adr + 7] = quat
    mujoco.mj_forward(env.model, env.data)


def test_a_tilted_block_is_stood_back_on_an_end(handover_env):
    env = handover_env
    block = env.scene.object("cube", 0)
    saved = env.data.qpos.copy()
    try:
        assert placing.stand_up_directions(env, "left", block, None) is None  # upright already
        assert Upright(obj="cube[0]", max_tilt_deg=20).evaluate(env).ok
        _turn_block(env, [np.cos(np.pi / 4), np.sin(np.pi / 4), 0.0, 0.0])  # laid on its side
        dirs = placing.stand_up_directions(env, "left", block, None)
        assert dirs is not None and {tuple(d) for d in dirs} == {(0.0, 0.0, 1.0), (0.0, 0.0, -1.0)}  # either end
        drawer = type("Container", (), {"annotations": library.annotations("drawer", 0)})()
        assert placing.stand_up_directions(env, "left", block, drawer) is None  # into a container as it is
        _turn_block(env, [0.0, 1.0, 0.0, 0.0])  # upside down
        assert not Upright(obj="cube[0]", max_tilt_deg=20).evaluate(env).ok
        assert Upright(obj="cube[0]", max_tilt_deg=20, either_end=True).evaluate(env).ok
    finally:
        env.data.qpos[:] = saved
        mujoco.mj_forward(env.model, env.data)


def test_a_block_tilted_a_little_is_set_down_level(handover_env):
    """Held 10 deg off upright (it swung in the grip), a slender block is set down with its z axis vertical where
    the hand can turn so; the ways as it is held follow. Not for a level one, nor one to be stood up, nor into a
    container, nor a cube."""
    env = handover_env
    block, cube = env.scene.object("cube", 0), env.scene.object("cube", 1)
    saved = env.data.qpos.copy()

    def tilt(deg: float) -> None:
        half = np.radians(deg) / 2
        _turn_block(env, [np.cos(half), np.sin(half), 0.0, 0.0])

    try:
        for deg, want in ((1.0, None), (10.0, (0.0, 0.0, 1.0)), (45.0, None)):
            tilt(deg)
            got = placing.level_direction(env, block, cube)
            assert (got is None if want is None else tuple(got) == want), deg
        tilt(10.0)
        drawer = type("Container", (), {"annotations": library.annotations("drawer", 0)})()
        assert placing.level_direction(env, block, drawer) is None  # into a container as it is
        assert placing.level_direction(env, cube, block) is None  # a cube is not slender: it lands on a face
        gen = move_action.move(env, {"left": block, "right": None}, "cube", 0, "left", cube, np.array([0, 0, 0.062]))
        ways = [gen, *gen.alternatives]
        levelled = [any(c.name == "cube 0 set down level" for c in g.constraints) for g in ways]
        # each set-down way levelled first, then as held: the asked height before a higher release
        assert levelled == [True, False] * (len(ways) // 2) and len(ways) >= 4
        assert any("turns it level" in n for n in gen.notes)
    finally:
        env.data.qpos[:] = saved
        mujoco.mj_forward(env.model, env.data)


def test_the_move_sets_a_cube_down_with_alternatives(handover_env):
    env = handover_env
    cube = env.scene.object("cube", 1)
    gen = move_action.move(env, {"left": cube, "right": None}, "cube", 1, "left", env.scene.object("cube", 0),
                           np.array([0.0, 0.05, -0.02]))  # on the table beside the block
    names = [c.name for g in [gen, *gen.alternatives] for c in g.constraints]
    assert any("raised" in n for n in gen.notes)  # the release clearance
    assert any("turned +90 deg" in n for n in names) and any("turned -90 deg" in n for n in names)
    higher = [g for g in gen.alternatives if any("let go" in n and "higher" in n for n in g.notes)]
    assert len(higher) == len(placing.RAISED_RELEASE_M)


def test_the_way_out_of_a_grip_turns_with_the_hand(handover_env):
    # A hand that turned the block on its side (a hand-over) lets go along its turned approach, not straight up:
    # backing out upward, its thumb under the block would lift it out of the other hand.
    from humanoidgen.planning.poses import Pose
    from humanoidgen.sim.geometry import axis_angle_mat

    planner = task_planner(handover_env)
    now = planner.ctx.current_pose("right")
    planner.ctx.hands["right"].last_approach = placing.DOWN
    turn = axis_angle_mat(np.array([1.0, 0.0, 0.0]), np.pi / 2)  # a quarter turn about x: down becomes +y
    target = Pose.from_mat(now.p, turn @ now.R, side="right")
    assert np.allclose(execute.turned_approach(planner.ctx, "right", target), [0.0, 1.0, 0.0], atol=1e-6)
    planner.ctx.hands["right"].last_approach = None
    assert execute.turned_approach(planner.ctx, "right", target) is None


MID_AIR_HANDOVER = '''def step(planner):
    # Step 1: the right hand pinches the block and presents it at the hand-over pose
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="rectangular_cube", obj_id=0)
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="target", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="rectangular_cube", object_id=0)
    # Step 2: the left hand takes it while the right still holds it; then the right lets go
    planner.hand_pre_pinch("left")
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="pinch", hand_name="left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=False)
    planner.hand_pinch("left", pinch_object="rectangular_cube", obj_id=0)
    planner.open_hand("right")
    # Step 3: the left hand sets it on the target cube
    c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="move", hand_name="left",
                                     relative_obj_name="target_cube", relative_obj_id=0, relative_p=np.array([0, 0, 0.08]))
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="rectangular_cube", object_id=0)
    planner.open_hand("left")
'''


def test_a_mid_air_handover_episode(tmp_path):
    result = run_plan(tmp_path, "block_handover", 0, MID_AIR_HANDOVER)
    events = " | ".join(e for s in result.steps for e in s.events)
    assert all(s.ok for s in result.steps), [s.error for s in result.steps]
    assert "pinched rectangular_cube 0 with the left hand" in events
    assert "stands it on an end" in events
    assert result.success, result.checks
