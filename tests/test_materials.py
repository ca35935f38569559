"""Object materials: an object's own friction decides its contacts with other objects (fingertips and the table
are grippier), so wood and glazed ceramic must let a cube slide on a slope a tipped cup's wall makes."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from humanoidgen.objects.family_data import material

CERAMIC, WOOD = material("ceramic"), material("wood")  # families/materials.yaml


def _slide(slope_deg: float, below: tuple, cube: tuple, seconds: float = 0.6) -> float:
    """How far (m) a 3 cm cube set on a static slab tilted `slope_deg` moves in `seconds`."""
    spec = mujoco.MjSpec()
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    spec.option.impratio = 10.0
    spec.option.timestep = 0.002
    a = math.radians(slope_deg)
    tilt = [math.cos(a / 2), 0.0, math.sin(a / 2), 0.0]  # about y: the slope falls toward +x
    spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.2, 0.2, 0.01], quat=tilt, friction=list(below),
                            condim=4)
    n = np.array([math.sin(a), 0.0, math.cos(a)])  # the slab's top normal
    body = spec.worldbody.add_body(pos=list(n * (0.01 + 0.015 + 0.0005)), quat=tilt)
    body.add_freejoint()
    body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.015] * 3, mass=0.02, friction=list(cube), condim=4)
    model = spec.compile()
    data = mujoco.MjData(model)
    start = data.qpos[:3].copy()
    while data.time < seconds:
        mujoco.mj_step(model, data)
    return float(np.linalg.norm(data.qpos[:3] - start))


@pytest.mark.parametrize("below", [CERAMIC, WOOD], ids=["on ceramic", "on wood"])
def test_a_wooden_cube_slides_on_a_steep_slope_and_rests_on_a_gentle_one(below):
    assert _slide(33.0, below, WOOD) > 0.02  # the wall of a cup tipped ~123 deg
    assert _slide(15.0, below, WOOD) < 0.002


def test_the_old_grippy_wood_would_have_held_the_cube_in_the_tipped_cup():
    # The case this guards: friction 1.0 kept two cubes wedged in a cup tipped well past horizontal.
    assert _slide(33.0, CERAMIC, (1.0, 0.01, 0.001)) < 0.002
