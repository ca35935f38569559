"""The goal search's last rung (`planning/pinch_slant.py`): a loose object's pinch with the fingers turned about
the squeeze axis, where no level pinch reaches (the G1's left hand at handover_and_storage's hand-over spot:
elbow or wrist in the torso with the fingers forward, the thumb in the open drawer with them to the side)."""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning import goal_search, pinch_slant
from humanoidgen.sim.geometry import axis_angle_mat
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


def _pinch(finger_offset: float = 0.0):
    _, env = build_scene(load_task("block_stack_single"), 0)
    planner = task_planner(env)
    planner.hand_pre_pinch("right")
    cons = planner.generate_constraints("cube", 0, "pinch", "right", finger_offset=finger_offset)
    return env, cons[0].meta


def test_the_leading_edge_turns_about_the_squeeze_axis():
    env, gen = _pinch()
    way = pinch_slant.slanted(gen, -60)
    lead = next(c for c in gen.constraints if c.name == pinch_slant.LEADS)
    squeeze = next(c for c in gen.constraints if c.name == pinch_slant.SQUEEZE)
    turned = next(c for c in way.constraints if c.name.startswith(pinch_slant.LEADS + " at"))
    expected = axis_angle_mat(squeeze.object_axis, np.radians(-60)) @ lead.object_axis
    assert np.allclose(turned.object_axis, expected) and np.allclose(way.approach_axis, expected)
    assert any(c is squeeze for c in way.constraints)  # the same two faces squeezed
    assert not way.alternatives and gen.constraints[1] is lead  # the generated way itself is left as it was


def test_a_finger_offset_stays_level_when_slanted():
    """Along slanted fingers a plan's finger_offset would lift the pads over a block's top: it is turned back level."""
    env, gen = _pinch(finger_offset=0.02)
    way = pinch_slant.slanted(gen, -60)
    raw = get_point_in_env(env, "pinch_point_base_right_hand")
    old = next(c for c in gen.constraints if c.type == "point2point").hand_key_point - raw
    new = next(c for c in way.constraints if c.type == "point2point").hand_key_point - raw
    # The hand turns -60 deg about its pinch axis to the slanted way: the offset, fixed in the hand, is turned
    # back +60 deg about it beforehand, so that at the goal it points where it pointed at the level way's.
    turn = axis_angle_mat(get_axis_in_env(env, "right_thumb_2_index"), np.radians(-60))
    assert np.isclose(np.linalg.norm(new), 0.02, atol=1e-6) and np.allclose(turn @ new, old, atol=1e-9)


def test_only_loose_pinches_are_slanted():
    _, env = build_scene(load_task("block_stack_single"), 0)
    planner = task_planner(env)
    grasp = planner.generate_constraints("cube", 0, "grasp", "right")[0].meta
    assert pinch_slant.slanted(grasp, 30) is None
    assert pinch_slant.slanted(None, 30) is None


def test_the_rung_comes_last():
    """Goals found before are found the same way: the slanted pinch is tried only after the wider search."""
    import inspect

    src = inspect.getsource(goal_search.solve_goal)
    assert src.index("wider_goal(") < src.index("pinch_slant.slanted_goal(")
