"""Explicit constraints that pin a hand's grip point on an object are solved as that grip (planning/grip_intent.py):
the MCTS-style pinch of the paper's prompts ("pinch point on the cube's centre, pinch axis parallel to [0, 0, -1]")
picks the cube up, and what the plan did not ask for is only filled in where it left it free."""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.library import add_object
from humanoidgen.objects.hands import hand_axes
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning import grip_intent
from humanoidgen.planning.constraints import Constraint
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.scene import SceneBuilder

from plan_runs import task_planner  # noqa: E402


def _planner(pos=(-0.32, -0.15), yaw=0.0):
    b = SceneBuilder()
    add_object(b, "cube", 0, pos=pos, yaw=yaw)
    add_object(b, "cube", 1, pos=(-0.32, 0.2))
    env = HumanoidEnv(b.build())
    return env, task_planner(env)


def _pinch_from_above(env, side: str, obj_id: int = 0, dz: float = 0.0) -> list:
    frame = "r_hand_base_link" if side == "right" else "l_hand_base_link"
    return [Constraint(env=env, type="point2point", end_effector_frame=frame,
                       hand_key_point=get_point_in_env(env, point_name=f"pinch_point_base_{side}_hand"),
                       object_key_point=get_point_in_env(env, type_name="cube", obj_id=obj_id) + [0, 0, dz]),
            Constraint(env=env, type="parallel", end_effector_frame=frame,
                       hand_axis=get_axis_in_env(env, axis_name=f"{side}_pinch_axis"), object_axis=np.array([0, 0, -1]))]


def test_pinch_axis_down_means_a_pinch_from_above():
    # thumb-to-index square to the pinch axis: with the pinch axis down the squeeze is horizontal (not thumb under)
    for side in ("left", "right"):
        ax = hand_axes(side)
        assert abs(ax[f"{side}_pinch_axis"] @ ax[f"{side}_thumb_2_index"]) < 1e-9


def test_the_intent_is_read_only_from_plan_written_grip_constraints():
    env, planner = _planner()
    planner.hand_pre_pinch("right")
    intent = grip_intent.infer(env, "right", _pinch_from_above(env, "right"), planner.holding)
    assert intent is not None and (intent.obj.type_name, intent.obj.obj_id, intent.operation) == ("cube", 0, "pinch")
    assert intent.first.approach_object == intent.obj.body
    assert np.allclose(intent.first.approach_axis, [0, 0, -1])
    # the squeeze across the faces is added (4 ways), then the plan's own; then the same at the annotated height
    ways = [intent.first, *intent.first.alternatives]
    assert [len(w.constraints) for w in ways] == [3, 3, 3, 3, 2] * 2
    # a point in the air is no grip; generated constraints carry their own grip; a held hand grips nothing new
    air = _pinch_from_above(env, "right", dz=0.2)
    assert grip_intent.infer(env, "right", air, planner.holding) is None
    gen = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch", hand_name="right")
    assert grip_intent.infer(env, "right", gen, planner.holding) is None
    # a plan that sets the squeeze itself keeps it
    c = _pinch_from_above(env, "right") + [Constraint(
        env=env, type="parallel", end_effector_frame="r_hand_base_link",
        hand_axis=get_axis_in_env(env, axis_name="right_thumb_2_index"), object_axis=np.array([1.0, 0, 0]))]
    assert [len(w.constraints) for w in [grip_intent.infer(env, "right", c, planner.holding).first]] == [3]


def test_an_explicit_centre_pinch_from_above_lifts_the_cube():
    env, planner = _planner(pos=(-0.36, -0.05), yaw=-0.4)
    planner.hand_pre_pinch("right")
    c = _pinch_from_above(env, "right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    assert all(x.meta is None for x in c)  # the plan's constraints are left as they were
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="cube", obj_id=0)
    lift = [Constraint(env=env, type="point2point", end_effector_frame="r_hand_base_link",
                       hand_key_point=get_point_in_env(env, type_name="cube", obj_id=0),
                       object_key_point=get_point_in_env(env, type_name="cube", obj_id=0) + np.array([0, 0, 0.1]))]
    _, pose = planner.generate_end_effector_pose(lift, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
    assert get_point_in_env(env, type_name="cube", obj_id=0)[2] > 0.1
    assert any("higher than asked" in e for e in planner.events), planner.events
