"""Room for the fingers: a change of finger posture that would strike something moves the hand off first.

This hand's posture changes are no small motions: from a pinch to open the thumb swings about 1.3 rad of yaw
and the curled fingers straighten, a sweep of 6-8 cm; to a pre-pinch the middle, ring and pinky curl 1.4 rad.
Two measured failures of plans written elsewhere came from such sweeps, never checked before:
- after a mid-air hand-over, the hand that let go backed out sideways to the long block and, opening, swung its
  thumb back into it: the other hand's pinch fell from 3.6 N to 1.2 N and the block dropped on the next move;
- a hand that had just let go of a drawer's handle curled its fingers for a pinch onto the drawer's front, and
  its next move dragged the open drawer from openness 0.82 to 0.20.
So the sweep is checked on the planner's kinematics first. A hand that let go of an object keeps a clearance
from it while it opens; an empty hand whose new posture would push into anything backs off first (on along the
way it came out, straight up, or away from what it would strike), changes posture there, and comes back to where
it was if the way back is clear with the new posture (so a plan that set the hand at a grip pose still finds it
there).
"""

from __future__ import annotations

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.objects.queries import get_axis_in_env
from humanoidgen.planning.collision import FAR, CollisionWorld
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.planning.motion import MotionError, first_collision, plan_arm_motion, time_dense_path
from humanoidgen.planning.part_joint import PartFollow, follow_openness, point_motion
from humanoidgen.sim.action import ARM_SLICE, HAND_SLICE
from humanoidgen.sim.layout import Side
from humanoidgen.sim.scene import SceneObject
from humanoidgen.planning.context import PlanningContext

UNHOOK_M = (0.03, 0.06)  # a hand letting go of a handle moves this far along its grip's attach axis: opening, then on
UNHOOK_MAX_COS = 0.5  # ... only where that axis is at least 60 deg off the way the part moves there
UNHOOK_BACK_M = 0.03  # ... and this far back out along its approach on the second leg
RELEASE_IN_PLACE_S = 0.3  # letting go of a part: the fingers first half open this long, the arm still
OPEN_CLEARANCE_M = 0.01  # a hand opening after it let go keeps at least this far from what it let go of
PUSH_TOL_M = 0.002  # an empty hand's new posture may come this much deeper into something than it is now
SWEEP_SAMPLES = 8  # finger postures checked between the current one and the new one
BACK_OFF_M = (0.05, 0.10)  # moves tried to give the fingers room
BACK_OFF_SPEED = 0.3  # rad/s, as the retreat after a release


def finger_sweep_clearance(kin: Kinematics, collisions: CollisionWorld, side: Side, start: np.ndarray,
                           goal: np.ndarray, obstacle_geoms: np.ndarray | list[int]) -> tuple[float, int | None]:
    """Smallest distance between `side`'s finger geoms and `obstacle_geoms` while the fingers move from posture
    `start` to `goal` (linearly, as the planner moves them), the arm where `kin` has it; and the nearest obstacle
    geom. Leaves the hand at `start`."""
    fingers = collisions.finger_geoms(side)
    best, nearest = FAR, None
    if not len(obstacle_geoms):
        return best, nearest
    try:
        for k in range(SWEEP_SAMPLES + 1):
            kin.set_hand(side, start + (goal - start) * k / SWEEP_SAMPLES)
            kin.forward()
            d, pair = collisions.closest_pair(fingers, obstacle_geoms)
            if d < best:
                best, nearest = d, pair[1]
    finally:
        kin.set_hand(side, start)
        kin.forward()
    return best, nearest


def back_off_directions(away: np.ndarray | None, hand_point: np.ndarray, from_point: np.ndarray) -> list[np.ndarray]:
    """Unit directions to give a hand room, best first: on along `away` (the way it backed out), straight up,
    and horizontally away from `from_point` (what it would strike)."""
    out: list[np.ndarray] = []
    flat = np.asarray(hand_point, float) - np.asarray(from_point, float)
    flat[2] = 0.0
    for v in (away, np.array([0.0, 0.0, 1.0]), flat):
        if v is None:
            continue
        n = float(np.linalg.norm(v))
        if n < 1e-6:
            continue
        u = np.asarray(v, float) / n
        if all(float(u @ w) < 0.95 for w in out):
            out.append(u)
    return out



