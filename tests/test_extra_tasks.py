"""The paper's additional challenging tasks (appendix): specs, the toaster's annotations, reference plans."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np
import pytest

from humanoidgen.objects import library
from humanoidgen.objects.articulated import ToasterFamily
from humanoidgen.tasks.registry import load_task, plan_path
from plan_runs import run_plan


@pytest.mark.parametrize("type_id", [0, 1])
def test_toaster_press_annotation_and_lever_travel(type_id):
    ann = library.annotations("toaster", type_id)
    (press,) = ann.operations_of("press")
    point = ann.point(press.point)
    assert point.part == "lever"
    assert ann.axis(press.approach_axis).direction == (0.0, 0.0, -1.0)  # pressed from above
    for name in (press.attach_axis, press.parallel_axis):
        assert np.linalg.norm(ann.axis(name).direction) == pytest.approx(1.0)
    fam = ToasterFamily()
    p = fam._p(type_id)
    design = fam._design(p)
    (lever,) = design.parts
    assert lever.joint.kind == "slide" and lever.joint.axis == (0, 0, -1)
    assert lever.joint.range == (0.0, p["travel"]) and ann.articulation.open == p["travel"]
    # The lever sticks out >= 5 cm from the front face, so the curled fingers clear the body on the way down.
    front = -p["depth"] / 2
    assert lever.pos[0] - p["lever_half"][0] <= front - 0.05
    # ...and its bottom stays above the table at full travel.
    assert lever.pos[2] - p["lever_half"][2] - p["travel"] > 0.0


def test_press_toaster_spec_matches_the_paper():
    spec = load_task("press_toaster")
    r = spec.randomization
    assert r.position[1] - r.position[0] == pytest.approx(0.05) and r.position[3] - r.position[2] == pytest.approx(0.05)
    assert r.yaw_deg == (-15.0, 15.0)
    assert plan_path(spec).is_file()


def test_press_toaster_reference_plan_succeeds(tmp_path):
    spec = load_task("press_toaster")
    result = run_plan(tmp_path, "press_toaster", 1000, plan_path(spec).read_text())
    assert result.success, result
