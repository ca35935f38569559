"""Pinching a plate's edge (a screen's top edge, a lid's front): the fingers may enter it at a slant where
pointing them straight in is out of reach, the pads go over the plate rather than off its edge, and the pinch
carries the part through its arc."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

os.environ.setdefault("MUJOCO_GL", "egl")

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env  # noqa: E402
from humanoidgen.planning.constraint_gen import PART_PINCH_INSET_M  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402
from plan_runs import run_plan, task_planner  # noqa: E402

# A corpus plan written from the paper's API (bench/foreign_plans): pinch the screen's edge, lift it to 0.85.
PINCH_OPEN = Path(__file__).parent.parent / "bench" / "foreign_plans" / "open_laptop_easy" / "alt_pinch_open.py"


def test_a_half_open_screens_top_edge_is_pinched_with_the_fingers_slanted_and_the_pads_over_the_screen():
    _, env = build_scene(load_task("close_laptop_easy"), 0)
    planner = task_planner(env, seed=0)
    planner.hand_pre_pinch("right")
    cons = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(cons, "right")  # straight in it is ~10 cm out of reach
    assert pose is not None
    edge = get_point_in_env(env, "screen_edge", "laptop", 0)
    edge_in = get_axis_in_env(env, "edge_in", obj_type="laptop", obj_id=0)
    gen = cons[0].meta
    ways = [gen, *gen.alternatives]
    assert any("index edge leads at" in c.name for w in ways for c in w.constraints)  # slanted ways are offered
    targets = [w.constraints[0].object_key_point for w in ways]
    depths = [float(np.dot(t - edge, edge_in)) for t in targets]
    assert min(depths) > 0.0  # every way puts the pads inside the edge, none on it
    assert max(depths) <= PART_PINCH_INSET_M + 1e-6


def test_a_pinched_screen_is_lifted_open(tmp_path):
    result = run_plan(tmp_path, "open_laptop_easy", 4, PINCH_OPEN.read_text())  # the seed that lost the pinch
    assert result.success, [s.error for s in result.steps if not s.ok] + [c["detail"] for c in result.checks]


def _first_squeeze(env) -> np.ndarray:
    planner = task_planner(env, seed=0)
    cons = planner.generate_constraints(obj_name="laptop", obj_id=0, action="pinch", hand_name="right")
    return next(c.object_axis for c in cons if c.name == "pinch along the attach axis")


def test_a_low_screen_is_pinched_thumb_on_its_outer_face_and_index_under_it():
    # Seeds where the most natural hand would put the thumb under the screen's edge (it then slipped off as the
    # screen was lifted, or the index coming in over the screen pressed it shut).
    for seed in (2, 3, 4):
        _, env = build_scene(load_task("open_laptop_easy"), seed)
        lid_in = get_axis_in_env(env, "lid_in", obj_type="laptop", obj_id=0)
        assert float(_first_squeeze(env) @ lid_in) > 0.9, seed  # thumb -> index: into the lid from its outer face
    # An upright screen (to be shut) keeps the most natural hand: the preference is only for parts pinched low.
    _, env = build_scene(load_task("close_laptop_easy"), 2)
    lid_in = get_axis_in_env(env, "lid_in", obj_type="laptop", obj_id=0)
    assert float(_first_squeeze(env) @ lid_in) < -0.9
