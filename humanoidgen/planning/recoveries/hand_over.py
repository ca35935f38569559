"""A hand-over in mid-air: the hand that gives lets go only once the hand that takes holds the object alone.

The taking hand closes on the object while the giving hand still holds it, so `hand_pinch` sees thumb and a
finger touching and calls it a hold; whether it is one shows only when the giver opens. Measured on the paper
authors' hand-over plans (handover_and_storage seed 0, _cooperation seed 2): the left hand's pinch of the block's
free end stopped short, the thumb 1 cm from the end and the index on the next face, and the block fell to the
table the moment the right hand opened; the plan failed two moves later with "slipped 392 mm".

So before the giver lets go, that is tried in the simulation from a snapshot, with nothing recorded: the giver
loosens, backs out and opens as `open_hand` does, and the object must stay in the taker's fingers. Where it would
fall, the taker loosens, goes deeper along the way it came in (REGRIP_DEPTHS) and closes again, and the release is
tried once more (all of it a trial); the first deeper grip that holds alone is then taken for real, with an event.
A pinch holds alone only between thumb and index (`hand_ops.is_pinched`), and where no deeper one does, grips
further out are tried: measured on handover_and_storage_cooperation (alt_folder seeds 0 and 1), the left hand's
pinch of the block's free end sat so deep that it touched the tucked middle finger; once the giver had let go the
block turned onto thumb and middle, the index off it, and fell on the carry into the drawer. Taken again 6 mm
further out it stayed between thumb and index through the carry.
Where none does and in the trial the object fell out of the taker's fingers, the giver keeps it: open_hand fails
with what the trial showed and what to do instead (measured, bottle_handover: the left hand's pinch of a 0.2 kg
bottle's neck, where its whole-hand grasp did not fit beside the right hand's, let the bottle fall 10 cm the moment
the right hand opened; the plan went on and failed at the next move with "slipped 236 mm"). Where the object only
shifted in the fingers, the plan goes on as asked, with an event.

The trial opens the giver as open_hand does (clear of the object, or not at all) and watches the object with the
giver's hand kept off it for HOLD_S: a giver that cannot open clear of it bears part of its weight until it leaves,
and a grip that holds only with that help gives way a second later (bottle_handover: the left hand's grip of a bottle's shoulder slid off it on the giver's way home). Where
neither deeper nor further out holds, a grip the hand has a firmer closing for is closed firmer
(`objects.hands.firmer`).
"""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np

from humanoidgen.objects.hands import HAND_POSTURES, firmer
from humanoidgen.planning.hand_ops import finger_contacts, hand_part, is_held, is_part, is_pinched
from humanoidgen.planning.motion import MotionError, plan_arm_motion, time_dense_path
from humanoidgen.planning.context import PlanningContext
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.recovery import Recovery, ReleaseRequest
from humanoidgen.planning.snapshot import trial
from humanoidgen.sim.layout import OTHER_SIDE, Side
from humanoidgen.sim.scene import SceneObject
from humanoidgen.planning import back_away, finger_room

TRIAL_S = 0.4  # after the giver let go, the object is watched this long ...
DROP_M = 0.01  # ... and one that moved this far from the taking hand by then is not held by it
HOLD_S = 2.0  # it is watched on until this long after ...
FALL_M = 0.03  # ... and one that moved this far by then fell out of the taker's fingers
AWAY_BIT = 1 << 30  # a contact bit no geom uses: the object's, while the giver's hand is kept off it
REGRIP_DEPTHS = (0.006, 0.012, -0.006, -0.012)  # along the taker's way in (negative: further out), in turn
DEEPER_SPEED = 0.1  # m/s, the taker's short move in


class HandOverTrial(Recovery):
    stage = "release"
    trigger = "before"
    answers = "a hand lets go of an object the other hand also holds (a hand-over)"
    tries = ("the release in a trial from a snapshot; where the object would fall (a pinch: not between thumb and "
             "index), the taker closes deeper or further out "
             f"({', '.join(f'{d * 1000:+.0f}' for d in REGRIP_DEPTHS)} mm) and the release is tried again")
    event = "the <taker> hand's <grip> would not hold <object> alone: it took it again <n> mm deeper (or further out)"

    def applies(self, ctx: PlanningContext, request: ReleaseRequest, failure: Exception | None) -> bool:
        held, other = request.held, OTHER_SIDE[request.side]
        return (held is not None and held.annotations is not None and not is_part(held)
                and ctx.hands[other].held is held and other not in request.releasing)

    def attempt(self, ctx: PlanningContext, request: ReleaseRequest, failure: Exception | None) -> bool:
        secure_taker(ctx, request.side, request.held)
        return False  # the release itself goes on as usual


