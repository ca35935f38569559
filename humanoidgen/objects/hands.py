"""Annotations of the two Inspire hands: key points and axes in each wrist-yaw link frame, named as the
paper's planner API names them, and the 6-D finger postures of the atomic operations.

Wrist-yaw frame facts (from the upstream MJCF): fingers point along +x, the index finger is on the +z side
and the pinky on -z, the palm faces -y on the left hand and +y on the right (the thumb's side).
"""

from __future__ import annotations

import numpy as np

from humanoidgen.sim.layout import PALM_SIGN, SIDES, Side

# Finger postures (thumb yaw, thumb pitch, index, middle, ring, pinky), radians.
HAND_POSTURES: dict[str, tuple[float, ...]] = {
    "open": (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    "pre_grasp": (1.3, 0.0, 0.0, 0.0, 0.0, 0.0),  # thumb turned to face the fingers
    "grasp": (1.3, 0.35, 1.3, 1.3, 1.3, 1.3),
    "pre_pinch": (1.3, 0.0, 0.0, 1.4, 1.4, 1.4),  # thumb and index opposed, other fingers tucked away
    "pinch": (1.3, 0.5, 0.9, 1.4, 1.4, 1.4),  # closes until the tips meet the object (tests/test_pinch_hold.py)
    # Around a round body: thumb, index and middle squeeze; ring and pinky only rest on it. With all four fingers
    # pushing, the squeeze sits below the thumb and tips a standing bottle over by about 30 degrees.
    "wrap": (1.3, 0.35, 1.3, 1.3, 0.6, 0.6),
    "press": (0.6, 0.5, 0.0, 1.6, 1.6, 1.6),  # index extended, the rest curled
}


def hand_points(side: Side) -> dict[str, np.ndarray]:
    s = PALM_SIGN[side]
    return {
        f"base_{side}_hand": np.array([0.054, 0.0, 0.0]),
        # Inside the ring that the closed fingers and thumb make (measured in the grasp posture).
        f"grasp_point_base_{side}_hand": np.array([0.165, s * 0.045, 0.005]),
        # Where thumb tip and index pad meet on a 4 cm cube (measured in simulation, tests/test_pinch_hold.py).
        f"pinch_point_base_{side}_hand": np.array([0.205, s * 0.045, 0.020]),
        f"press_point_base_{side}_hand": np.array([0.265, 0.0, 0.032]),
        f"palm_center_{side}_hand": np.array([0.125, s * 0.03, 0.0]),
    }


# A wrapped round body lies against the finger pads just beyond the opposed thumb, whose tip reaches about
# x = 0.17 in the wrist frame and 10 cm out of the palm in the pre-grasp posture (measured in simulation).
WRAP_NEAR_EDGE_X = 0.178
WRAP_PAD_OFFSET = 0.014  # the body's surface this far out of the palm plane
WRAP_HEIGHT = 0.005  # towards the index: between the thumb and the middle of the fingers


def wrap_point(side: Side, width: float, across: float | None = None) -> np.ndarray:
    """Where on the hand (wrist frame) the near surface point of a wrapped body goes: `width` its extent along
    the approach, `across` its extent along the fingers (a flat bottle's broad face against the palm; None: round).
    Its edge nearest the thumb then lies just past the thumb, whatever its shape."""
    along = width if across is None else across
    return np.array([WRAP_NEAR_EDGE_X + along / 2, PALM_SIGN[side] * WRAP_PAD_OFFSET, WRAP_HEIGHT])


def hand_axes(side: Side) -> dict[str, np.ndarray]:
    s = PALM_SIGN[side]
    return {
        f"{side}_grasp_axis": np.array([0.0, s, 0.0]),  # back of the palm -> out of the palm
        # The direction the pinch faces, out of the hand's index edge. The paper's prompts: "pinch axis parallel to
        # [0, 0, -1] means pinching with the palm facing down", i.e. from above. This hand's thumb meets the index
        # pad along the palm normal, so a pinch from above has the index edge down and the thumb beside the
        # object (with the palm itself down the thumb would be under the object, in the table).
        f"{side}_pinch_axis": np.array([0.0, 0.0, 1.0]),
        f"{side}_thumb_2_index": np.array([0.0, -s, 0.0]),  # thumb tip -> index tip when pinching
        f"{side}_ring_2_index": np.array([0.0, 0.0, 1.0]),
        f"{side}_grasp_wrist_2_palm_axis": np.array([1.0, 0.0, 0.0]),
        f"{side}_pinch_wrist_2_palm_axis": np.array([1.0, 0.0, 0.0]),
        f"{side}_press_axis": np.array([1.0, 0.0, 0.0]),  # along the extended index finger
    }


# What each hand point and axis is, in words ("{side}" stands for left / right): plan authors know the hands only
# from these (the prompts and docs show them; tests fail on a point or axis without one). They are given in the
# world at the hand's pose now (get_point_in_env / get_axis_in_env) and move with the hand.
HAND_POINT_DESCRIPTIONS: dict[str, str] = {
    "base_{side}_hand": "the base of the hand, 5.4 cm from the wrist joint toward the fingers",
    "grasp_point_base_{side}_hand": "inside the ring that the closed fingers and thumb make, 16.5 cm out from the "
                                    "wrist and 4.5 cm out of the palm: what a whole-hand grasp holds is centred here",
    "pinch_point_base_{side}_hand": "where the thumb tip and the index finger's pad meet in a pinch",
    "press_point_base_{side}_hand": "the tip of the extended index finger (in the hand_press posture)",
    "palm_center_{side}_hand": "the middle of the palm, 12.5 cm from the wrist joint",
}
HAND_AXIS_DESCRIPTIONS: dict[str, str] = {
    "{side}_grasp_axis": "out of the palm, from the back of the hand through the palm: the way the palm faces",
    "{side}_pinch_axis": "out of the hand's index-finger edge (from the little finger's edge toward the index's): "
                         "the way a pinch faces; pointing down means pinching from above, index edge down and the "
                         "thumb beside the object",
    "{side}_thumb_2_index": "from the thumb tip toward the index fingertip in a pinch: into the palm, opposite to "
                            "the grasp axis",
    "{side}_ring_2_index": "across the hand from the ring finger toward the index finger (the same as the pinch axis)",
    "{side}_grasp_wrist_2_palm_axis": "from the wrist toward the fingertips, along the straight fingers",
    "{side}_pinch_wrist_2_palm_axis": "from the wrist toward the fingertips (the same as the grasp one)",
    "{side}_press_axis": "along the extended index finger, from its knuckle toward its tip: the way a press pushes "
                         "(to press down, point it along the pressed object's `down` axis, [0, 0, -1])",
}


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
