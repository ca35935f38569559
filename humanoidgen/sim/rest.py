"""Whether the scene's objects have come to rest (the robot aside): a task is judged on a still scene.

A plan's last move can leave things in flight: cubes tipped out of a cup are still falling when the tilt ends,
a released block is still rocking. Judging them mid-air fails a pour that lands a tenth of a second later.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.sim.scene import Scene

# Below these an object counts as still: 1 cm/s and 0.1 rad/s (about 6 deg/s) for every degree of freedom of
# the object and its parts (free joints' linear and angular velocity, hinges, slides); and accelerating less
# than 1 m/s^2 and 10 rad/s^2, so that one let go in mid-air (at rest for an instant, falling at g) is moving.
STILL_LINEAR = 0.01
STILL_ANGULAR = 0.1
STILL_LINEAR_ACC = 1.0
STILL_ANGULAR_ACC = 10.0
# Long enough for a cube tipped from 15 cm to land and stop bouncing (about 0.2 s); an object still moving
# after this is judged where it is (a part swinging on its own, a ball rolling away). Here, not in
# `planning.settling` which waits for it, so that the parent's replay client (`episodes.replay`) can name it
# without importing the planner (numba, Drake: half a second of `hgen run`'s start).
MAX_REST_WAIT_S = 1.0


def object_dofs(scene: Scene) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Per object (`type[id]`), its velocity indices split into linear and angular ones: every joint of
    the bodies under the object's root body."""
    model = scene.model
    out: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for obj in scene.objects:
        root = model.body(obj.body).id
        linear: list[int] = []
        angular: list[int] = []
        for j in range(model.njnt):
            if model.body_rootid[model.jnt_bodyid[j]] != root:
                continue
            adr, kind = int(model.jnt_dofadr[j]), int(model.jnt_type[j])
            if kind == 0:  # free: 3 linear, then 3 angular
                linear += [adr, adr + 1, adr + 2]
                angular += [adr + 3, adr + 4, adr + 5]
            elif kind == 1:  # ball
                angular += [adr, adr + 1, adr + 2]
            elif kind == 2:  # slide
                linear.append(adr)
            else:  # hinge
                angular.append(adr)
        if linear or angular:
            out[f"{obj.type_name}[{obj.obj_id}]"] = (np.array(linear, int), np.array(angular, int))
    return out


def moving_objects(qvel: np.ndarray, qacc: np.ndarray, dofs: dict[str, tuple[np.ndarray, np.ndarray]]) -> list[str]:
    """The objects with any degree of freedom moving or accelerating faster than the tolerances above
    (`qvel`, `qacc`: the simulation's `data.qvel` and `data.qacc`)."""
    out = []
    for name, (lin, ang) in dofs.items():
        fast = (lin.size and (np.max(np.abs(qvel[lin])) > STILL_LINEAR or np.max(np.abs(qacc[lin])) > STILL_LINEAR_ACC)) \
            or (ang.size and (np.max(np.abs(qvel[ang])) > STILL_ANGULAR or np.max(np.abs(qacc[ang])) > STILL_ANGULAR_ACC))
        if fast:
            out.append(name)
    return out