def open_clear_of(ctx: PlanningContext, released: list[tuple[Side, SceneObject, np.ndarray | None]]) -> None:
    """Open the hands that let go of rigid objects (side, object, the way the hand backed out), each clear of
    what it let go of; a hand that finds no room stays as it is, with an event."""
    m = ctx.env.model
    opening = []
    for side, obj, away in released:
        geoms = sorted(ctx.collisions.body_geoms(m.body(obj.body).id))
        where = room_for(ctx, side, "open", geoms, OPEN_CLEARANCE_M, away, come_back=False)
        if where is None:
            ctx.events.append(f"the {side} hand stayed half open: opening it would strike {obj.type_name} "
                               f"{obj.obj_id}")
            continue
        if where:
            ctx.events.append(f"the {side} hand {where} from {obj.type_name} {obj.obj_id} before "
                               "opening, so that its fingers would not strike it")
        opening.append(side)
    if opening:
        ctx.move_fingers(tuple(opening), "open", seconds=0.5)

def posture_with_room(ctx: PlanningContext, sides: tuple[Side, ...], posture: str) -> None:
    """Change empty hands' finger posture where the fingers do not push into anything (hands that hold
    something change in place: their fingers are meant to touch it)."""
    in_place = []
    for side in sides:
        if ctx.hands[side].held is not None:
            in_place.append(side)
            continue
        ctx.kin.sync(ctx.env.data.qpos)
        obstacles = ctx.collisions.obstacles(side)
        ctx.kin.set_hand(side, ctx.action[HAND_SLICE[side]])  # the posture the fingers are driven to now
        ctx.kin.forward()
        current, _ = ctx.collisions.closest_pair(ctx.collisions.finger_geoms(side), obstacles)
        floor = min(current, 0.0) - PUSH_TOL_M
        where = room_for(ctx, side, posture, obstacles, floor, None, come_back=True)
        if where is None:
            ctx.events.append(f"the {side} hand changed to {posture} where it was, pushing against what is "
                               "next to its fingers (no room found to back off)")
        elif where:
            ctx.events.append(f"the {side} hand {where} to change to {posture} without pushing what is next "
                               "to its fingers")
            continue  # changed on the way
        in_place.append(side)
    if in_place:
        ctx.move_fingers(tuple(in_place), posture)

def room_for(ctx: PlanningContext, side: Side, posture: str, obstacle_geoms, clearance: float, away: np.ndarray | None,
              come_back: bool) -> str | None:
    """Make room for `side`'s fingers to move to `posture` keeping `clearance` from `obstacle_geoms`: "" if
    there is room where the hand is, a description of the move that made room, or None if none was found.
    The posture itself is not changed here, except on a way back (`come_back`), where the hand changes it
    before returning."""
    goal = np.array(HAND_POSTURES[posture])
    start = ctx.action[HAND_SLICE[side]].copy()
    ctx.kin.sync(ctx.env.data.qpos)
    sweep, nearest = finger_sweep_clearance(ctx.kin, ctx.collisions, side, start, goal, obstacle_geoms)
    if sweep >= clearance:
        return ""
    p, R = ctx.kin.ee_pose(side)
    arm = ctx.kin.arms[side]
    q0 = np.clip(ctx.kin.arm_q(side), arm.lo, arm.hi)
    struck = ctx.kin.data.geom_xpos[nearest].copy() if nearest is not None else p
    for dist in BACK_OFF_M:
        for u in back_off_directions(away, p, struck):
            try:
                path = plan_arm_motion(ctx.kin, ctx.collisions, side, q0, (p + dist * u, R), allow_sampling=False)
                ctx.kin.set_arm(side, path.waypoints[-1])
                ctx.kin.forward()
                clear, _ = finger_sweep_clearance(ctx.kin, ctx.collisions, side, start, goal, obstacle_geoms)
            except MotionError:
                continue
            finally:
                ctx.kin.sync(ctx.env.data.qpos)
            if clear < clearance:
                continue
            ctx.run_arm_samples({side: timed(ctx, path.waypoints)})
            how = f"moved {dist * 100:.0f} cm away"
            if come_back:
                how += change_on_the_way_back(ctx, side, posture, path.waypoints[::-1])
            return how
    return None

def change_on_the_way_back(ctx: PlanningContext, side: Side, posture: str, way_back: np.ndarray) -> str:
    """Change posture where the hand made room, then return along `way_back` if that is clear with the new
    posture; says which."""
    ctx.move_fingers((side,), posture)
    ctx.kin.sync(ctx.env.data.qpos)
    try:
        ctx.kin.set_hand(side, np.array(HAND_POSTURES[posture]))
        ctx.kin.forward()
        blocked = first_collision(ctx.kin, ctx.collisions, side, way_back) is not None
    finally:
        ctx.kin.sync(ctx.env.data.qpos)
    if blocked:
        return " and stayed there (the way back is blocked with the fingers so)"
    ctx.run_arm_samples({side: timed(ctx, way_back)})
    return " and came back"

