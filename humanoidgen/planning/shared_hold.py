"""One object held by both hands (a pot lifted by its two handles): the two arms carry it together.

Each arm's motion is planned on its own with the object riding on that arm's hand. The other arm moves with the
object, so it is no obstacle there (`CollisionWorld` leaves it out while both hands carry the same body); the
arms are checked against each other at every step of the joint move instead (`arm_moves.coordinate_arms`), and
the object itself, held by both, is no contact between them. The two motions are then put in step: at every
control step each hand has gone the same share of its way, so the object is not pulled between the hands (two
straight moves of the same displacement keep the hands' offset all the way; timed on their own, one arm's
trapezoid profile runs ahead of the other's).
"""

from __future__ import annotations

import numpy as np

from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.sim.layout import SIDES, Side
from humanoidgen.sim.scene import SceneObject


def shared_object(holding: dict[Side, SceneObject | None]) -> SceneObject | None:
    """The object both hands hold, or None."""
    left, right = (holding.get(s) for s in SIDES)
    return left if left is not None and left is right else None


def _progress(kin: Kinematics, side: Side, samples: np.ndarray) -> np.ndarray:
    """Share of the hand's way (path length of its end effector) done at each sample, 0 to 1, non-decreasing."""
    points = np.empty((len(samples), 3))
    for k, row in enumerate(samples):
        kin.set_arm(side, row[:7])
        kin.forward()
        points[k] = kin.ee_pose(side)[0]
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    done = np.concatenate([[0.0], np.cumsum(steps)])
    return done / done[-1] if done[-1] > 1e-9 else np.linspace(0.0, 1.0, len(samples))


def _at_progress(samples: np.ndarray, progress: np.ndarray, wanted: np.ndarray) -> np.ndarray:
    """The samples' rows (arm and finger targets) interpolated where the hand has gone `wanted` of its way."""
    # np.interp needs increasing abscissae: a hand at rest for a few steps gets a hair of progress per step.
    x = progress + np.arange(len(progress)) * 1e-12
    return np.column_stack([np.interp(wanted, x, samples[:, j]) for j in range(samples.shape[1])])


def in_step(kin: Kinematics, samples: dict[Side, np.ndarray]) -> dict[Side, np.ndarray]:
    """Both arms' control-step samples re-timed so that the hands go the same share of their ways at every step:
    as many steps as the longer motion, each at the share the slower hand has reached by then (the kinematic
    state is left changed: the caller syncs it)."""
    n = max(len(s) for s in samples.values())
    progress = {side: _progress(kin, side, s) for side, s in samples.items()}
    # Each hand's share at each common step on its own timing (a shorter motion has arrived early), the slower's
    # kept: neither arm runs ahead of its own planned timing.
    own = [np.concatenate([p, np.ones(n - len(p))]) for p in progress.values()]
    wanted = np.minimum(*own)
    wanted[-1] = 1.0
    return {side: _at_progress(s, progress[side], wanted) for side, s in samples.items()}
