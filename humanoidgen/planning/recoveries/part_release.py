"""Letting go of an articulated part without undoing what the hand did to it.

A hand that moved a lid, a laptop screen or a knob to an openness has its fingers around the part; letting go,
they can drag it back. Measured on plans written outside the project (each the pinch or grasp, the move to an
openness, then `open_hand`): a laptop screen closed to 0.04 came back to 0.47 as the hand backed out, a box lid
turned shut to 0.00 came back to 0.40, a screen lifted to 0.86 fell to 0.74 (the open thumb behind it), a knob
turned to 96 deg came back to 88 (the curled middle finger, straightening). No one way out fits every grip.

So the ways out are tried in the simulation itself, from a snapshot, with nothing recorded: the usual one first
(unhook along the grip's attach axis, or back out the way the hand came in, opening on the way); then the fingers
loosened to the grip's "pre" posture (a pinch opens only thumb and index), or opened, where they are, and the hand
backed out the way in, off the part's edge away from its hinge, or along the hinge; then opened and backed out
straight up, up by a sampled path, the way the part went, or not at all. Each is judged once the trial has also
sent the hand home, as the plans do next (a hand left with a finger on a turned knob dragged it from 0.76 to 0.68
on its way home); the back-outs are planned with the fingers where they are (driven open against a door, the
commanded posture lies 2 cm inside it on the planner's model, and every way out looked blocked). The first that
leaves the part where it was, or further on the way the hand moved it (going back at most RELEASE_DRIFT), with the
hand off it runs for real, and only the way, not the trial's move home (letting go to grip again at once, the usual
way may leave the hand on it, and the hand does not go home); where none does, the one that lets it go back least.
The extra cost is one simulated release and move home where the usual way is fine.
"""

from __future__ import annotations

import logging
from collections.abc import Callable

import numpy as np

from humanoidgen.objects.describe import openness
from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.planning.arm_moves import RETREAT_DISTANCE
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.recovery import Recovery, ReleaseRequest
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.hand_ops import finger_contacts
from humanoidgen.planning.motion import MotionError, plan_arm_motion, time_dense_path
from humanoidgen.planning.paths import time_parametrize
from humanoidgen.planning.part_joint import (PartFollow, follow_articulation, follow_openness, hinge_line,
                                             hinge_through_hold, point_motion, stays_now)
from humanoidgen.planning.snapshot import take_snapshot, trial
from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.sim.layout import Side
from humanoidgen.sim.scene import SceneObject
from humanoidgen.planning import arm_moves
from humanoidgen.planning import finger_room
from humanoidgen.planning.hand_ops import is_part

log = logging.getLogger(__name__)

RELEASE_DRIFT = 0.02  # openness a part may go back while the hand lets go of it
TRIAL_SETTLE_S = 0.3  # after a way out is tried, the part is watched this long (a dragged lid swings on)
BACK_OUT_SPEED = 0.3  # rad/s, as the retreat after a release
# A grip slid off its part along the part's hinge goes this far, else the shorter (a pinch 6 mm in from a fin's
# outer face is clear of it after 3 cm; an arm reaching to a knob near its body has little room toward it).
SLIDE_OFF_M = (0.06, 0.04, 0.03)


class PartRelease(Recovery):
    stage = "release"
    trigger = "before"
    answers = "a hand lets go of an articulated part it moved (its fingers may drag the part back)"
    tries = ("each way out (unhook, back out, loosen, open and rise, ...) in a trial from a snapshot, judged "
             "after the move home; the first that leaves the part where it was runs for real")
    event = "letting go of <part>, the <side> hand <way> (the usual way moved it back <n>)"

    def applies(self, ctx: PlanningContext, request: ReleaseRequest, failure: Exception | None) -> bool:
        return is_part(request.held)

    def attempt(self, ctx: PlanningContext, request: ReleaseRequest, failure: Exception | None) -> bool:
        # A hooked handle: back away while the fingers open, so they do not push the part back.
        hand = ctx.hands[request.side]
        hand.held = None
        let_go(ctx, request.side, request.held, hand.take("part_moved"))
        return True  # released: the usual way is not taken