def loosen_in_place(ctx: PlanningContext, side: Side) -> None:
    """Half open `side`'s fingers over RELEASE_IN_PLACE_S, the arm still: a grip on a part loosens before
    the hand moves away (moving with the fingers still around a handle drags the part along)."""
    start, goal = ctx.action[HAND_SLICE[side]].copy(), np.array(HAND_POSTURES["open"])
    n = int(round(RELEASE_IN_PLACE_S * ctx.env.control_hz))
    for k in range(1, n + 1):
        ctx.action[HAND_SLICE[side]] = start + (goal - start) * 0.5 * k / n
        ctx.step()

def timed(ctx: PlanningContext, waypoints: np.ndarray) -> np.ndarray:
    return time_dense_path(waypoints, 1.0 / ctx.env.control_hz, v_max=BACK_OFF_SPEED)

def unhook(ctx: PlanningContext, side: Side, part: SceneObject, follow: PartFollow | None) -> bool:
    """Let go of a handle the hand moved its part by, along the grip's attach axis: the fingers open while the
    hand moves UNHOOK_M[0] along it, then it goes on UNHOOK_M[1] along it and UNHOOK_BACK_M back. Backing
    straight out instead, the fingertips behind the bar drag the part back (measured: a drawer just pushed
    shut by its handle came back to openness 0.67 as the open hand backed 10 cm out; along the attach axis it
    stayed at 0.00). False (nothing done) without an attach axis or a free way."""
    if follow is None or not follow.unhook_axis or ctx.env.scene.object(*follow.obj).body != part.body:
        return False
    u = get_axis_in_env(ctx.env, follow.unhook_axis, obj_type=part.type_name, obj_id=part.obj_id)
    # Either way along the part's arc (only the angle to it counts): a step into the range it has.
    motion = point_motion(ctx.env, follow, 0.02 if follow_openness(ctx.env, follow) < 0.5 else -0.02)
    if abs(float(u @ motion)) > UNHOOK_MAX_COS:
        return False  # along the attach axis the hand would push the part itself (a lid near shut)
    back = ctx.hands[side].last_approach
    m = ctx.env.model
    ignored = set(ctx.collisions.ignored_bodies)
    ctx.collisions.ignored_bodies.add(m.body(part.body).id)  # the fingers leave it: they touch it at first
    try:
        ctx.kin.sync(ctx.env.data.qpos)
        ctx.kin.set_hand(side, np.array(HAND_POSTURES["open"]))
        ctx.kin.forward()
        p, R = ctx.kin.ee_pose(side)
        arm = ctx.kin.arms[side]
        q0 = np.clip(ctx.kin.arm_q(side), arm.lo, arm.hi)
        first = plan_arm_motion(ctx.kin, ctx.collisions, side, q0, (p + UNHOOK_M[0] * u, R), allow_sampling=False)
        p2 = p + UNHOOK_M[1] * u - (UNHOOK_BACK_M * np.asarray(back, float) if back is not None else 0.0)
        second = plan_arm_motion(ctx.kin, ctx.collisions, side, first.waypoints[-1], (p2, R), allow_sampling=False)
    except MotionError:
        return False
    finally:
        ctx.collisions.ignored_bodies = ignored
        ctx.kin.sync(ctx.env.data.qpos)
    goal = np.array(HAND_POSTURES["open"])
    loosen_in_place(ctx, side)  # the grip's squeeze off the bar first
    start = ctx.action[HAND_SLICE[side]].copy()
    opening = timed(ctx, first.waypoints)
    n = max(len(opening), int(round(0.5 * ctx.env.control_hz)))
    for k in range(n):
        ctx.action[ARM_SLICE[side]] = opening[min(k, len(opening) - 1)]
        ctx.action[HAND_SLICE[side]] = start + (goal - start) * (k + 1) / n
        ctx.step()
    ctx.run_arm_samples({side: timed(ctx, second.waypoints)})
    ctx.hands[side].last_approach = None
    ctx.events.append(f"the {side} hand let go of {part.type_name} {part.obj_id} along its grip's attach axis "
                       f"({follow.unhook_axis}), off the handle")
    return True
