"""Parametric articulated object families: drawer, laptop, box, toaster (the safe: objects/safe.py, the same way).

Each family builds its object from box geoms into the object's (fixed) body: the root body holds the static
shell, child bodies "<body>_<part>" hold the moving parts, joints are "<body>_<joint>". The object's frame has
its origin at the centre of its bounding box at openness 0 (closed), +x pointing away from the robot, z up.
Joints carry damping and friction loss so that a part stays where a hand leaves it (no drift under gravity).

The models (dimensions, colours, masses, joint dynamics) and each family's annotation vocabulary are data:
humanoidgen/objects/families/<family>/ (objects/family_data.py, objects/params.py). This module says how a
model's geoms, parts and joints follow from its parameters and where its annotated points are.

`set_openness` / `get_openness` map the annotated articulation joint to openness in [0, 1].
"""

from __future__ import annotations

import mujoco
import numpy as np

from humanoidgen.objects.articulated_base import _DEG, _DataFamily, _Design, _Geom, _joint, _Part, _shell
from humanoidgen.objects.family import ObjectFamily
from humanoidgen.objects.params import BoxParams, DrawerParams, LaptopParams, ToasterParams
from humanoidgen.objects.schema import Articulation, ObjectAnnotations

__all__ = ["ARTICULATED_FAMILIES", "set_openness", "get_openness", "openness_joint"]

Vec3 = tuple[float, float, float]


# -- drawer ---------------------------------------------------------------------------------------------------
class DrawerFamily(_DataFamily):
    name = "drawer"
    Params = DrawerParams

    def _geometry(self, p: dict) -> dict:
        D, W, H, t, g, dt = p["depth"], p["width"], p["height"], p["shell_wall"], p["clearance"], p["drawer_wall"]
        dx = D - t - g  # drawer depth
        wy = W / 2 - t - g  # drawer half width
        zb, zt = -H / 2 + t + g, H / 2 - t - g
        return dict(D=D, W=W, H=H, t=t, dt=dt, dx=dx, wy=wy, zb=zb, zt=zt, zc=(zb + zt) / 2, hz=(zt - zb) / 2,
                    xc=-D / 2 + dx / 2, bar_x=-D / 2 - p["handle_offset"], bar_h=p["handle_bar_half"][2],
                    bar_z=zt - p["handle_drop"])

    def _design(self, p: dict) -> _Design:
        q = self._geometry(p)
        D, dt, dx, wy, zb, zc, hz, xc = q["D"], q["dt"], q["dx"], q["wy"], q["zb"], q["zc"], q["hz"], q["xc"]
        c, dc, metal, m = p["rgba"], p["drawer_rgba"], p["handle_rgba"], p["masses"]
        post, post_y = p["handle_post_half"], p["handle_post_y"]
        drawer = [
            _Geom("drawer_front", (dt / 2, wy, hz), (-D / 2 + dt / 2, 0, zc), dc, m["drawer_front"]),
            _Geom("drawer_back", (dt / 2, wy, hz), (-D / 2 + dx - dt / 2, 0, zc), dc, m["drawer_back"]),
            _Geom("drawer_left", ((dx - 2 * dt) / 2, dt / 2, hz), (xc, wy - dt / 2, zc), dc, m["drawer_left"]),
            _Geom("drawer_right", ((dx - 2 * dt) / 2, dt / 2, hz), (xc, -(wy - dt / 2), zc), dc, m["drawer_right"]),
            _Geom("drawer_bottom", ((dx - 2 * dt) / 2, wy - dt, dt / 2), (xc, 0, zb + dt / 2), dc,
                  m["drawer_bottom"]),
            # The handle: a bar on two posts in front of the drawer's front, near its top.
            _Geom("handle_post_left", post, (-D / 2 - post[0], post_y, q["bar_z"]), metal, m["handle_post_left"]),
            _Geom("handle_post_right", post, (-D / 2 - post[0], -post_y, q["bar_z"]), metal,
                  m["handle_post_right"]),
            _Geom("handle_bar", p["handle_bar_half"], (q["bar_x"], 0, q["bar_z"]), metal, m["handle_bar"]),
        ]
        slide = _joint("slide", "slide", (-1, 0, 0), (0.0, p["travel"]), p["slide"])
        return _Design(_shell(D, q["W"], q["H"], q["t"], c, m), [_Part("drawer", (0, 0, 0), slide, drawer)])

    def _positions(self, p: dict) -> dict[str, Vec3]:
        q = self._geometry(p)
        bx, zc, bz, h = q["bar_x"], q["zc"], q["bar_z"], q["bar_h"]
        return {"handle": (bx, 0, bz), "handle_upper": (bx, 0, bz + h), "handle_lower": (bx, 0, bz - h),
                "front": (-q["D"] / 2, q["wy"] / 2, zc), "storage": (q["xc"], 0, q["zb"] + q["dt"] + 0.005),
                "head": (-q["D"] / 2, 0, bz)}

    def _articulation(self, p: dict) -> Articulation:
        return Articulation(joint="slide", closed=0.0, open=p["travel"])