def holds_alone(ctx: PlanningContext, giver: Side, taker: Side, obj: SceneObject) -> bool:
    """Whether `taker` keeps `obj` once `giver` loosens its grip (tried from a snapshot; the state is restored).
    A pinch keeps it only between thumb and index (`hand_ops.is_pinched`): thumb and middle alone, the index
    off the object once the giver let go, held still but dropped the block on the carry that followed."""
    moved, touched = _release_outcome(ctx, giver, taker, obj)
    held = is_pinched(touched) if ctx.hands[taker].grip == "pinch" else is_held(touched)
    return moved <= DROP_M and held


def release_trial(ctx: PlanningContext, giver: Side, taker: Side, obj: SceneObject) -> tuple[float, bool]:
    """How far `obj` moves in `taker`'s hand once `giver` lets go, and whether `taker` still holds it then (tried
    from a snapshot; the state is restored)."""
    moved, touched = _release_outcome(ctx, giver, taker, obj)
    return moved, is_held(touched)


def _release_outcome(ctx: PlanningContext, giver: Side, taker: Side, obj: SceneObject) -> tuple[float, set[str]]:
    """How far `obj` moves in `taker`'s hand once `giver` lets go, and which of `taker`'s fingers touch it then."""
    env = ctx.env
    before = _in_hand(ctx, taker, obj)
    with trial(ctx):
        # As open_hand lets go: loosen, back out the way it came in, open.
        ctx.move_fingers((giver,), f"pre_{ctx.hands[giver].grip or 'pinch'}")
        ctx.hands[giver].held = None
        ctx.kin.detach(giver)
        ctx.settle(0.3)
        axis = ctx.hands[giver].last_approach
        back_away.retreat_from(ctx, giver, obj)
        # and opens as open_hand does: clear of the object, or not at all (opened where it is, a half-open
        # giver's fingers swept into a bottle and pressed it into the taker's hand, holding it up)
        finger_room.open_clear_of(ctx, [(giver, obj, None if axis is None else -np.asarray(axis, float))])
        # Watched with the giver's hand no longer touching the object: a giver that cannot open clear of the
        # object (a thumb three quarters round a bottle) still bore part of its weight in the trial, and the
        # object slid out of the taker's fingers once the giver went (bottle_handover, both_hands_all seed 0:
        # 3 mm in the trial, "slipped 231 mm" on the giver's way home, its hand off the bottle after 0.3 s).
        # Such a grip gives way only after a while (there: 13 mm at 0.8 s, 50 mm at 1 s), so it is watched
        # HOLD_S; a grip that holds still creeps a few mm in that time (the shoulder grip that held on every
        # carry: 6-11 mm in 2 s).
        with _hand_away(env.model, giver, obj.body):
            ctx.settle(TRIAL_S)
            moved = float(np.linalg.norm(_in_hand(ctx, taker, obj) - before))
            ctx.settle(HOLD_S - TRIAL_S)
            late = float(np.linalg.norm(_in_hand(ctx, taker, obj) - before))
        return (moved if late <= FALL_M else late), finger_contacts(env.model, env.data, taker, obj.body)


@contextmanager
def _hand_away(model, side: Side, body: str):
    """`side`'s hand and the object `body` do not touch while inside; each touches all else as before (the taker's
    fingers still rest on the giver's where they did: a block pinched between them fell in the trial when the
    giver's hand was taken out of every contact, and held in the real hand-over). The object's geoms get a
    contact bit of their own that only what it could touch before accepts; restored on the way out."""
    mine = [g for g in range(model.ngeom) if hand_part(model, int(model.geom_bodyid[g]), side) is not None]
    root = model.body(body).id
    obj = [g for g in range(model.ngeom) if model.body_rootid[model.geom_bodyid[g]] == root]
    saved = model.geom_contype.copy(), model.geom_conaffinity.copy()
    c_o = int(np.bitwise_or.reduce(model.geom_contype[obj])) if obj else 0
    a_o = int(np.bitwise_or.reduce(model.geom_conaffinity[obj])) if obj else 0
    skip = set(obj) | set(mine)
    others = [g for g in range(model.ngeom) if g not in skip
              and (model.geom_contype[g] & a_o or c_o & model.geom_conaffinity[g])]
    model.geom_conaffinity[others] |= AWAY_BIT
    model.geom_contype[obj] = AWAY_BIT
    model.geom_conaffinity[obj] = 0
    try:
        yield
    finally:
        model.geom_contype[:], model.geom_conaffinity[:] = saved


