"""Where and how a held object is set down by the "move" action: the orientation it goes down in and the height it
is let go at.

- Standing it back up: an object the hand holds tilted (a block turned on its side for a hand-over) is stood on a
  face it can rest on before it is set on another object; the end the hand holds goes up (the hand stays above it).
  A face it can rest on is a "rest" function of its annotations (a long block: either end); without one, its
  bottom. Into a container (an object with a "storage" function) it goes as it is.
- Setting it down level: a slender object tilted a little in the hand (it swung in the grip) is set down with its z axis
  vertical where the hand can turn so (the ways as it is held follow as alternatives): let go tilted onto a small
  support, it lands on an edge and may topple off.
- Release clearance: a goal that puts the held object's lowest corner into (or onto) what is under it, the table
  or an object below, is raised so that it ends RELEASE_CLEARANCE_M above it (the paper: "release it slightly above
  the target position"); an event says by how much.
- Coming down: a goal within SET_DOWN_M of what is under it is come to from above (the approach axis is down),
  and open_hand backs the hand out upward; crossing at the goal's height, the object sweeps what stands there.
- Turning about the vertical: a held object whose footprint is the same turned by a quarter turn (a cube) may be
  set down with the hand turned by a quarter turn about the vertical, so that the fingers are not between it and
  a neighbour it is set down against; where no way reaches low enough, it is let go up to RAISED_RELEASE_M higher.
  These are the move's alternatives, tried in that order (an event names the one taken).
- Lifting before turning (arm_moves): a standing object the hand is to turn is first lifted straight up.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.sim.geometry import axis_angle_mat
from humanoidgen.sim.layout import TABLE_TOP_Z, Side
from humanoidgen.sim.scene import SceneObject

STAND_TILT_DEG = 30.0  # a held object tilted more than this from its upright is stood back up to be set down
# A held object tilted more than LEVEL_TILT_DEG (it swung in the grip as it was lifted) is set down with its z axis
# within LEVEL_WITHIN_DEG of the vertical where the hand can turn so: a 3x3x8 cm block let go on a 4 cm cube 9-10
# deg off upright landed on its edge and stood back up or toppled off by chance (2 mm of robot height decided it).
# Only slender objects (standing at least SLENDER times as tall as their narrower side) are levelled: they tip over
# at a small angle (the 3x3x8 cm block at 21 deg); a cube let go a few degrees off lands on a face and settles, and
# levelling its set-down costs the ways beside a neighbour their reach (pyramid_stack 19 -> 10/20).
LEVEL_TILT_DEG = 3.0
LEVEL_WITHIN_DEG = 2.0
SLENDER = 1.5
RELEASE_CLEARANCE_M = 0.006  # the held object's lowest corner ends this far above what it is set down on
# A goal that would let the held object go less than this above what is under it is lowered to the clearance: let go
# 2 cm above two bases, a pyramid's top cube dropped, tipped into the gap between them and ended 1.2 cm further off.
DROP_LIMIT_M = 0.03
# An object is under the goal when the footprints (world boxes) overlap by more than this and by more than this share
# of the narrower one, along x and y: a neighbour set down against (a tilted box's footprint grows) is not under it.
SUPPORT_OVERLAP_M = 0.005
SUPPORT_SHARE = 0.25
# Where the hand cannot set the object down that low (its fingers in a neighbour), it lets go this much higher.
RAISED_RELEASE_M = (0.015, 0.03)  # higher, a cube dropped beside another tips over
SQUARE_TOL_M = 0.002  # footprint sides equal within this: a quarter turn about the vertical changes nothing
# A goal this near what is under it sets the object down: the hand comes to it from above, over the approach's last
# centimetres (crossing at the goal's height, the object would sweep whatever stands beside the place, e.g. a stack).
SET_DOWN_M = 0.05
UP = np.array([0.0, 0.0, 1.0])
DOWN = -UP


def _corners(obj: SceneObject) -> np.ndarray:
    lo, hi = np.asarray(obj.annotations.bbox_min), np.asarray(obj.annotations.bbox_max)
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])


def object_pose(env, obj: SceneObject) -> tuple[np.ndarray, np.ndarray]:
    """The object's position and rotation matrix now."""
    bid = env.model.body(obj.body).id
    return env.data.xpos[bid].copy(), env.data.xmat[bid].reshape(3, 3).copy()


