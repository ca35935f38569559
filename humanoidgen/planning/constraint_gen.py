"""Constraints for the planner API's actions, built from the asset annotations and the task's targets.

- "grasp" / "pinch": the hand's grasp (pinch) point on the operation point, the hand turned to the operation's
  axes (an object the other hand holds: at the point farthest from that hand's grip, a hand-over); with `openness`, the same at the part's pose for that openness (pulling a drawer, lifting a lid). An
  object without that operation but with the other (an object annotated only for pinching is pinched when grasped) uses the other.
  A `point=` on a rigid object comes first; its other grips of that kind follow as the last resort.
- "target": the object the hand holds (its centre) to the object's target pose in this task (listed in the scene
  as the object's "targets": a hand-over pose, the place above the bowl, the spot to stack on), keeping the
  hand's orientation and the object upright. Where the task defines none, it lifts the held object 10 cm.
- "target1" / "target2": the held object to its target pose of that name, where the task defines one; on an
  articulated object (drawer, laptop, box) with a task push: the pre-push pose and the push to the task's
  openness (push_actions); without one: the fingertip on its first / second push or flip point (with
  `openness`: pushing the part to that openness).
- "move": the held object's centre (or the grasp point) to `relative_p` (world offset) from another object
  (`relative_obj_name`, `relative_obj_id`): from its "head" where it has one, else its centre; set down as
  `placing` says, a cube beside another lined up with it (`move_action`).
- "pour": the held cup beside and above a receptacle (relative_obj_name, else the nearest bowl or other
  container), tipped toward it so that its contents fall in.
Objects may be named by type and obj_id ("cube", 1), as "cube1", or by an alias the scene lists.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from humanoidgen.objects.describe import openness as openness_now
from humanoidgen.objects.hands import hand_axes, narrow_grasp, wrap_point
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env, wrist_point_in_env
from humanoidgen.objects.schema import OperationAnnotation
from humanoidgen.planning import placing
from humanoidgen.planning.constraints import Const, Constraint
from humanoidgen.planning.part_joint import PartFollow, point_articulation
from humanoidgen.sim.geometry import axis_angle_mat
from humanoidgen.sim.layout import HAND_BASE_FRAME, OTHER_SIDE, Side

ACTIONS = ("grasp", "pinch", "target", "target1", "target2", "move", "pour")
# Not the paper's, but plans use them: the object's push / flip / press point (as target1 / target2).
PUSH_ACTIONS = ("push", "flip", "press")
# A round body can be wrapped from a range of directions around its axis, not only the annotated one: these
# turns (degrees), nearest first, are tried where the annotated direction is out of reach.
WRAP_TURNS_DEG = (0, 20, -20, 40, -40)
# A pinch this far (horizontally) from the object's centre of mass squeezes top and bottom where it can.
OFF_CENTRE_PINCH_M = 0.015
PUSH_CONE_DEG = 30
# A plate's edge (a screen's, a lid's) pinched between the fingertips holds with the fingers entering it at a
# slant too: these turns of the fingers about the squeeze axis, nearest first, are tried where pointing them
# straight in is out of reach (an open screen's top edge would need the hand high above it, fingers down).
PART_PINCH_LEAD_TURNS_DEG = (0, 30, -30, 60, -60)
PART_PINCH_INSET_M = 0.012
LOW_PART = 0.5  # a part pinched below this openness is taken index under it, thumb on its outer face
# How far a hand holding a part may turn about the part's parallel axis (a bar, a tab, a screen's edge) while it
# moves the part: a grasp around a bar or tab lets the part turn in the fingers; a pinch with the pads 12 mm over
# the plate (PART_PINCH_INSET_M) holds through a 30 deg roll (measured: with the fingertips on the very edge, a
# screen let go within 0.2 s of a 30 deg roll; 45 deg closed a screen but then it sprang back open on release).
GRASP_ROLL_DEG = 90.0
PINCH_ROLL_DEG = 30.0
LIFT = np.array([0.0, 0.0, 0.10])
TURNED_WITHIN_DEG = 20.0  # a move's quarter-turned hand (placing.py) keeps its palm this near the turned direction


class ConstraintGenerationError(ValueError):
    pass


def hand_axes_local(side: Side) -> dict[str, np.ndarray]:
    """The hand axes in the wrist frame, by role."""
    ax = hand_axes(side)
    return {"palm": ax[f"{side}_grasp_axis"], "pinch": ax[f"{side}_thumb_2_index"],
            "ring_2_index": ax[f"{side}_ring_2_index"], "fingers": ax[f"{side}_grasp_wrist_2_palm_axis"]}


@dataclass
class Generated:
    """Constraints plus what the move needs to know about them."""

    constraints: list
    approach_axis: np.ndarray | None = None
    approach_object: str | None = None
    follow: PartFollow | None = None
    posture: str | None = None  # the finger posture the grip closes with (None: the operation's default)
    # Other ways to take the grip (other annotated points, the object's symmetric axes, the other sign), most
    # natural first: Generated objects the goal solver tries in turn when the first cannot be reached.
    alternatives: list = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # for the planner's events: a fallback or mapping that was made
    # A grip on an articulated part with no openness asked (yet): the part and the grip's roll axis, so that the
    # goal search can prefer the arm posture that keeps the most reach along the part's arc (the next move).
    grip_part: PartFollow | None = None
    request: tuple | None = None  # the generate_constraints arguments that made it (set by the planner)
    fallback: Generated | None = None  # the grip to take where this one cannot be solved (a pinch for a grasp)
    presses: bool = False  # the goal presses the fingertip into approach_object (Pose.presses)


def _frame_from_two(l1: np.ndarray, w1: np.ndarray, l2: np.ndarray, w2: np.ndarray) -> np.ndarray | None:
    """The rotation taking local directions l1, l2 onto world w1, w2 (None if w1, w2 are not orthogonal)."""
    if abs(float(w1 @ w2)) > 1e-3:
        return None
    L = np.column_stack([l1, l2, np.cross(l1, l2)])
    W = np.column_stack([w1, w2, np.cross(w1, w2)])
    return W @ L.T


def _off_centre(env, obj_name: str, obj_id: int, point: np.ndarray) -> float:
    """How far (horizontally) a grip point is from the object's centre of mass."""
    body = env.model.body(env.scene.object(obj_name, obj_id).body).id
    return float(np.linalg.norm((point - env.data.xipos[body])[:2]))