def let_go(ctx: PlanningContext, side: Side, part: SceneObject, follow: PartFollow | None) -> None:
    """Open `side`'s hand on `part` (no longer in `ctx.hands[side].held`) and move it off, the way that moves the part
    least (see the module's doc). Adds an event when the usual way was not the one taken."""
    measure = _openness_gauge(ctx, part, follow)
    before = measure()
    ways = _ways_out(ctx, side, part, follow)
    if before is None or falls_here(ctx, follow):
        # A part whose joint does not hold it where it is let go (a light lid low) falls whatever the way out: the
        # least drift was then the way that shoved it up to where it balances (a lid let go at 0.53 left at 0.63,
        # where a fingertip then came under it to flip it open and it fell to 0.39 in the push, open_box_hard
        # seeds 1, 3, 4, 7, 8 with the tab grasped under its tip). It is let go the usual way and falls, as the
        # family's description says.
        ways[0][1]()
        return
    # Only a part going back counts: one going on the way the hand moved it (a lid let go low falls shut, as a
    # plan may mean it to) is not undone. A part turned about an axis through the hold (a knob, by its fin) goes
    # on only where the fingers push it: that is an overshoot past the angle asked (a knob turned to 60 deg and
    # let go the usual way, the straightening index spun it on to 97-105), so there it counts both ways.
    onward = 0.0 if follow is None or _on_the_hinge(ctx, side, follow) else 1.0 if _opens(ctx, follow) else -1.0
    start = take_snapshot(ctx)
    tried: list[tuple[bool, float, int]] = []
    first_drift = None
    chosen = None
    for k, (_, way) in enumerate(ways):
        try:
            with trial(ctx, start):  # nothing of it is recorded
                way()
                ctx.settle(TRIAL_SETTLE_S)
                touching = bool(finger_contacts(ctx.env.model, ctx.env.data, side, part.body))
                if not ctx.regripping:
                    _leave(ctx, side)  # judged once the hand has gone, as the plan's next move takes it
                drift = max(0.0, (before - measure()) * onward) if onward else abs(measure() - before)
        except (MotionError, PlanningError) as exc:
            log.debug("letting go %s: no way (%s)", ways[k][0], exc)
            continue
        if k == 0:
            first_drift = drift
        log.debug("letting go %s: drift %.3f, %s", ways[k][0], drift, "touching" if touching else "off the part")
        tried.append((touching, drift, k))
        # A way that leaves the part where it was, off it. Letting go to grip again at once, the usual way may
        # leave the hand on it: leaving a screen where the arm's reach ends, off it, let it rise 0.56 -> 0.72
        # before the second grip. Letting go for good, the hand must be off it: left on the safe's door, the
        # plan's next move started in contact and found no path.
        if drift <= RELEASE_DRIFT and (not touching or (k == 0 and ctx.regripping)):
            chosen = tried[-1]
            break
    if not tried:
        ways[0][1]()
        return
    # Else, letting go for good, the least drift once the hand has gone home (a hand left on the part drags it
    # then: measured, a lid left pressed shut came back to 0.46); letting go to grip again, off the part first.
    key = (lambda t: t) if ctx.regripping else (lambda t: (t[1], t[0], t[2]))
    _, drift, k = chosen or min(tried, key=key)
    ways[k][1]()
    if k:
        usual = "" if first_drift is None else f" (backing out as usual: by {first_drift:.2f})"
        ctx.events.append(f"the {side} hand let go of {part.type_name} {part.obj_id} {ways[k][0]}, which let "
                              f"it go back by {drift:.2f} in openness{usual}")


def falls_here(ctx, follow: PartFollow | None) -> bool:
    """Whether the part `follow` moves would not stay where it is now if let go (its weight beats its joint's
    friction), as `part_joint.part_stays` judges it."""
    return follow is not None and not stays_now(ctx.env, follow)


def _leave(ctx, side: Side) -> None:
    """In a trial: the hand goes to its arm's init pose, as the paper's plans send a hand after letting go (any
    move away drags a part the fingers still rest on alike); where there is no way, it stays."""
    try:
        ctx.run_arm_samples({side: arm_moves.plan_side(ctx, side, ctx.init_poses[side])})
    except (MotionError, PlanningError):
        return
    ctx.settle(TRIAL_SETTLE_S)


def _openness_gauge(ctx, part: SceneObject, follow: PartFollow | None) -> Callable[[], float | None]:
    env = ctx.env
    if follow is not None and env.scene.object(*follow.obj).body == part.body:
        return lambda: follow_openness(env, follow)
    return lambda: openness(env.model, env.data, part)


