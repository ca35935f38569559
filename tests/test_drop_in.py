"""A carried object brought between a deep container's walls (planning/drop_in.py): no way leads the hand down
there, so the move ends above the container's top and letting go drops the object in.

- geometry: which goals count as "in the container, below its top", and how far up they go;
- end to end: a plan written outside the project (the paper's task description, literally) moves the block to
  10 cm above the open drawer's storage point, which in our 23 cm deep drawer is between the walls; the planner
  brings it above the drawer instead, says so, and the block lands inside.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from humanoidgen.objects.articulated import set_openness
from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.objects.queries import storage_region
from humanoidgen.planning.drop_in import DROP_CLEARANCE_M, DROP_HIGHER_M, drop_in
from humanoidgen.planning.placing import lowest_offset, object_pose
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene
from plan_runs import run_plan


@pytest.fixture(scope="module")
def open_drawer():
    _, env = build_scene(load_task("handover_and_storage"), 0)
    drawer = env.scene.object("drawer", 0)
    set_openness(env.model, env.data, drawer.body, drawer.annotations, 0.9)
    return env, drawer, env.scene.object("cube", 0)


def test_a_goal_between_the_walls_is_raised_above_the_top(open_drawer):
    env, drawer, cube = open_drawer
    R = object_pose(env, cube)[1]
    storage = get_point_in_env(env, "storage", "drawer", 0)
    way = drop_in(env, cube, storage + np.array([0.0, 0.0, 0.10]), R)
    assert way is not None and way.container is drawer
    raises = way.raises(cube, storage + np.array([0.0, 0.0, 0.10]), R)
    _, _, _, top = storage_region(env, drawer)
    assert way.top == pytest.approx(top)
    # The first raise puts the block's lowest corner DROP_CLEARANCE_M over the top; the others go higher.
    bottom = storage[2] + 0.10 - lowest_offset(cube, R) + raises[0]
    assert bottom == pytest.approx(top + DROP_CLEARANCE_M)
    assert np.diff(raises) == pytest.approx(np.diff(DROP_HIGHER_M))


def test_goals_above_the_top_or_beside_the_container_are_left_alone(open_drawer):
    env, drawer, cube = open_drawer
    R = object_pose(env, cube)[1]
    storage = get_point_in_env(env, "storage", "drawer", 0)
    _, _, _, top = storage_region(env, drawer)
    above = storage.copy()
    above[2] = top + lowest_offset(cube, R) + 0.01
    assert drop_in(env, cube, above, R) is None
    beside = storage + np.array([0.0, -0.25, 0.10])  # right of the drawer, at the same height
    assert drop_in(env, cube, beside, R) is None


HANDOVER_AND_STORE = (Path(__file__).resolve().parents[1] / "bench" / "foreign_plans" / "handover_and_storage"
                      / "paper.py")


@pytest.mark.slow
def test_a_block_moved_to_a_point_between_the_drawer_walls_is_dropped_in(tmp_path):
    result = run_plan(tmp_path, "handover_and_storage", 1, HANDOVER_AND_STORE.read_text())
    failed = result.failed_step
    assert result.success, (failed.error if failed else None, result.checks)
    assert any("above where asked, clear of drawer 0's top" in e for e in result.events), result.events