def _natural_choices(side: Side, fixed_local: np.ndarray, fixed_world: np.ndarray, free_local: np.ndarray,
                     candidates: list[np.ndarray], current_fingers: np.ndarray) -> list[np.ndarray]:
    """Pick the signed candidate for the second hand axis that gives the most natural hand: fingers pointing
    away from the robot and close to where they point now. Symmetric grips (a cube pinched along x or y, a
    handle grasped with the index up or down) then resolve to a reachable posture."""
    fingers_local = hand_axes_local(side)["fingers"]
    scored = []
    for c in candidates:
        for sign in (1.0, -1.0):
            R = _frame_from_two(fixed_local, fixed_world, free_local, sign * c)
            if R is None:
                continue
            f = R @ fingers_local
            scored.append((_posture_score(side, R @ hand_axes_local(side)["palm"], f) + 0.3 * f @ current_fingers,
                           sign * c))
    if not scored:
        raise ConstraintGenerationError("the operation's axes are not perpendicular to each other")
    return [c for _, c in sorted(scored, key=lambda x: -x[0])]


def _operations(env, obj_name: str, obj_id: int, operation: str) -> list[OperationAnnotation]:
    obj = env.scene.object(obj_name, obj_id)
    ann = obj.annotations
    if ann is None:
        raise ConstraintGenerationError(f"{obj_name} {obj_id} has no annotations")
    ops = ann.operations_of(operation)
    if not ops:
        available = sorted({o.operation for o in ann.operations})
        raise ConstraintGenerationError(
            f"{obj_name} has no '{operation}' annotation; it supports: {', '.join(available) or 'nothing'}"
        )
    return ops


INWARD = {"left": np.array([0.0, -1.0, 0.0]), "right": np.array([0.0, 1.0, 0.0])}


def _posture_score(side: Side, palm_world: np.ndarray, fingers_world: np.ndarray) -> float:
    """How natural a hand orientation is: fingers away from the robot, palm not turned outward."""
    return float(fingers_world @ np.array([1.0, 0.0, 0.0]) + 0.5 * palm_world @ INWARD[side])