def is_container(obj: SceneObject) -> bool:
    return obj.annotations is not None and any(f.function == "storage" for f in obj.annotations.functions)


def stand_up_directions(env, side: Side, obj: SceneObject, rel: SceneObject | None) -> list[np.ndarray] | None:
    """World directions for the held object's own z axis to set it down standing, the one that keeps the hand
    above it first; None when it is upright enough already or goes into a container as it is."""
    z_now = get_axis_in_env(env, "z", obj_type=obj.type_name, obj_id=obj.obj_id)
    if obj.annotations is None or float(z_now @ UP) >= np.cos(np.radians(STAND_TILT_DEG)):
        return None
    if rel is not None and is_container(rel):
        return None
    rests = [f for f in obj.annotations.functions if f.function == "rest"]
    # Resting on the face whose outward normal is `axis`, that axis points down; only faces across z are used.
    signs = [-float(np.sign(obj.annotations.axis(f.axis).direction[2])) for f in rests
             if abs(obj.annotations.axis(f.axis).direction[2]) > 0.99] or [1.0]
    centre = get_point_in_env(env, "center", obj.type_name, obj.obj_id)
    grip = get_point_in_env(env, f"pinch_point_base_{side}_hand")
    held_end = float(np.sign((grip - centre) @ z_now)) or 1.0  # +1: the hand is at the object's +z end
    ordered = sorted(dict.fromkeys(signs), key=lambda s: s != held_end)  # that end up first
    return [s * UP for s in ordered]


def level_direction(env, obj: SceneObject, rel: SceneObject | None) -> np.ndarray | None:
    """The vertical the held object's z axis is turned to for setting it down level (the end up now stays up);
    None where it is level enough, is no slender object, is to be stood up (`stand_up_directions`) or goes into
    a container as it is."""
    z_now = get_axis_in_env(env, "z", obj_type=obj.type_name, obj_id=obj.obj_id)
    cos = abs(float(z_now @ UP))
    if obj.annotations is None or (rel is not None and is_container(rel)):
        return None
    size = np.asarray(obj.annotations.bbox_max) - np.asarray(obj.annotations.bbox_min)
    if size[2] < SLENDER * min(size[0], size[1]):
        return None
    if cos >= np.cos(np.radians(LEVEL_TILT_DEG)) or cos < np.cos(np.radians(STAND_TILT_DEG)):
        return None
    return float(np.sign(z_now @ UP)) * UP


def lowest_offset(obj: SceneObject, R: np.ndarray) -> float:
    """How far the object's lowest bbox corner is below its centre, in orientation R."""
    return float(-(_corners(obj) @ R.T)[:, 2].min())


def highest_offset(obj: SceneObject, R: np.ndarray) -> float:
    """How far the object's highest bbox corner is above its centre, in orientation R."""
    return float((_corners(obj) @ R.T)[:, 2].max())


def _centre_over(obj: SceneObject, c: np.ndarray, Ro: np.ndarray, goal: np.ndarray) -> bool:
    """Whether `goal` lies over the object's footprint (its own horizontal axes, not the world box)."""
    lo, hi = np.asarray(obj.annotations.bbox_min), np.asarray(obj.annotations.bbox_max)
    local = Ro.T @ (np.asarray(goal, float) - c)
    return bool(np.all(local[:2] >= lo[:2]) and np.all(local[:2] <= hi[:2]))