def _ways_out(ctx, side: Side, part: SceneObject, follow: PartFollow | None) -> list[tuple[str, Callable[[], None]]]:
    """(how, do it) for each way of letting go, the usual one first."""
    def usual() -> None:
        if not finger_room.unhook(ctx, side, part, follow):
            arm_moves.retreat(ctx, side, open_fingers=True)

    def loosened_then(posture: str, direction: Callable[[], np.ndarray | None],
                      sampled: bool = False) -> Callable[[], None]:
        def go() -> None:
            finger_room.loosen_in_place(ctx, side)
            ctx.move_fingers((side,), posture)
            u = direction()
            if u is not None:
                _back_out(ctx, side, u, sampled)
            if posture != "open":
                ctx.move_fingers((side,), "open")
            ctx.hands[side].last_approach = None
        return go

    approach = ctx.hands[side].last_approach
    ways_back = {
        "backing out the way it came in": lambda: None if approach is None else -np.asarray(approach, float),
        "sliding off the part's edge, away from its hinge": lambda: _off_the_edge(ctx, side, follow),
        "backing out along the part's hinge": lambda: _hinge_away(ctx, side, part, follow),
    }
    def slid_off_along_hinge(loosen: str | None) -> Callable[[], None]:
        # Off the part's end along its own hinge: friction along the axis has no moment about it, so a knob's fin
        # slides out of the fingers unturned; opening on it instead (the thumb swinging, the curled fingers
        # straightening) spun a knob turned to 60 deg on to 97-105. The squeeze is first eased to the grip's
        # "pre" posture (a pinch: thumb and index only open, off the fin's faces).
        def go() -> None:
            u = _hinge_away(ctx, side, part, follow)
            if u is None:
                raise MotionError("the part has no hinge to slide off along")
            if loosen is not None:
                ctx.move_fingers((side,), loosen)
            m = ctx.env.model
            ignored = set(ctx.collisions.ignored_bodies)
            ctx.collisions.ignored_bodies.add(m.body(part.body).id)  # the fingers leave it: they touch it at first
            try:
                _back_out(ctx, side, u, distances=SLIDE_OFF_M)
            finally:
                ctx.collisions.ignored_bodies = ignored
            ctx.move_fingers((side,), "open")
            ctx.hands[side].last_approach = None
        return go

    pre = f"pre_{ctx.hands[side].grip or 'grasp'}"
    slide = []
    if _on_the_hinge(ctx, side, follow):  # a knob, turned about an axis through the fingers' hold
        slide = [(f"loosening to {pre}, then sliding off along the part's hinge", slid_off_along_hinge(pre))] \
            if pre in HAND_POSTURES else []
        slide.append(("sliding off along the part's hinge, the fingers still closed", slid_off_along_hinge(None)))
        if pre in HAND_POSTURES:
            # Where the arm has no room to slide off (a knob close to the body): only the squeeze let go, the
            # curled fingers kept curled (half opening them all first, as the ways below do, spun a knob 29 deg on)
            # and the hand left there; the plan's next move takes it away.
            slide.append((f"loosening to {pre} only and staying there",
                          lambda: (ctx.move_fingers((side,), pre), setattr(ctx.hands[side], "last_approach", None))))
    ways = [("as usual", usual), *slide]
    # The grip's own "pre" posture first (a pinch: only thumb and index open; the curled fingers, straightening,
    # would push the part): it leaves the part without sweeping it; the hand opens fully once off it.
    if pre in HAND_POSTURES:
        ways += [(f"loosening to {pre} first, then {how}", loosened_then(pre, way)) for how, way in ways_back.items()]
    ways += [(f"opening in place first, then {how}", loosened_then("open", way)) for how, way in ways_back.items()]
    ways += [("opening in place first, then backing out straight up",
              loosened_then("open", lambda: np.array([0.0, 0.0, 1.0]))),
             # An arm at its limits may find no straight way at all (a shoulder against the torso after reaching
             # across to shut a screen): any free path up, from the sampling planner.
             ("opening in place first, then rising by a planned path",
              loosened_then("open", lambda: np.array([0.0, 0.0, 1.0]), sampled=True))]
    if follow is not None:
        ways.append(("opening in place first, then backing out the way the part went",
                     loosened_then("open", lambda: _part_onward(ctx, follow))))
    ways.append(("opening in place and staying there", loosened_then("open", lambda: None)))
    return ways