# Ranking a grip on an object the other hand holds: each metre of clearance from that hand's grip counts this much
# more than posture (up to OTHER_GRIP_CLEAR_M), so the far end of a held block comes first. A grip approached from
# below an object that rests on something is blocked by its support: it goes last.
OTHER_GRIP_WEIGHT = 30.0
OTHER_GRIP_CLEAR_M = 0.10
FROM_BELOW_PENALTY = 5.0
# A round body no hand holds is wrapped round its body before any other grasp (a bottle's shoulder: hand-overs).
NOT_WRAP_PENALTY = 5.0


def _rank_operations(env, side: Side, obj_name: str, obj_id: int, operation: str,
                     openness: float | None, point: str | None = None,
                     other_grip: list[np.ndarray] | None = None) -> list[OperationAnnotation]:
    """The object's annotations for this operation, the ones the hand can take most naturally first.

    `other_grip`: where the other hand holds this object (its grip points), or None when no hand holds it. A
    hand-over then takes the point farthest from the other hand (a block's free end); an object no hand holds
    is not taken from below."""
    ops = _operations(env, obj_name, obj_id, operation)
    if point is not None:
        chosen = [o for o in ops if o.point == point]
        if not chosen:
            raise ConstraintGenerationError(f"{obj_name} has no '{operation}' annotation at point {point!r}; "
                                            f"points: {', '.join(sorted({o.point for o in ops}))}")
        ops = chosen
    if len(ops) == 1:
        return ops
    loc = hand_axes_local(side)
    rigid = env.scene.object(obj_name, obj_id).annotations.articulation is None
    first_local = loc["palm"] if operation == "grasp" else loc["ring_2_index"]
    second_local = loc["ring_2_index"] if operation == "grasp" else loc["pinch"]

    def score(op: OperationAnnotation) -> float:
        ax = lambda n: get_axis_in_env(env, n, obj_type=obj_name, obj_id=obj_id, openness=openness)  # noqa: E731
        cands = [ax(op.parallel_axis)] if operation == "grasp" else [ax(op.attach_axis), ax(op.parallel_axis)]
        best = -np.inf
        for c in cands:
            for sign in (1.0, -1.0):
                R = _frame_from_two(first_local, ax(op.approach_axis), second_local, sign * c)
                if R is not None:
                    best = max(best, _posture_score(side, R @ loc["palm"], R @ loc["fingers"]))
        if other_grip:  # a wrap is centred on the body's axis, as the other hand's grip of it: compared there
            where = get_point_in_env(env, op.point, obj_name, obj_id, openness=openness)
            where = where if op.width is None else where + op.width / 2 * ax(op.approach_axis)
            clear = min(float(np.linalg.norm(where - g)) for g in other_grip)
            best += OTHER_GRIP_WEIGHT * min(clear, OTHER_GRIP_CLEAR_M)
        elif rigid and float(ax(op.approach_axis)[2]) > 0.5:
            best -= FROM_BELOW_PENALTY
        if not other_grip and operation == "grasp" and op.width is None and any(o.width is not None for o in ops):
            best -= NOT_WRAP_PENALTY
        return best

    return sorted(ops, key=score, reverse=True)


def other_hand_grip(env, holding: dict, side: Side, obj_name: str, obj_id: int) -> list[np.ndarray] | None:
    """Where the other hand holds this object (its pinch and grasp points), or None if it does not hold it."""
    other = OTHER_SIDE[side]
    held = holding.get(other)
    if held is None or (held.type_name, held.obj_id) != (obj_name, obj_id):
        return None
    return [get_point_in_env(env, f"{kind}_point_base_{other}_hand") for kind in ("pinch", "grasp")]