def support_below(env, obj: SceneObject, goal: np.ndarray, R: np.ndarray, centred: bool = False) -> tuple[float, str]:
    """The height of what the held object would rest on with its centre at `goal` in orientation R: the table or
    the top of an object whose footprint is under it (containers excepted: things go down into them). `centred`:
    only an object the centre is over counts (one whose corner the held object's corner overlaps is beside it)."""
    pts = _corners(obj) @ R.T + goal
    lo, hi = pts[:, :2].min(0), pts[:, :2].max(0)
    best, what = TABLE_TOP_Z, "the table"
    for o in env.scene.objects:
        if o is obj or o.annotations is None or is_container(o):
            continue
        c, Ro = object_pose(env, o)
        opts = _corners(o) @ Ro.T + c
        olo, ohi = opts[:, :2].min(0), opts[:, :2].max(0)
        overlap = np.minimum(hi, ohi) - np.maximum(lo, olo)
        need = np.maximum(SUPPORT_OVERLAP_M, SUPPORT_SHARE * np.minimum(hi - lo, ohi - olo))
        top = float(c[2] + highest_offset(o, Ro))
        if centred and not _centre_over(o, c, Ro, goal):
            continue
        if np.all(overlap > need) and top > best and top < goal[2]:
            best, what = top, f"{o.type_name} {o.obj_id}"
    return best, what


def height_above(env, obj: SceneObject, centre: np.ndarray, R: np.ndarray) -> float:
    """How far the object's lowest corner would be above what is under it, with its centre at `centre`."""
    support, _ = support_below(env, obj, centre, R)
    return float(centre[2] - lowest_offset(obj, R) - support)


def height_above_support(env, obj: SceneObject) -> float:
    """How far the object's lowest corner is above what is under it now."""
    return height_above(env, obj, *object_pose(env, obj))


def release_lift(env, obj: SceneObject, goal: np.ndarray, R: np.ndarray,
                 centred: bool = False) -> tuple[np.ndarray, str | None]:
    """The goal moved up or down so that the held object ends RELEASE_CLEARANCE_M above its support, and a note
    saying so (None when it is left as it is). Up where it would reach into the support; down where it would be
    let go less than DROP_LIMIT_M above it (a plan's "a little above" is a drop otherwise); higher goals are
    where the plan wants the object held, and stay."""
    support, what = support_below(env, obj, goal, R, centred)
    bottom = goal[2] - lowest_offset(obj, R)
    lift = support + RELEASE_CLEARANCE_M - bottom
    if -DROP_LIMIT_M < lift < -1e-3:
        out = goal.copy()
        out[2] += lift
        return out, (f"{obj.type_name} {obj.obj_id}'s goal lowered {-lift * 1000:.0f} mm, to be set down "
                     f"{RELEASE_CLEARANCE_M * 1000:.0f} mm above {what} rather than dropped onto it")
    if lift <= 1e-4:
        return goal, None
    out = goal.copy()
    out[2] += lift
    return out, (f"{obj.type_name} {obj.obj_id}'s goal raised {lift * 1000:.0f} mm: there it would reach into "
                 f"{what}; it is let go {RELEASE_CLEARANCE_M * 1000:.0f} mm above it")


def quarter_turn_symmetric(obj: SceneObject) -> bool:
    """Whether a quarter turn about its own z leaves the object's footprint as it is (a cube, a round body)."""
    if obj.annotations is None:
        return False
    size = np.asarray(obj.annotations.bbox_max) - np.asarray(obj.annotations.bbox_min)
    return abs(size[0] - size[1]) <= SQUARE_TOL_M


def turned_about_vertical(axis_now: np.ndarray, turn_deg: float) -> np.ndarray:
    """A hand axis as it would be after the hand turned `turn_deg` about the vertical."""
    return axis_angle_mat(UP, np.radians(turn_deg)) @ axis_now


def turning(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The smallest rotation taking unit vector a onto unit vector b."""
    axis = np.cross(a, b)
    n = float(np.linalg.norm(axis))
    if n < 1e-6:
        if a @ b > 0:
            return np.eye(3)
        axis = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
        return axis_angle_mat(axis, np.pi)
    return axis_angle_mat(axis / n, float(np.arctan2(n, a @ b)))
