"""The safe: a box on the table with a door on a vertical hinge, a handle bar on the door and a turning knob.

Built with the articulated families' machinery (objects/articulated_base.py): the shell is the root body, the
door a child body "<body>_door" on a hinge about z at the right-hand side of the front (as the robot sees it),
the knob a child of the door ("<body>_knob") on a hinge about its own axis, normal to the door. The object's
openness is the door's; the knob has an articulation of its own (`ObjectAnnotations.part_articulations`), so an
openness asked for a knob point (a pinch turned to openness 0.75) is the knob's turn.

The models (sizes, colours, masses, joint dynamics, where the handle and knob sit) and the annotation vocabulary
are data: humanoidgen/objects/families/safe/ (validated by `SafeParams`); family.yaml says why its numbers are
what they are. This module says how the geoms, parts and joints follow from them and where the points are.
"""

from __future__ import annotations

from humanoidgen.objects.articulated_base import _DEG, _DataFamily, _Design, _Geom, _joint, _Part, _shell
from humanoidgen.objects.params import SafeParams
from humanoidgen.objects.schema import Articulation, ObjectAnnotations

__all__ = ["SafeFamily", "SAFE_FAMILIES"]

Vec3 = tuple[float, float, float]
# The fin's pinch point sits this far in from the fin's outer face (toward the robot), not at the middle of its
# depth: a pinch's fingers point along the knob's axis, into the door, and reach ~4 cm past the pinch point; at the
# middle the index curled onto the door (its tip stopped there) and only the thumb held the fin, which then did
# not turn with the hand (issue 35: 0-9% of the way).
FIN_PINCH_IN = 0.006


class SafeFamily(_DataFamily):
    name = "safe"
    Params = SafeParams

    # -- geometry (design coordinates, closed) -------------------------------------------------------------
    @staticmethod
    def _fin_x(p: dict) -> float:
        """The fin's centre along the knob's axis (knob frame: +x into the door)."""
        return -(2 * p["knob_base_half"][0] + p["knob_fin_half"][0])

    @staticmethod
    def _bar(p: dict) -> Vec3:
        """The handle bar's middle in the door's frame (y from the hinge)."""
        return (-p["door_thick"] - p["handle_offset"], p["width"] - p["handle_in"], p["handle_z"])

    def _design(self, p: dict) -> _Design:
        D, W, H, td, m = p["depth"], p["width"], p["height"], p["door_thick"], p["masses"]
        dc, metal, (gy, gz) = p["door_rgba"], p["metal_rgba"], p["door_gap"]
        _, hy, bz = self._bar(p)
        r, half_len, (py, pz) = p["handle_radius"], p["handle_half_len"], p["handle_post_half"]
        post_half = (p["handle_offset"] - r) / 2
        post_dz = p["handle_post_at"] * half_len
        door = [
            _Geom("door", (td / 2, W / 2 - gy, H / 2 - gz), (-td / 2, W / 2, 0), dc, m["door"]),
            _Geom("handle_post_upper", (post_half, py, pz), (-td - post_half, hy, bz + post_dz), metal,
                  m["handle_post_upper"]),
            _Geom("handle_post_lower", (post_half, py, pz), (-td - post_half, hy, bz - post_dz), metal,
                  m["handle_post_lower"]),
            _Geom("handle_bar", (r, r, half_len), self._bar(p), metal, m["handle_bar"]),
        ]
        base = p["knob_base_half"]
        knob = [_Geom("knob_base", base, (-base[0], 0, 0), metal, m["knob_base"]),
                _Geom("knob_fin", p["knob_fin_half"], (self._fin_x(p), 0, 0), metal, m["knob_fin"])]
        door_j = _joint("hinge", "hinge", (0, 0, 1), (0.0, p["door_open_deg"] * _DEG), p["hinge"])
        knob_j = _joint("knob_hinge", "hinge", (1, 0, 0), (0.0, p["knob_open_deg"] * _DEG), p["knob_hinge"])
        return _Design(_shell(D, W, H, p["wall"], p["rgba"], m), [
            _Part("door", (-D / 2, -W / 2, 0), door_j, door),
            _Part("knob", (-td, W - p["knob_in"], p["knob_z"]), knob_j, knob, parent="door"),
        ])

    # -- annotations ---------------------------------------------------------------------------------------
    def _positions(self, p: dict) -> dict[str, Vec3]:
        W, H, td = p["width"], p["height"], p["door_thick"]
        fx, fin = self._fin_x(p), p["knob_fin_half"]
        return {
            "handle": self._bar(p),
            "door_edge": (-td, W - p["door_edge_in"], 0),
            "door_inner": (0, W - p["door_inner_in"], 0),
            "knob": (fx - fin[0], 0, 0),
            "knob_fin_right": (fx - fin[0] + FIN_PINCH_IN, -fin[1], 0),
            "knob_fin_left": (fx, fin[1], 0),
            "storage": (0, 0, -H / 2 + p["wall"] + 0.005),
        }

    def _articulation(self, p: dict) -> Articulation:
        return Articulation(joint="hinge", closed=0.0, open=p["door_open_deg"] * _DEG)

    def annotations(self, type_id: int) -> ObjectAnnotations:
        ann = super().annotations(type_id)
        p = self._p(type_id)
        knob = Articulation(joint="knob_hinge", closed=0.0, open=p["knob_open_deg"] * _DEG, part="knob")
        return ObjectAnnotations.model_validate(ann.model_dump() | {"part_articulations": [knob.model_dump()]})


SAFE_FAMILIES = {SafeFamily.name: SafeFamily()}