def grasp_or_pinch(env, side: Side, obj_name: str, obj_id: int, operation: str,
                   openness: float | None, point: str | None = None, finger_offset: float = 0.0,
                   holding: dict | None = None) -> Generated:
    """Every way to take the grip, most natural first: the first, with the others as its alternatives. An object
    the other hand holds (`holding`) is taken as far from that hand's grip as its annotations allow."""
    other_grip = other_hand_grip(env, holding or {}, side, obj_name, obj_id)
    ops = _rank_operations(env, side, obj_name, obj_id, operation, openness, point, other_grip)
    ways = _ways(env, side, obj_name, obj_id, operation, ops, openness, finger_offset)
    if point is not None and env.scene.object(obj_name, obj_id).annotations.articulation is None:
        # A named point on a rigid object is the author's preference, not a different task: where it cannot be
        # reached or approached (a cup's front grip on a cup standing beyond the arm's reach from the front),
        # the object's other grips of this kind are the last resort (measured: a plan naming a cup's "side"
        # failed on 5 of 10 seeds where its right flank was in reach). On a part, the point names which part.
        others = [o for o in _rank_operations(env, side, obj_name, obj_id, operation, openness, None, other_grip)
                  if o.point != point]
        for op in others:
            for g in _ways(env, side, obj_name, obj_id, operation, [op], openness, finger_offset):
                g.notes.append(f"the {side} hand cannot take {obj_name} {obj_id} at '{point}' as asked (out of "
                               f"reach, or no way in): it takes it at '{op.point}' instead")
                ways.append(g)
    first = ways[0]
    first.alternatives = ways[1:]
    return first


def _ways(env, side: Side, obj_name: str, obj_id: int, operation: str, ops: list[OperationAnnotation],
          openness: float | None, finger_offset: float) -> list[Generated]:
    # Round wraps (not `across`: flat) also turn about the body; a non-wrap grip ranked below a wrap comes after.
    wraps = [op for op in ops if op.width is not None]
    turns = WRAP_TURNS_DEG if operation == "grasp" and wraps and all(o.across is None for o in wraps) else (0,)
    k = ops.index(wraps[0]) if wraps else len(ops)
    order = ([(op, 0) for op in ops[:k]] + [(op, t) for t in turns for op in ops[k:] if op.width is not None]
             + [(op, 0) for op in ops[k:] if op.width is None])
    return [g for op, turn in order
            for g in _grip_variants(env, side, obj_name, obj_id, operation, op, openness, turn, finger_offset)]


def _openness_of(env, obj_name: str, obj_id: int, point: str) -> float:
    """The openness of the joint that moves `point`'s part (a safe's knob: its own)."""
    obj = env.scene.object(obj_name, obj_id)
    part = obj.annotations.point(point).part
    got = openness_now(env.model, env.data, obj, part)
    return 1.0 if got is None else float(got)


