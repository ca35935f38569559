"""The safe: a box on the table with a door on a vertical hinge, a handle bar on the door and a turning knob.

Built with the articulated families' machinery (objects/articulated.py): the shell is the root body, the door a
child body "<body>_door" on a hinge about z at the right-hand side of the front (as the robot sees it), the knob
a child of the door ("<body>_knob") on a hinge about its own axis, normal to the door. The object's openness is
the door's; the knob has an articulation of its own (`ObjectAnnotations.part_articulations`), so an openness
asked for a knob point (a pinch turned to openness 0.75) is the knob's turn.

Sizes are for the H1-2's right hand (README "The world"): with the safe at x ~ -0.19 its handle bar stands at
x ~ -0.36, where the drawer's handle is hooked, and swings to x ~ -0.5 fully open; the knob's fin sits 18-19 cm
above the table, high enough that the hand turned past upright (a handshake) keeps its little finger off the
table, and 12 cm above the handle bar's middle.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.articulated import (
    _BASIC_AXES,
    _Annot,
    _ArticulatedFamily,
    _ax,
    _Design,
    _Geom,
    _Joint,
    _op,
    _Part,
    _pt,
    _shell,
)
from humanoidgen.objects.schema import Articulation, FunctionAnnotation, ObjectAnnotations

__all__ = ["SafeFamily", "SAFE_FAMILIES"]

_DEG = np.pi / 180.0
_METAL = (0.78, 0.78, 0.74, 1.0)


class SafeFamily(_ArticulatedFamily):
    name = "safe"
    _params = {
        0: dict(description="small grey safe with a handle and a turning knob", depth=0.16, width=0.18, height=0.22,
                rgba=(0.35, 0.37, 0.4, 1.0), door_rgba=(0.45, 0.47, 0.5, 1.0)),
        1: dict(description="dark green safe with a handle and a turning knob", depth=0.18, width=0.20, height=0.24,
                rgba=(0.15, 0.3, 0.2, 1.0), door_rgba=(0.2, 0.38, 0.26, 1.0)),
    }
    _T, _TD = 0.012, 0.015  # wall, door thickness
    DOOR_OPEN_DEG = 90.0
    KNOB_OPEN_DEG = 120.0
    # The handle: a vertical bar on two posts, 8.5 cm off the door: a hand grasping it from the side comes in
    # with straight fingers, which reach ~6 cm past the bar before they close around it.
    BAR_OFF, BAR_HALF_LEN, BAR_R = 0.11, 0.05, 0.006
    HANDLE_IN = 0.03  # the bar this far in from the door's free edge
    # The knob: a round base on the door and a fin across it (horizontal when the knob is at 0), 4.8 cm out of
    # the door, so that fingertips reaching ~2.5 cm past the pinch stay off the door.
    # The knob sits high on the door above the handle bar (both near the free edge), 12 cm over the bar's
    # middle: a hand coming in sideways to the bar from the hinge's side passes nowhere near it (a planner
    # coming to grip the safe does not avoid the safe's own parts), and the hand turning the knob keeps clear
    # of the bar and the table.
    KNOB_IN = 0.045  # the knob's axis this far in from the door's free edge
    KNOB_Z = 0.075  # above the door's middle
    BAR_Z = -0.045
    BASE_HALF = (0.0125, 0.012, 0.012)
    FIN_HALF = (0.02, 0.03, 0.008)  # along the knob's axis (out of the door), across, thickness

    # -- geometry (design coordinates, closed) -------------------------------------------------------------
    def _fin_x(self) -> float:
        """The fin's centre along the knob's axis (knob frame: +x into the door)."""
        return -(2 * self.BASE_HALF[0] + self.FIN_HALF[0])

    def _design(self, p: dict) -> _Design:
        D, W, H, td = p["depth"], p["width"], p["height"], self._TD
        dc = p["door_rgba"]
        hy = W - self.HANDLE_IN  # the bar's position across the door (door frame: y from the hinge)
        post_half = (self.BAR_OFF - self.BAR_R) / 2
        door = [
            _Geom("door", (td / 2, W / 2 - 0.002, H / 2 - 0.005), (-td / 2, W / 2, 0), dc, 0.4),
            _Geom("handle_post_upper", (post_half, 0.005, 0.005), (-td - post_half, hy, self.BAR_Z + 0.7 * self.BAR_HALF_LEN),
                  _METAL, 0.01),
            _Geom("handle_post_lower", (post_half, 0.005, 0.005), (-td - post_half, hy, self.BAR_Z - 0.7 * self.BAR_HALF_LEN),
                  _METAL, 0.01),
            _Geom("handle_bar", (self.BAR_R, self.BAR_R, self.BAR_HALF_LEN), (-td - self.BAR_OFF, hy, self.BAR_Z), _METAL,
                  0.02),
        ]
        bx = self.BASE_HALF[0]
        knob = [_Geom("knob_base", self.BASE_HALF, (-bx, 0, 0), _METAL, 0.01),
                _Geom("knob_fin", self.FIN_HALF, (self._fin_x(), 0, 0), _METAL, 0.01)]
        # The door's hinge holds it where a hand leaves it; the knob turns stiffly enough not to spin on from a
        # flick, and its fin is symmetric about the axis, so gravity does not turn it.
        door_j = _Joint("hinge", "hinge", (0, 0, 1), (0.0, self.DOOR_OPEN_DEG * _DEG), damping=0.3, frictionloss=0.3)
        knob_j = _Joint("knob_hinge", "hinge", (1, 0, 0), (0.0, self.KNOB_OPEN_DEG * _DEG), damping=0.01,
                        frictionloss=0.02, armature=0.001)
        return _Design(_shell(D, W, H, self._T, p["rgba"]), [
            _Part("door", (-D / 2, -W / 2, 0), door_j, door),
            _Part("knob", (-td, W - self.KNOB_IN, self.KNOB_Z), knob_j, knob, parent="door"),
        ])

    # -- annotations ---------------------------------------------------------------------------------------
    def _annot(self, p: dict, design: _Design) -> _Annot:
        W, H, td = p["width"], p["height"], self._TD
        hy, bx = W - self.HANDLE_IN, -td - self.BAR_OFF
        fx, fy = self._fin_x(), self.FIN_HALF[1]
        points = [
            _pt("handle", (bx, hy, self.BAR_Z), "door", "middle of the vertical handle bar"),
            _pt("door_edge", (-td, W - 0.012, 0), "door", "door's outer face near its free edge"),
            _pt("door_inner", (0, W - 0.02, 0), "door", "door's inner face near its free edge (to push it shut)"),
            _pt("knob", (fx - self.FIN_HALF[0], 0, 0), "knob", "front of the knob, on its axis"),
            # The pinch point is the fin's right end; the pads go 12 mm in from it (the planner's part-pinch inset),
            # 1.8 cm off the knob's axis: turning the hand then presses the index and thumb on the fin's faces with
            # that lever (on the axis, only the pads' torsional friction would turn it, and they slip).
            _pt("knob_fin_right", (fx, -fy, 0), "knob", "right end of the knob's fin (knob at 0)"),
            _pt("knob_fin_left", (fx, fy, 0), "knob", "left end of the knob's fin (knob at 0)"),
            _pt("storage", (0, 0, -H / 2 + self._T + 0.005), None, "inside the safe, above its floor"),
        ]
        axes = _BASIC_AXES + [
            _ax("front", (-1, 0, 0), None, "out of the safe's opening"),
            _ax("door_in", (1, 0, 0), "door", "into the door from its outer face"),
            _ax("door_out", (-1, 0, 0), "door", "out of the door's outer face"),
            _ax("door_across", (0, 1, 0), "door", "from the hinge toward the free edge"),
            _ax("door_toward_hinge", (0, -1, 0), "door", "from the free edge toward the hinge"),
            _ax("grip_from_hinge_side", (0.259, 0.966, 0), "door", "into the handle from in front, on the hinge's side"),
            _ax("door_hinge", (0, 0, 1), "door", "the door's hinge axis (vertical)"),
            _ax("knob_axis", (1, 0, 0), "knob", "the knob's rotation axis, into the door"),
            _ax("fin_leftward", (0, 1, 0), "knob", "along the fin toward its left end (knob at 0)"),
            _ax("fin_rightward", (0, -1, 0), "knob", "along the fin toward its right end (knob at 0)"),
            _ax("fin_normal", (0, 0, 1), "knob", "across the fin's thickness (up with the knob at 0)"),
        ]
        ops = [
            # Around the bar, the fingers along it (the grip rolls about the bar while the door swings): from the
            # hinge's side and in front (a right hand's handshake, the fingers pointing past the bar 15 deg off the
            # door's normal: open, they reach 10 cm beyond the grasp point, less than the bar's 11 cm off the
            # door), or with the palm toward the door. Not from the free edge's side: that is a left hand's
            # handshake, and a left hand cannot follow the bar where the door swings it (to the hinge's side, the
            # robot's right); a right hand taking it so has its index down and its pre-grasp thumb in the bar.
            _op("grasp", "handle", "grip_from_hinge_side", "door_out", "door_hinge"),
            _op("grasp", "handle", "door_in", "door_across", "door_hinge"),
            _op("pull", "handle", "door_in", "door_across", "door_hinge"),
            _op("push", "door_inner", "door_out", "door_across", "door_hinge"),
            # Thumb and index squeeze the fin across its thickness, the index edge leading along the fin from its
            # right end. The knob turns clockwise (as the robot sees it), so this one pinch suits either hand: a
            # right hand comes palm down and turns toward a handshake (supination), a left hand comes palm up
            # and turns toward palm down (pronation). From the left end the turn would strain either forearm
            # past its natural range, so that end is not annotated for a pinch.
            _op("pinch", "knob_fin_right", "fin_leftward", "fin_normal", "knob_axis"),
        ]
        return _Annot(p["description"], points, axes, ops,
                      [FunctionAnnotation(function="storage", point="storage", axis="front")],
                      Articulation(joint="hinge", closed=0.0, open=self.DOOR_OPEN_DEG * _DEG))

    def annotations(self, type_id: int) -> ObjectAnnotations:
        ann = super().annotations(type_id)
        knob = Articulation(joint="knob_hinge", closed=0.0, open=self.KNOB_OPEN_DEG * _DEG, part="knob")
        return ObjectAnnotations.model_validate(ann.model_dump() | {"part_articulations": [knob.model_dump()]})


SAFE_FAMILIES = {SafeFamily.name: SafeFamily()}