def secure_taker(ctx: PlanningContext, giver: Side, obj: SceneObject) -> None:
    """Before `giver` lets go of `obj` that the other hand also holds: make the other hand's grip one that holds
    it alone (see the module's doc)."""
    taker = OTHER_SIDE[giver]
    if holds_alone(ctx, giver, taker, obj):
        return
    axis = ctx.hands[taker].last_approach
    if axis is None:
        return
    posture = ctx.hands[taker].grip or "pinch"
    axis = np.asarray(axis, float)
    # Then closed firmer, where the hand has a firmer closing for this grip (a bottle's shoulder: the same grip
    # deeper or further out slid out of the fingers in the trial on both_hands_all seeds 0, 2 and 4; closed
    # firmer where it was, it held there and through the carry to the table).
    firm = firmer(ctx.hands[taker].closing or posture)
    tries = [(d, None) for d in REGRIP_DEPTHS] + ([(d, firm) for d in (0.0, *REGRIP_DEPTHS)] if firm else [])
    for depth, close in tries:
        # A trial too (nothing recorded): a recording must not hold a grip that is then undone.
        with trial(ctx):
            works = (_close_deeper(ctx, taker, obj, axis, depth, posture, close)
                     and holds_alone(ctx, giver, taker, obj))
        if works:
            _close_deeper(ctx, taker, obj, axis, depth, posture, close)  # for real (the state is restored)
            where = "deeper" if depth > 0 else "further out"
            how = f"{abs(depth) * 1000:.0f} mm {where}" if depth else "where it was"
            if close is not None:
                ctx.hands[taker].closing = close
                how += ", closed firmer (the thumb further in)"
            ctx.events.append(f"the {taker} hand's {posture} would not hold {obj.type_name} {obj.obj_id} alone: "
                              f"it took it again {how} before the {giver} hand let go")
            return
    moved, held = release_trial(ctx, giver, taker, obj)
    if not held:
        raise PlanningError("open_hand", would_fall(ctx, giver, taker, obj, moved))
    ctx.events.append(f"the {taker} hand's {posture} may not hold {obj.type_name} {obj.obj_id} alone when the "
                          f"{giver} hand lets go (taking it deeper or further out did not help)")


def would_fall(ctx: PlanningContext, giver: Side, taker: Side, obj: SceneObject, moved: float) -> str:
    """Why the giver keeps the object, for the plan's author: what the trial showed and one thing to do instead."""
    label = f"{obj.type_name} {obj.obj_id}"
    hand = ctx.hands[taker]
    grip = hand.grip or "pinch"
    if hand.closing == "pinch" and grip != "pinch":  # a grasp that closed as a pinch (the whole hand did not fit)
        grip = f"{grip} (closed as a pinch)"
    mass = float(ctx.env.model.body_subtreemass[ctx.env.model.body(obj.body).id])
    return (f"the {taker} hand's {grip} would not hold {label} alone ({mass:.2f} kg): in a trial with the {giver} "
            f"hand let go, the {taker} hand's thumb and fingers no longer held it (it had moved {moved * 1000:.0f} mm "
            f"within {HOLD_S:g} s), so the {giver} hand keeps holding it. Where the {giver} hand's grip leaves no "
            f"room for the {taker} hand's grasp, hand it over through the table: the {giver} hand sets {label} down "
            f"(action='move' or a target on the table), lets go, and the {taker} hand grasps it there")


def _in_hand(ctx: PlanningContext, side: Side, obj: SceneObject) -> np.ndarray:
    p_hand, R_hand = ctx.env.hand_pose(side)
    return R_hand.T @ (ctx.env.object_pose(obj.body)[0] - p_hand)


def _close_deeper(ctx: PlanningContext, side: Side, obj: SceneObject, axis: np.ndarray, depth: float,
                  posture: str, close: str | None = None) -> bool:
    """Loosen `side`'s fingers, move the hand `depth` further along `axis` (its way in) and close again (with
    `close`, or as the grip closed); False where that move cannot be planned."""
    kin = ctx.kin
    body = ctx.env.model.body(obj.body).id
    ignored = set(ctx.collisions.ignored_bodies)
    ctx.move_fingers((side,), f"pre_{posture}")
    if depth == 0.0:  # closed again where it is
        ctx.move_fingers((side,), close or ctx.hands[side].closing or posture)
        ctx.settle(0.3)
        return is_held(finger_contacts(ctx.env.model, ctx.env.data, side, obj.body))
    try:
        kin.sync(ctx.env.data.qpos)
        kin.set_hand(side, np.array(HAND_POSTURES[f"pre_{posture}"]))
        kin.forward()
        ctx.collisions.ignored_bodies.add(body)
        p, R = kin.ee_pose(side)
        arm = kin.arms[side]
        path = plan_arm_motion(kin, ctx.collisions, side, np.clip(kin.arm_q(side), arm.lo, arm.hi),
                               (p + depth * axis, R), allow_sampling=False)
    except MotionError:
        ctx.move_fingers((side,), posture)
        return False
    finally:
        ctx.collisions.ignored_bodies = ignored
        kin.sync(ctx.env.data.qpos)
    ctx.run_arm_samples({side: time_dense_path(path.waypoints, 1.0 / ctx.env.control_hz,
                                                    v_max=DEEPER_SPEED)})
    ctx.move_fingers((side,), close or ctx.hands[side].closing or posture)  # as hand_grasp closed it (a wrap)
    ctx.settle(0.3)
    return is_held(finger_contacts(ctx.env.model, ctx.env.data, side, obj.body))
