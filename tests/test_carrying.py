"""Carrying and setting down what others' plans ask for.

- A drawer has a "head" (the paper's articulated_object_head: its front at the handle's height); 'move' relative
  to a drawer measures `relative_p` from it, as the paper's planner does, with the drawer's centre as the
  alternative (plans that took "relative to the drawer" to mean its centre).
- A pinch far from the object's centre of mass (the free end of a block held level) squeezes top and bottom first.
- A cube set down beside another is turned to line up with it and put just clear of it (`move_action.beside`).
- A sampled path keeps a carried object near the shortest turn between its start and goal orientations
  (`motion.carried_turn_check`, through `paths.plan_rrt_connect(state_ok=...)`).
"""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from humanoidgen.planning import skills
from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.planning import constraint_gen
from humanoidgen.planning.motion import CARRY_TURN_SLACK, carried_turn_check
from humanoidgen.planning.paths import plan_rrt_connect
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


@pytest.fixture(scope="module")
def storage():
    _, env = build_scene(load_task("handover_and_storage"), 0)
    return env, task_planner(env, seed=0)


def test_the_drawer_head_is_its_front_at_the_handle(storage):
    env, _ = storage
    head = get_point_in_env(env, "head", "drawer", 0)
    np.testing.assert_allclose(get_point_in_env(env, "articulated_object_head", "drawer", 0), head)
    handle = get_point_in_env(env, "handle", "drawer", 0)
    centre = get_point_in_env(env, "center", "drawer", 0)
    assert head[2] == pytest.approx(handle[2])  # at the handle's height
    assert handle[0] < head[0] < centre[0]  # on the front, between the handle bar and the middle
    # It rides with the drawer: open, the head comes out by the drawer's travel.
    opened = get_point_in_env(env, "head", "drawer", 0, openness=1.0)
    assert opened[0] < head[0] - 0.1


def test_move_relative_to_a_drawer_measures_from_its_head_then_its_centre(storage):
    env, planner = storage
    offset = np.array([0.08, 0.0, 0.10])
    gen = skills.generate(env, planner.holding, "cube", 0, "move", "right", relative_obj_name="drawer",
                                  relative_obj_id=0, relative_p=offset)
    head = get_point_in_env(env, "head", "drawer", 0)
    centre = get_point_in_env(env, "center", "drawer", 0)
    np.testing.assert_allclose(gen.constraints[0].object_key_point, head + offset)
    assert "head" in gen.constraints[0].name
    from_centre = [g for g in gen.alternatives if np.allclose(g.constraints[0].object_key_point, centre + offset)]
    assert from_centre and any("centre" in n for n in from_centre[0].notes)
    # An object without a head is measured from its centre only.
    gen = skills.generate(env, planner.holding, "drawer", 0, "move", "left", relative_obj_name="cube",
                                  relative_obj_id=0, relative_p=offset)
    np.testing.assert_allclose(gen.constraints[0].object_key_point, get_point_in_env(env, "center", "cube", 0) + offset)
    assert not gen.alternatives


def _lay_block_level(env) -> None:
    """The 3x3x8 cm block in mid-air, its long (z) axis along -y: as one hand presents it to the other."""
    m, d = env.model, env.data
    body = m.body(env.scene.object("cube", 0).body)
    adr = m.jnt_qposadr[body.jntadr[0]]
    d.qpos[adr:adr + 3] = [-0.30, -0.05, 0.25]
    d.qpos[adr + 3:adr + 7] = [np.cos(np.pi / 4), np.sin(np.pi / 4), 0.0, 0.0]  # +90 deg about x: z -> -y
    mujoco.mj_forward(m, d)


def test_a_pinch_far_from_the_centre_of_mass_squeezes_top_and_bottom():
    _, env = build_scene(load_task("handover_and_storage"), 0)
    _lay_block_level(env)
    task_planner(env, seed=0)  # the planner's kinematics anchor the hand points
    end = get_point_in_env(env, "pinch_bottom", "cube", 0)
    assert constraint_gen._off_centre(env, "cube", 0, end) > constraint_gen.OFF_CENTRE_PINCH_M
    ways = constraint_gen._grip_variants(env, "left", "cube", 0, "pinch",
                                         env.scene.object("cube", 0).annotations.operations_of("pinch")[1], None)
    squeeze = [c for c in ways[0].constraints if c.name == "pinch along the attach axis"][0].object_axis
    assert abs(squeeze[2]) > 0.9
    assert any(abs(c.object_axis[2]) < 0.1 for w in ways[1:] for c in w.constraints
               if c.name == "pinch along the attach axis")  # the level squeeze is still there, later