def _grip_variants(env, side: Side, obj_name: str, obj_id: int, operation: str, op: OperationAnnotation,
                   openness: float | None, turn_deg: float = 0.0, finger_offset: float = 0.0) -> list[Generated]:
    frame = HAND_BASE_FRAME[side]
    kind = "grasp" if operation == "grasp" else "pinch"
    hand_point = get_point_in_env(env, f"{kind}_point_base_{side}_hand")
    wrap = kind == "grasp" and op.width is not None
    round_body = any(o.width is not None for o in env.scene.object(obj_name, obj_id).annotations.operations_of(kind))
    closing = "wrap" if wrap else narrow_grasp() if round_body and kind == "grasp" else None  # a bottle's shoulder
    if wrap:  # a round body goes against the finger pads, past the thumb (hands.wrap_point)
        hand_point = wrist_point_in_env(env, side, wrap_point(side, op.width, op.across))
    if finger_offset:
        hand_point = hand_point + finger_offset * get_axis_in_env(env, f"{side}_grasp_wrist_2_palm_axis")
    target = get_point_in_env(env, op.point, obj_name, obj_id, openness=openness)

    def axis(name: str) -> np.ndarray:
        return get_axis_in_env(env, name, obj_type=obj_name, obj_id=obj_id, openness=openness)

    approach, attach, parallel = axis(op.approach_axis), axis(op.attach_axis), axis(op.parallel_axis)
    if turn_deg:  # the same wrap from another direction: turn about the round body's own axis
        centre_line = target + op.width / 2 * approach
        R = axis_angle_mat(parallel, np.radians(turn_deg))
        approach, attach = R @ approach, R @ attach
        target = centre_line - op.width / 2 * approach
    fingers_now = get_axis_in_env(env, f"{side}_grasp_wrist_2_palm_axis")
    turned = f" turned {turn_deg:+.0f} deg" if turn_deg else ""
    cons = [Constraint(env, "point2point", frame, hand_key_point=hand_point, object_key_point=target,
                       name=f"{kind} point on {obj_name} {obj_id} {op.point}{turned}")]
    if kind == "grasp":
        # The palm faces the object along the approach; the fingers line up with the part's parallel axis.
        palm = get_axis_in_env(env, f"{side}_grasp_axis")
        r2i = get_axis_in_env(env, f"{side}_ring_2_index")
        loc = hand_axes_local(side)
        options = _natural_choices(side, loc["palm"], approach, loc["ring_2_index"], [parallel], fingers_now)
        variants = [(cons + [
            Constraint(env, "parallel", frame, hand_axis=palm, object_axis=approach, name="palm faces the approach"),
            Constraint(env, "parallel", frame, hand_axis=r2i, object_axis=along, name="fingers along the parallel axis"),
        ], approach) for along in options]
    else:
        # Thumb and index squeeze along the attach (or parallel) axis; the index edge leads the approach.
        pinch = get_axis_in_env(env, f"{side}_thumb_2_index")
        r2i = get_axis_in_env(env, f"{side}_ring_2_index")
        loc = hand_axes_local(side)
        # A moving part's edge (a screen's, a lid's tab) is a plate: it is pinched across its thickness (the
        # attach axis) only; a compact body also along its parallel axis (a cube from either pair of sides).
        ann = env.scene.object(obj_name, obj_id).annotations
        on_part = ann is not None and ann.articulation is not None and ann.point(op.point).part is not None
        options = _natural_choices(side, loc["ring_2_index"], approach, loc["pinch"],
                                   [attach] if on_part else [attach, parallel], fingers_now)
        if on_part and openness is None and _openness_of(env, obj_name, obj_id, op.point) < LOW_PART:
            # A lid or screen pinched low is lifted next: the index, which reaches deeper along the plate, goes
            # under it and the thumb on its outer face (the squeeze along +attach). Measured, a laptop screen
            # pinched at 0.15: with the thumb under the edge it lifted on 1 of 4 seeds (the thumb, at the very
            # edge, slipped off, or the index coming in over the screen pressed it shut); thumb on top, 6 of 6.
            options = sorted(options, key=lambda sq: -float(sq @ attach))
        if not on_part and _off_centre(env, obj_name, obj_id, target) > OFF_CENTRE_PINCH_M:
            # Pinched away from its centre of mass (the free end of a block held level), the object's weight
            # turns it about the squeeze axis, which only the pads' torsional friction resists: squeeze top
            # and bottom instead, so that the pads' pressure carries that moment.
            options = sorted(options, key=lambda sq: -abs(float(sq[2])))
        fingers_forward = Const(env, "parallel", frame, hand_axis=get_axis_in_env(env, f"{side}_pinch_wrist_2_palm_axis"),
                                object_axis=np.array([1.0, 0.0, 0.0]), weight=0.1, name="fingers forward (preferred)")
        turns = PART_PINCH_LEAD_TURNS_DEG if on_part else (0,)
        variants = []
        for squeeze in options:
            for lead_turn in turns:
                lead = axis_angle_mat(squeeze, np.radians(lead_turn)) @ approach if lead_turn else approach
                slant = f" at {lead_turn:+d} deg" if lead_turn else ""
                at = cons if not on_part else [  # the pads over the plate, not hanging off its edge
                    Constraint(env, "point2point", frame, hand_key_point=hand_point,
                               object_key_point=target + PART_PINCH_INSET_M * lead, name=cons[0].name)]
                variants.append((at + [
                    Constraint(env, "parallel", frame, hand_axis=r2i, object_axis=lead, name=f"index edge leads{slant}"),
                    Constraint(env, "parallel", frame, hand_axis=pinch, object_axis=squeeze,
                               name="pinch along the attach axis"),
                    fingers_forward,
                ], lead))
    body = env.scene.object(obj_name, obj_id).body
    out = []
    for cons, lead in variants:
        gen = Generated(cons, approach_axis=lead, approach_object=body, posture=closing)
        # The hand is already on the part; a grasp around a bar or tab may roll about the part's parallel axis.
        ride_with_part(env, gen, obj_name, obj_id, op.point, openness, grip_axis=op.parallel_axis,
                        roll_deg=GRASP_ROLL_DEG if kind == "grasp" else PINCH_ROLL_DEG,
                        unhook_axis=op.attach_axis if kind == "grasp" else None)
        out.append(gen)
    return out


