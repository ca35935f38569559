"""A cube set down beside another that stands turned 40-50 deg to the plan's line (issue 36, the G1's pyramid).

The two cubes' world boxes then overlap corner to corner at the distance the plan asks (4.3 cm), though the held
cube's centre is off the other's footprint: it could not rest on it. It is a neighbour the cube is lined up with
and set down against (`move_action._neighbour`), face to face where keeping the plan's line would put the two
more than `LINE_NUDGE_M` further apart than asked. Before, the goal was raised onto the neighbour's corner and the
cube slid off: a pyramid's bases 5.8-7.0 cm apart where 4.0-5.5 cm are wanted (G1, seeds 1000, 1002, 1003, 1007).
"""

from __future__ import annotations

import mujoco
import numpy as np

from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.planning import move_action, placing
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


def _turn(env, obj, yaw_deg: float, tilt_deg: float = 0.0) -> None:
    """Turn the object at its place `yaw_deg` about the vertical, then tilt it `tilt_deg` about its own x."""
    adr = env.model.jnt_qposadr[env.model.body(obj.body).jntadr[0]]
    yaw, tilt = np.zeros(4), np.zeros(4)
    mujoco.mju_axisAngle2Quat(yaw, [0.0, 0.0, 1.0], np.radians(yaw_deg))
    mujoco.mju_axisAngle2Quat(tilt, [1.0, 0.0, 0.0], np.radians(tilt_deg))
    q = np.zeros(4)
    mujoco.mju_mulQuat(q, yaw, tilt)
    env.data.qpos[adr + 3:adr + 7] = q
    mujoco.mj_forward(env.model, env.data)


def test_a_cube_beside_a_turned_one_is_set_against_its_face_not_on_its_corner():
    _, env = build_scene(load_task("pyramid_stack"), 0)
    task_planner(env, seed=0)
    cube0, cube1 = env.scene.object("cube", 0), env.scene.object("cube", 1)
    _turn(env, cube0, 41.0)
    _turn(env, cube1, -49.0, 9.0)  # lined up with cube 0 (mod 90 deg), 9 deg off upright: the G1's seed 1000
    c0 = get_point_in_env(env, "center", "cube", 0)
    gen = move_action.move(env, {"right": cube1, "left": None}, "cube", 1, "right", cube0,
                           np.array([0.0, -0.043, 0.03]))
    first = gen.constraints
    assert "lined up with cube 0" in first[0].name
    goal = first[0].object_key_point
    R1 = placing.object_pose(env, cube1)[1]
    # Let go just above the table, not raised onto cube 0's corner.
    assert placing.support_below(env, cube1, goal, R1, centred=True)[1] == "the table"
    assert goal[2] < c0[2] + 0.02
    # Against cube 0's face: centres as far apart as two cubes and the gap, well inside the 4.0-5.5 cm wanted.
    d = float(np.linalg.norm(goal[:2] - c0[:2]))
    assert 0.04 < d < 0.05
    assert goal[1] < c0[1]  # still on the side the plan asked (to the right of cube 0)
    assert any("nearest face" in n for n in gen.notes)


def test_a_cube_set_on_another_is_still_stacked():
    """The neighbour rule leaves stacks alone: a cube whose centre is over the other rests on it."""
    _, env = build_scene(load_task("pyramid_stack"), 0)
    task_planner(env, seed=0)
    cube0, cube1 = env.scene.object("cube", 0), env.scene.object("cube", 1)
    _turn(env, cube0, 41.0)
    _turn(env, cube1, -49.0, 9.0)
    gen = move_action.move(env, {"right": cube1, "left": None}, "cube", 1, "right", cube0,
                           np.array([0.005, -0.005, 0.045]))
    assert not any("lined up" in c.name for g in [gen, *gen.alternatives] for c in g.constraints)
    assert gen.constraints[0].object_key_point[2] > get_point_in_env(env, "center", "cube", 0)[2] + 0.04
