"""The paper's target1 / target2 on an articulated part the task defines a push for (tasks/targets.py `push:`):
the index fingertip pushes a lid, a laptop screen or a drawer front along its joint to the task's openness.

- target1: the pre-push pose, the fingertip `standoff` off the contact point at the part's openness now (under a
  lid: in front of its edge, to slide in; on an outer face: just out of it, or, where the way there is blocked,
  e.g. behind a screen standing nearly upright, as far again out past its edge), with the index finger extended.
- target2 (or either with `openness=`): the push. generate_constraints gives the first contact (the fingertip on
  the part at its openness now); the move then goes on in stages of at most `step` openness, the contact point
  moving along the part as the task's inset table says, collisions with the part ignored (the fingertip is meant
  to touch it), and ends by taking the fingertip `standoff` off the part again. A target2 without target1
  before goes to the pre-push pose first. A part left short of half the way is an error that says so.

Why stages and not one motion along the joint: a fingertip has no grip. Pushed along the part's arc it slips
round a lid's edge or off a rising screen; re-aimed at each stage (the contact further in as the part rises) it
keeps driving the part, as the reference plans' staged pushes showed (tasks/specs/open_box_easy.py and the like).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from humanoidgen.objects.describe import openness as openness_of
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning.constraint_gen import ConstraintGenerationError, Generated
from humanoidgen.planning.constraints import Constraint
from humanoidgen.sim.layout import HAND_BASE_FRAME, Side
from humanoidgen.sim.scene import SceneObject
from humanoidgen.planning.push_spec import FingertipPush

AT_M = 0.02  # a fingertip this near a pose's contact point is there (no pre-push move needed first)
REACH_M = 0.02  # the pre-push pose is free space: the hand must get this near it
TOUCH_SHORT_M = 0.05  # ... or this near, stopped by its fingers resting on the part
PALM_ACROSS_DEG = (70.0, 110.0)
FINGERS_SET = 0.05  # rad: finger targets this near the press posture already are it
SHORT_SHARE = 0.5  # a part moved less than this share of the way did not follow the fingertip: an error
# A push to the joint's end (openness 0 or 1) ends with the fingertip this far past the contact: the stop holds
# the part, and the fingertip's pad, which yields, and its centre's offset from the face otherwise leave it a few
# millimetres short (a drawer "shut" at openness 0.03-0.05, a lid left at 0.91 of the way).
HOME_PRESS_M = 0.01


@dataclass
class PushMove:
    """What a move to a target1/target2 pose does (the goal solver's Pose carries it to the move)."""

    obj: SceneObject
    spec: FingertipPush
    phase: Literal["pre", "push"]
    to: float  # the openness the push brings the part to


@dataclass
class PushGenerated(Generated):
    push: PushMove | None = None


def _label(obj: SceneObject) -> str:
    return f"{obj.type_name} {obj.obj_id}"


def _axis(env, obj: SceneObject, name: str, openness: float | None) -> np.ndarray:
    return get_axis_in_env(env, name, obj_type=obj.type_name, obj_id=obj.obj_id, openness=openness)


def _aim(env, obj: SceneObject, spec: FingertipPush) -> np.ndarray:
    if isinstance(spec.aim, str):
        return _axis(env, obj, spec.aim, None)
    a = np.asarray(spec.aim, float)
    return a / np.linalg.norm(a)


def part_openness(env, obj: SceneObject) -> float:
    """The part's openness now, within [0, 1] (contact can press a part a hair past its stop)."""
    return float(np.clip(openness_of(env.model, env.data, obj), 0.0, 1.0))


def contact_point(env, obj: SceneObject, spec: FingertipPush, openness: float | None, press: float = 0.0) -> np.ndarray:
    """Where the fingertip's centre touches the part with the part at `openness` (None: as it is now); `press`:
    that many metres further, into the part along the push."""
    o = part_openness(env, obj) if openness is None else openness
    p = get_point_in_env(env, spec.point, obj.type_name, obj.obj_id, openness=openness)
    along, normal = (_axis(env, obj, a, openness) for a in spec.axes)
    side = 1.0 if spec.face == "inner" else -1.0  # the inner face lies along the normal, the outer against it
    return p + spec.inset_at(o) * along + side * (spec.depth - press) * normal


def standoff_direction(env, obj: SceneObject, spec: FingertipPush, openness: float | None) -> np.ndarray:
    """Which way the pre-push pose lies off the contact: under a lid, back against the fingertip's aim (it then
    slides in under the edge); on an outer face, out of it (it then comes down onto it)."""
    if spec.face == "inner":
        return -_aim(env, obj, spec)
    return -_axis(env, obj, spec.axes[1], openness)


def stage_constraints(env, side: Side, obj: SceneObject, spec: FingertipPush, openness: float | None,
                      off: float = 0.0, what: str = "on", over_edge: bool = False,
                      press: float = 0.0) -> list[Constraint]:
    """The fingertip on (or `off` metres off) the part at `openness`, pointing within the cone of the aim;
    `over_edge`: as far again out past the part's edge (against axes[0]); `press`: metres into it (contact_point)."""
    frame = HAND_BASE_FRAME[side]
    goal = contact_point(env, obj, spec, openness, press)
    if off:
        goal = goal + off * standoff_direction(env, obj, spec, openness)
    if over_edge:
        goal = goal - off * _axis(env, obj, spec.axes[0], openness)
    at = "now" if openness is None else f"{openness:.2f}"
    cons = [
        Constraint(env, "point2point", frame, hand_key_point=get_point_in_env(env, f"press_point_base_{side}_hand"),
                   object_key_point=goal, name=f"fingertip {what} {_label(obj)} {spec.point} ({spec.face} face, "
                                               f"openness {at})"),
        Constraint(env, "angle", frame, hand_axis=get_axis_in_env(env, f"{side}_press_axis"),
                   object_axis=_aim(env, obj, spec), lower=0.0, upper=np.radians(spec.aim_cone_deg),
                   name=f"fingertip within {spec.aim_cone_deg:g} deg of its push direction"),
    ]
    if spec.palm_across is not None:
        lo, hi = PALM_ACROSS_DEG
        cons.append(Constraint(env, "angle", frame, hand_axis=get_axis_in_env(env, f"{side}_grasp_axis"),
                               object_axis=_axis(env, obj, spec.palm_across, None), lower=np.radians(lo),
                               upper=np.radians(hi), name=f"palm across {spec.palm_across}"))
    return cons


def generate(env, holding: dict, obj: SceneObject, side: Side, action: str, spec: FingertipPush,
             openness: float | None) -> Generated:
    """Constraints for target1 (the pre-push pose) or target2 (the push's first contact), see the module doc."""
    held = holding.get(side)
    if held is not None:
        raise ConstraintGenerationError(
            f"action={action!r} pushes {_label(obj)} with the {side} index fingertip, and the {side} hand holds "
            f"{_label(held)}: let go first (open_hand({side!r})), then ask for {action!r}")
    pushing = action == "target2" or openness is not None
    to = spec.to if openness is None else float(np.clip(openness, 0.0, 1.0))
    if not pushing:
        gen = PushGenerated(stage_constraints(env, side, obj, spec, None, spec.standoff, "just off"))
        gen.push = PushMove(obj, spec, "pre", to)
        return gen
    # The first contact: the goal may touch the part (approach_object), the move then pushes it in stages.
    gen = PushGenerated(stage_constraints(env, side, obj, spec, None), approach_object=obj.body)
    gen.push = PushMove(obj, spec, "push", to)
    gen.notes.append(f"{action}: the {side} fingertip pushes {_label(obj)} at {spec.point} to openness {to:g} "
                     f"in stages (from {part_openness(env, obj):.2f})")
    return gen


def mark(pose, constraints: list) -> None:
    """A goal solved for target1/target2 constraints: the pose tells the move to do the push."""
    gen = getattr(constraints[0], "meta", None) if constraints else None
    if getattr(gen, "push", None) is not None:
        pose.push = gen.push


def stages(start: float, to: float, step: float) -> list[float]:
    n = max(1, int(np.ceil(abs(to - start) / step - 1e-9)))
    # The last stage is `to` exactly (float error would put a "0" a hair below the joint's range).
    return [float(np.clip(start + (to - start) * k / n, 0.0, 1.0)) for k in range(1, n)] + [to]