def _back_out(ctx, side: Side, u: np.ndarray, sampled: bool = False,
              distances: tuple[float, ...] = (RETREAT_DISTANCE, RETREAT_DISTANCE / 2)) -> None:
    """Move the hand RETREAT_DISTANCE (else half that) along `u`, straight (`sampled`: by any free path to
    there); MotionError where neither is free."""
    kin = ctx.kin
    kin.sync(ctx.env.data.qpos)  # the fingers where they are: driven open against a door, the commanded
    # posture lies 2 cm inside it on the planner's model and every way out looked blocked (a turned knob, measured)
    try:
        p, R = kin.ee_pose(side)
        arm = kin.arms[side]
        q0 = np.clip(kin.arm_q(side), arm.lo, arm.hi)
        path, last = None, None
        for dist in distances:
            try:
                path = plan_arm_motion(kin, ctx.collisions, side, q0, (p + dist * np.asarray(u, float), R),
                                       allow_sampling=sampled, seed=ctx.seed, time_limit=2.0)
                break
            except MotionError as exc:
                last = exc
        if path is None:
            raise last
    finally:
        kin.sync(ctx.env.data.qpos)
    dt = 1.0 / ctx.env.control_hz
    if path.method == "rrt_connect":
        samples = time_parametrize(path.waypoints, dt=dt, v_max=BACK_OUT_SPEED)[1]
    else:
        samples = time_dense_path(path.waypoints, dt, v_max=BACK_OUT_SPEED)
    ctx.run_arm_samples({side: samples})


def _on_the_hinge(ctx, side: Side, follow: PartFollow | None) -> bool:
    """Whether the part's hinge passes near the hand's grip point (a knob's axis through the pinched fin; a lid's
    or a door's hinge is far from the hand on it)."""
    return follow is not None and hinge_through_hold(ctx.env, side, ctx.hands[side].grip, follow.joint)


def _hinge_away(ctx, side: Side, part: SceneObject, follow: PartFollow | None) -> np.ndarray | None:
    """The hinge axis of the part the hand moved (a safe's knob, not its door), signed from the part toward the
    hand (moving along it cannot turn the part); None for a slide."""
    m, d = ctx.env.model, ctx.env.data
    joint = follow.joint if follow is not None else f"{part.body}_{part.annotations.articulation.joint}"
    line = hinge_line(m, d, joint)
    if line is None:
        return None
    hinge, anchor = line
    ctx.kin.sync(d.qpos)
    p, _ = ctx.kin.ee_pose(side)
    return hinge if float((p - anchor) @ hinge) >= 0.0 else -hinge


def _off_the_edge(ctx, side: Side, follow: PartFollow | None) -> np.ndarray | None:
    """From the hinge axis of the part the hand moved out to the grip point, across the axis: the way off the
    part's edge (a thumb under a shut screen's edge, fingers around a knob's fin); None for a slide or without a
    hinge."""
    if follow is None:
        return None
    line = hinge_line(ctx.env.model, ctx.env.data, follow.joint)
    if line is None:
        return None
    hinge, anchor = line
    obj = ctx.env.scene.object(*follow.obj)
    grip = get_point_in_env(ctx.env, follow.part_point, obj.type_name, obj.obj_id)
    out = grip - anchor
    out = out - (out @ hinge) * hinge
    n = float(np.linalg.norm(out))
    return out / n if n > 1e-3 else None


def _opens(ctx, follow: PartFollow) -> bool:
    """Whether the hand's move opened the part: moves toward high openness open, toward low openness close."""
    return follow_articulation(ctx.env, follow).openness_of(follow.q_target) >= 0.5


def _part_onward(ctx, follow: PartFollow) -> np.ndarray | None:
    """The way the grip point went as the hand moved the part (toward the openness asked); at the part's end stop,
    on the same way (into the stop)."""
    step = 0.02 if _opens(ctx, follow) else -0.02
    u = point_motion(ctx.env, follow, step)
    if np.linalg.norm(u) == 0:
        u = -point_motion(ctx.env, follow, -step)
    return u if np.linalg.norm(u) > 0 else None