def test_a_carried_object_keeps_near_its_shortest_turn(storage):
    env, planner = storage
    kin = planner.ctx.kin
    kin.sync(env.data.qpos)
    kin.attach("right", env.scene.object("cube", 0).body)
    try:
        q0 = kin.arm_q("right")
        q1 = q0.copy()
        arm = kin.arms["right"]
        turn = 0.4 if q0[-1] + 0.4 < arm.hi[-1] else -0.4  # the last wrist joint turns the object by 0.4 rad
        q1[-1] += turn
        check = carried_turn_check(kin, "right", q0, q1)
        assert check is not None
        away = q0.copy()
        away[-1] -= np.sign(turn) * (0.4 + 2 * CARRY_TURN_SLACK)  # the other way, beyond the slack
        for q, ok in ((q0, True), (q1, True), ((q0 + q1) / 2, True), (away, False)):
            kin.set_arm("right", q)
            kin.forward()
            assert check(kin) is ok
        # The sampling planner honours it: no state may be taken, so only the direct way could be (not tried here).
        res = plan_rrt_connect(kin, planner.ctx.collisions, "right", q0, q1, time_limit=0.5, try_direct=False,
                               state_ok=lambda k: False)
        assert not res.ok
        res = plan_rrt_connect(kin, planner.ctx.collisions, "right", q0, q1, time_limit=2.0, state_ok=check)
        assert res.ok
    finally:
        kin.detach("right")
        kin.sync(env.data.qpos)
    assert carried_turn_check(kin, "right", q0, q1) is None  # nothing carried: no condition


def test_a_cube_set_down_beside_another_lines_up_with_it_just_clear():
    from humanoidgen.planning import move_action

    _, env = build_scene(load_task("pyramid_stack"), 0)
    task_planner(env, seed=0)
    cube0, cube1 = env.scene.object("cube", 0), env.scene.object("cube", 1)
    gen = move_action.move(env, {"right": cube1, "left": None}, "cube", 1, "right", cube0, np.array([0.0, -0.04, 0.0]))
    first = gen.constraints
    assert "lined up with cube 0" in first[0].name and any("square to cube 0" in c.name for c in first)
    goal = first[0].object_key_point
    c0 = get_point_in_env(env, "center", "cube", 0)
    assert goal[1] < c0[1] - 0.04  # moved further from cube 0 (the cubes' yaws differ)
    # Along the plan's line where that costs at most LINE_NUDGE_M; here (cube 0 turned further from the line) it
    # would cost more (seed 0: cube 0 turned to the line): set against its nearest face, as close as the gap allows.
    on_line = abs(goal[0] - c0[0]) < 1e-6 and c0[1] - goal[1] - 0.04 <= move_action.LINE_NUDGE_M
    against = any("nearest face" in n for n in gen.notes) and 0.04 < np.linalg.norm(goal[:2] - c0[:2]) < 0.05
    assert on_line or against
    # Lined up: the turn makes cube 1's x axis parallel to one of cube 0's faces' axes (mod 90 deg).
    align = [c for c in first if "square to" in c.name][0]
    R0 = env.data.xmat[env.model.body(cube0.body).id].reshape(3, 3)
    cos = max(abs(float(align.object_axis @ R0[:, k])) for k in (0, 1))
    assert cos > np.cos(np.radians(1.0))
    assert any("turned" in n and "line up" in n for n in gen.notes)
    # Nothing beside: the plain set-down ways, no lining up.
    far = move_action.move(env, {"right": cube1, "left": None}, "cube", 1, "right", cube0, np.array([0.0, -0.15, 0.0]))
    assert not any("lined up" in c.name for g in [far, *far.alternatives] for c in g.constraints)