# -- laptop ---------------------------------------------------------------------------------------------------
class LaptopFamily(_DataFamily):
    name = "laptop"
    Params = LaptopParams

    def _design(self, p: dict) -> _Design:
        D, W, hb, ts, m = p["depth"], p["width"], p["base_h"], p["screen_t"], p["masses"]
        base = [_Geom("base", (D / 2, W / 2, hb / 2), (0, 0, hb / 2), p["rgba"], m["base"])]
        screen = [_Geom("screen", (D / 2, W / 2, ts / 2), (-D / 2, 0, ts / 2), p["screen_rgba"], m["screen"])]
        hinge = _joint("hinge", "hinge", (0, 1, 0), (0.0, p["open_deg"] * _DEG), p["hinge"])
        return _Design(base, [_Part("screen", (D / 2, 0, hb), hinge, screen)])

    def _positions(self, p: dict) -> dict[str, Vec3]:
        D, hb, ts = p["depth"], p["base_h"], p["screen_t"]
        return {"screen_edge": (-D, 0, ts / 2), "screen_grip": (-D + p["grip_depth"], 0, ts / 2),
                "screen_back": (-0.85 * D, 0, ts), "screen_center": (-D / 2, 0, 0), "keyboard": (0, 0, hb)}

    def _articulation(self, p: dict) -> Articulation:
        return Articulation(joint="hinge", closed=0.0, open=p["open_deg"] * _DEG)


# -- box with a hinged lid ------------------------------------------------------------------------------------
class BoxFamily(_DataFamily):
    name = "box"
    Params = BoxParams

    def _design(self, p: dict) -> _Design:
        D, W, H, t, tl, tab = p["depth"], p["width"], p["height"], p["wall"], p["lid_thick"], p["tab_half"]
        c, lc, hw, m = p["rgba"], p["lid_rgba"], (H - t) / 2, p["masses"]
        walls = [
            _Geom("bottom", (D / 2, W / 2, t / 2), (0, 0, t / 2), c, m["bottom"]),
            _Geom("wall_front", (t / 2, W / 2, hw), (-(D / 2 - t / 2), 0, t + hw), c, m["wall_front"]),
            _Geom("wall_back", (t / 2, W / 2, hw), (D / 2 - t / 2, 0, t + hw), c, m["wall_back"]),
            _Geom("wall_left", (D / 2 - t, t / 2, hw), (0, W / 2 - t / 2, t + hw), c, m["wall_left"]),
            _Geom("wall_right", (D / 2 - t, t / 2, hw), (0, -(W / 2 - t / 2), t + hw), c, m["wall_right"]),
        ]
        lid = [_Geom("lid", (D / 2, W / 2, tl / 2), (-D / 2, 0, tl / 2), lc, m["lid"]),
               _Geom("lid_tab", (tab, 0.02, tl / 2 * 0.6), (-D - tab, 0, tl / 2), lc, m["lid_tab"])]
        hinge = _joint("hinge", "hinge", (0, 1, 0), (0.0, p["open_deg"] * _DEG), p["hinge"])
        return _Design(walls, [_Part("lid", (D / 2, 0, H), hinge, lid)])

    def _positions(self, p: dict) -> dict[str, Vec3]:
        D, tl, tab = p["depth"], p["lid_thick"], p["tab_half"]
        return {"lid_front": (-D - 2 * tab, 0, tl / 2), "lid_top": (-D + 0.015, 0, tl),
                "lid_grip": (-D - 2 * tab, 0, tl / 2 - p["grip_under"]),
                "lid_pinch": (-D - 2 * tab + p["pinch_in"], 0, tl / 2),
                "storage": (0, 0, p["wall"] + 0.005)}

    def _articulation(self, p: dict) -> Articulation:
        return Articulation(joint="hinge", closed=0.0, open=p["open_deg"] * _DEG)