def ride_with_part(env, gen: Generated, obj_name: str, obj_id: int, point: str, openness: float | None,
                    grip_axis: str | None = None, roll_deg: float = 0.0, unhook_axis: str | None = None) -> None:
    """Moving an articulated part to `openness` with the hand on it: the hand follows the part's joint path from
    where it touches it now (the solved goal is a fallback) and comes in along no approach axis. `grip_axis`:
    the part's axis a holding grip may roll about on the way, up to `roll_deg` (part_grip.track_rolling).
    `unhook_axis`: the part's axis along which the hand came onto a handle it hooks (a grasp's attach axis); the
    hand lets go along it (finger_room.unhook)."""
    obj = env.scene.object(obj_name, obj_id)
    art = point_articulation(obj, point)  # the joint that moves the point's part (a knob's own, on a door)
    if art is None:
        return
    if openness is None:
        gen.grip_part = PartFollow(obj.body, f"{obj.body}_{art.joint}", (obj_name, obj_id), art,
                                   grip_axis=grip_axis, roll_deg=roll_deg)
        return
    gen.follow = PartFollow(obj.body, f"{obj.body}_{art.joint}", (obj_name, obj_id), art,
                            q_target=art.joint_position(openness), part_point=point, grip_axis=grip_axis,
                            roll_deg=roll_deg, unhook_axis=unhook_axis)
    gen.approach_axis = None


def keep_orientation(env, side: Side, held: tuple[str, int] | None = None, up: np.ndarray | None = None,
                     turn_deg: float = 0.0) -> list[Constraint]:
    """Prefer the hand's present orientation (soft; turned `turn_deg` about the vertical); a held
    object's up axis stays within 10 deg of now (hard). With `up` (a world direction), the held object's own z
    axis turns to within 10 deg of it instead, the hand preferring its fingers forward (how a hand presents what
    it turns)."""
    frame = HAND_BASE_FRAME[side]
    if held is not None and up is not None:
        z = get_axis_in_env(env, "z", obj_type=held[0], obj_id=held[1])
        to = np.asarray(up, float) / np.linalg.norm(up)
        return [Constraint(env, "angle", frame, hand_axis=z, object_axis=to, lower=0.0, upper=np.radians(10),
                           name=f"{held[0]} {held[1]}'s z axis toward {np.round(to, 2).tolist()}"),
                Const(env, "parallel", frame, hand_axis=get_axis_in_env(env, f"{side}_grasp_wrist_2_palm_axis"),
                      object_axis=np.array([1.0, 0.0, 0.0]), weight=0.1, name="fingers forward (preferred)")]
    palm = get_axis_in_env(env, f"{side}_grasp_axis")
    r2i = get_axis_in_env(env, f"{side}_ring_2_index")
    turned = f" turned {turn_deg:+.0f} deg about the vertical" if turn_deg else ""
    out: list[Constraint] = [
        Const(env, "parallel", frame, hand_axis=palm, object_axis=placing.turned_about_vertical(palm, turn_deg),
              weight=0.5, name=f"keep the palm's direction{turned}"),
        Const(env, "parallel", frame, hand_axis=r2i, object_axis=placing.turned_about_vertical(r2i, turn_deg),
              weight=0.5, name=f"keep the fingers' direction{turned}"),
    ]
    if turn_deg:  # a turned hand is a way of its own, not a preference the solver may give up near the start
        out.append(Constraint(env, "angle", frame, hand_axis=palm, object_axis=out[0].object_axis, lower=0.0,
                              upper=np.radians(TURNED_WITHIN_DEG), name=f"the palm{turned}"))
    if held is not None:
        up_now = get_axis_in_env(env, "z", obj_type=held[0], obj_id=held[1])
        out.append(Constraint(env, "angle", frame, hand_axis=up_now, object_axis=up_now, lower=0.0,
                              upper=np.radians(10), name=f"keep {held[0]} {held[1]} upright"))
    return out
