"""The 26-D action: joint-position targets for both arms and both hands.

Order (index: meaning), all values are joint angles in radians:

    0-6    left arm   shoulder pitch, shoulder roll, shoulder yaw, elbow pitch, elbow roll, wrist pitch, wrist yaw
    7-13   right arm  same order
    14-19  left hand  thumb yaw, thumb pitch, index, middle, ring, pinky (proximal joints; larger = more closed)
    20-25  right hand same order

The hands' other joints follow their proximal joint through the URDF's mimic couplings. The layout is derived
from the robot file (`robots.Robot.action_joints`: the arms, left then right, then the hands, left then right).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from humanoidgen.sim.layout import ROBOT, SIDES, Side

# Joint names in action order: what each action entry drives.
ACTION_JOINTS: tuple[str, ...] = ROBOT.action_joints
ACTION_DIM = len(ACTION_JOINTS)
ARM_SLICE: dict[Side, slice] = {side: ROBOT.arm_slices[side] for side in SIDES}
HAND_SLICE: dict[Side, slice] = {side: ROBOT.hand_slices[side] for side in SIDES}
_PARTS = ", ".join(f"{sl[s].stop - sl[s].start} {s} {part}" for sl, part in ((ARM_SLICE, "arm"), (HAND_SLICE, "hand"))
                   for s in SIDES)


class ActionError(ValueError):
    """An action that cannot be applied (wrong shape, not finite)."""


@dataclass(frozen=True)
class ActionLayout:
    """Index ranges of the action vector, for code that builds actions part by part."""

    arm: dict[Side, slice]
    hand: dict[Side, slice]

    def split(self, action: np.ndarray) -> dict[str, np.ndarray]:
        a = validate_action(action)
        return {f"{side}_{part}": a[sl[side]] for side in SIDES for part, sl in (("arm", self.arm), ("hand", self.hand))}


LAYOUT = ActionLayout(arm=ARM_SLICE, hand=HAND_SLICE)


def validate_action(action: object) -> np.ndarray:
    """Return the action as a float64 array of shape (26,), or raise ActionError saying what is wrong."""
    try:
        a = np.asarray(action, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ActionError(f"action must be a sequence of {ACTION_DIM} numbers: {exc}") from None
    if a.shape != (ACTION_DIM,):
        raise ActionError(
            f"action must have shape ({ACTION_DIM},) ({_PARTS}), "
            f"got shape {a.shape}"
        )
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        names = ", ".join(f"{i} ({ACTION_JOINTS[i]})" for i in bad[:5])
        raise ActionError(f"action has non-finite entries at index {names}")
    return a
