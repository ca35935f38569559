"""Start-up (`hgen run` beyond its episode; bench/startup.py): the robot's meshes that no geom uses are not
compiled, and that changes nothing that is simulated."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402

import humanoidgen.sim.robot as robot  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402


def _model_arrays(model: mujoco.MjModel, skip: tuple[str, ...] = ()) -> dict[str, np.ndarray]:
    return {n: getattr(model, n) for n in dir(model) if not n.startswith("_") and not n.startswith(skip)
            and isinstance(getattr(model, n, None), np.ndarray)}


def _assert_same_model(a: mujoco.MjModel, b: mujoco.MjModel, skip: tuple[str, ...] = ()) -> None:
    x, y = _model_arrays(a, skip), _model_arrays(b, skip)
    assert x.keys() == y.keys()
    differ = [n for n in x if x[n].shape != y[n].shape or not np.array_equal(x[n], y[n], equal_nan=True)]
    assert differ == []


def test_no_robot_mesh_is_compiled_that_no_geom_uses_and_the_physics_is_the_same(monkeypatch):
    model = SceneBuilder().build().model
    used = set(model.geom_dataid[model.geom_type == mujoco.mjtGeom.mjGEOM_MESH])
    assert used == set(range(model.nmesh))
    monkeypatch.setattr(robot, "_drop_unused_meshes", lambda spec: None)
    kept = SceneBuilder().build().model
    assert kept.nmesh == model.nmesh + 16  # the upstream meshes only visual geoms used
    _assert_same_model(model, kept, skip=("mesh_", "bvh_", "name_", "names", "paths", "geom_dataid"))
    a, b = mujoco.MjData(model), mujoco.MjData(kept)
    for k in range(300):  # the arms swing; contacts with the table and between the hands as they go
        ctrl = np.sin(k / 40 + np.arange(model.nu)) * 0.6
        a.ctrl[:], b.ctrl[:] = ctrl, ctrl
        mujoco.mj_step(model, a)
        mujoco.mj_step(kept, b)
    assert np.array_equal(a.qpos, b.qpos) and np.array_equal(a.qvel, b.qvel)

