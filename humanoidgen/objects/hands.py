"""Annotations of the two hands: key points and axes in each wrist-yaw link frame, named as the paper's planner
API names them, and the finger postures of the atomic operations. They are the default robot's hand file's
(`robots/hands/inspire.yaml`: values, what they mean in words, the frame they are given in).

Wrist-yaw frame facts (the Inspire hand on the H1-2): fingers point along +x, the index finger is on the +z side
and the pinky on -z, the palm faces -y on the left hand and +y on the right (the thumb's side).
"""

from __future__ import annotations

import numpy as np

from humanoidgen.sim.layout import PALM_SIGN, ROBOT, SIDES, Side

_HAND = ROBOT.hand
# Finger postures (one value per actuated hand joint: thumb yaw, thumb pitch, index, middle, ring, pinky), radians.
HAND_POSTURES: dict[str, tuple[float, ...]] = _HAND.postures


def hand_points(side: Side) -> dict[str, np.ndarray]:
    return _HAND.points(side)


# A wrapped round body lies against the finger pads just beyond the opposed thumb (the hand file's `wrap`).
WRAP_NEAR_EDGE_X = _HAND.data.wrap.near_edge_x
WRAP_PAD_OFFSET = _HAND.data.wrap.pad_offset  # the body's surface this far out of the palm plane
WRAP_HEIGHT = _HAND.data.wrap.height  # towards the index: between the thumb and the middle of the fingers


def wrap_point(side: Side, width: float, across: float | None = None) -> np.ndarray:
    """Where on the hand (wrist frame) the near surface point of a wrapped body goes: `width` its extent along
    the approach, `across` its extent along the fingers (a flat bottle's broad face against the palm; None: round).
    Its edge nearest the thumb then lies just past the thumb, whatever its shape."""
    along = width if across is None else across
    return np.array([WRAP_NEAR_EDGE_X + along / 2, PALM_SIGN[side] * WRAP_PAD_OFFSET, WRAP_HEIGHT])


def narrow_grasp() -> str | None:
    """The posture a whole hand closes with on a narrow part of a round body (a bottle's shoulder, from above):
    the thumb further in than `grasp`'s; None where the hand has none (it then closes as `grasp`)."""
    return "grasp_narrow" if "grasp_narrow" in HAND_POSTURES else None


def firmer(posture: str) -> str | None:
    """A firmer closing of `posture` (its `<posture>_firm`, the thumb further in), for a grip that would not hold
    alone; None where the hand has none."""
    return f"{posture}_firm" if f"{posture}_firm" in HAND_POSTURES else None


def hand_axes(side: Side) -> dict[str, np.ndarray]:
    return _HAND.axes(side)


# What each hand point and axis is, in words ("{side}" stands for left / right): plan authors know the hands only
# from these (the prompts and docs show them; the hand file's schema refuses a point or axis without one). They
# are given in the world at the hand's pose now (get_point_in_env / get_axis_in_env) and move with the hand.
HAND_POINT_DESCRIPTIONS: dict[str, str] = _HAND.point_descriptions
HAND_AXIS_DESCRIPTIONS: dict[str, str] = _HAND.axis_descriptions


def hand_description(name: str) -> str:
    """What a hand point or axis is, in words."""
    generic = name.replace(side_of(name), "{side}", 1)
    table = {**HAND_POINT_DESCRIPTIONS, **HAND_AXIS_DESCRIPTIONS}
    if generic not in table:
        raise KeyError(f"no description of hand annotation {name!r}")
    return table[generic]


HAND_POINT_NAMES = tuple(n for side in SIDES for n in hand_points(side))
HAND_AXIS_NAMES = tuple(n for side in SIDES for n in hand_axes(side))


def side_of(name: str) -> Side:
    """Which hand a hand annotation name belongs to."""
    for side in SIDES:
        if f"_{side}_" in f"_{name}_":
            return side
    raise KeyError(name)
