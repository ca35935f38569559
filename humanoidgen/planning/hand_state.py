"""What the planner knows about each hand between calls: what it holds and how, how it came in, what it moved.

One `HandState` per side, owned by the planning context (`context.PlanningContext.hands`). Stages and
recoveries read and write these typed fields instead of dicts keyed by side on the planner; a snapshot copies
them whole. Rule: plain data, no behaviour beyond taking a one-shot value.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass
class HandState:
    held: Any = None  # the SceneObject the hand holds (a rigid object or an articulated part), or None
    grip: str | None = None  # "grasp" or "pinch": how `held` is held
    closing: str | None = None  # finger posture the next hand_grasp closes with ("wrap" for round bodies)
    last_approach: np.ndarray | None = None  # the direction the last grip came in along: the way back out
    part_moved: dict | None = None  # the follow dict of the part the hand last moved: how to let go of it
    approach_used: np.ndarray | None = None  # another way in than the operation's axis, taken by the last move
    goal_moved: Any = None  # the Pose a move went to instead of the one asked (a drop into a container)
    # Where the hand closed on an articulated part: (the object's body, {body id: the hand's end-effector pose
    # (point, rotation) in that body's frame}) for each body of the object; a hand that slid along or turned on
    # the part since goes back there as it moves the part on (part_grip.slid_since_grip).
    grip_anchor: tuple[str, dict[int, tuple[np.ndarray, np.ndarray]]] | None = None

    def take(self, name: str, default: Any = None) -> Any:
        """The field's value, and clear it (a one-shot message from one stage to the next)."""
        value = getattr(self, name)
        setattr(self, name, None)
        return default if value is None else value