# -- toaster --------------------------------------------------------------------------------------------------
class ToasterFamily(_DataFamily):
    name = "toaster"
    Params = ToasterParams

    def _lever_pos(self, p: dict) -> Vec3:
        return (-p["depth"] / 2 - p["lever_half"][0], p["width"] / 2 - 0.04, 0.8 * p["height"])

    def _design(self, p: dict) -> _Design:
        D, W, H, m = p["depth"], p["width"], p["height"], p["masses"]
        shell = [_Geom("body", (D / 2, W / 2, H / 2), (0, 0, H / 2), p["rgba"], m["body"])] + [
            _Geom(f"slot_{i}", (0.3 * D, 0.012, 0.002), (0, s * 0.04, H + 0.002), p["slot_rgba"], m[f"slot_{i}"])
            for i, s in enumerate((1, -1))
        ]
        lever = [_Geom("lever", p["lever_half"], (0, 0, 0), p["lever_rgba"], m["lever"])]
        slide = _joint("slide", "slide", (0, 0, -1), (0.0, p["travel"]), p["slide"])
        return _Design(shell, [_Part("lever", self._lever_pos(p), slide, lever)])

    def _positions(self, p: dict) -> dict[str, Vec3]:
        return {"lever_top": (0, 0, p["lever_half"][2]), "slot": (0, 0.04, p["height"] + 0.004)}

    def _articulation(self, p: dict) -> Articulation:
        return Articulation(joint="slide", closed=0.0, open=p["travel"])


ARTICULATED_FAMILIES: dict[str, ObjectFamily] = {
    f.name: f for f in (DrawerFamily(), LaptopFamily(), BoxFamily(), ToasterFamily())
}


# -- openness -------------------------------------------------------------------------------------------------
def openness_joint(model: mujoco.MjModel, body_name: str, ann: ObjectAnnotations) -> int:
    """The id of the object's articulation joint ("<body>_<joint>")."""
    if ann.articulation is None:
        raise ValueError(f"{ann.family}: the object has no articulation")
    return model.joint(f"{body_name}_{ann.articulation.joint}").id


def set_openness(model: mujoco.MjModel, data: mujoco.MjData, body_name: str, ann: ObjectAnnotations,
                 openness: float) -> None:
    """Put the articulation joint at `openness` (clipped to [0, 1]) with zero velocity, then mj_forward."""
    j = openness_joint(model, body_name, ann)
    data.qpos[model.jnt_qposadr[j]] = ann.articulation.joint_position(float(np.clip(openness, 0.0, 1.0)))
    data.qvel[model.jnt_dofadr[j]] = 0.0
    mujoco.mj_forward(model, data)


def get_openness(model: mujoco.MjModel, data: mujoco.MjData, body_name: str, ann: ObjectAnnotations) -> float:
    """The articulation joint's position as openness (0 closed, 1 open), clipped to [0, 1]."""
    j = openness_joint(model, body_name, ann)
    return ann.articulation.openness_of(float(data.qpos[model.jnt_qposadr[j]]))
