"""A press to a force: `generate_constraints(obj, action="press", force=N)`.

A press to a depth (`openness=`) rides with the part to a joint value. A press to a force rides the same way
toward the part's end and on past its stop (FORCE_PAST_STOP, extrapolated: the stop holds the part while the
finger pushes into it), and the move ends at the first control step at which the contact between the pressing
hand and the part carries `force` newtons; the arm's targets stay where they were then, so the finger keeps
pushing. With `openness` too, the press goes no deeper than that openness (a depth limit).

The force is the normal force MuJoCo's contact solver reports between the hand's geoms and the pressed part
(`mj_contactForce`), summed: what the part feels from the finger, not the arm's effort. After the move the force
and the part's openness are an event; a force the arm did not reach before the path ran out is the move's
error, naming the most it measured."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import mujoco
import numpy as np

from humanoidgen.planning import target_actions
from humanoidgen.planning.constraint_gen import ConstraintGenerationError, Generated
from humanoidgen.planning.errors import PlanningError
from humanoidgen.planning.hand_ops import hand_part
from humanoidgen.planning.part_joint import PartFollow, follow_openness
from humanoidgen.sim.action import ARM_SLICE
from humanoidgen.sim.layout import Side

FORCE_PAST_STOP = 1.3  # the openness, extrapolated past the end stop, a press to a force may aim for at most
MAX_FORCE_N = 40.0  # more than a fingertip should be asked to push (the Inspire hand's rated grip is ~10 N a finger)
HELD_SHARE = 0.7  # after the move settles, a force this share of the asked one still counts as held
HOLD_S = 0.5  # after the force is first reached: the arm's targets step along the path to keep it (the arm lags)
HOLD_BAND = 0.1  # within this share of the asked force the targets stay put


def generate(env, side: Side, obj, action: str, openness: float | None, force: float, push) -> Generated:
    """The press's constraints and its ride (`push`: skills._push), the ride carrying the force to stop at."""
    if action != "press":
        raise ConstraintGenerationError(f"force= is for action='press' (a fingertip pressing a part), not "
                                        f"action={action!r}")
    if not (isinstance(force, (int, float)) and math.isfinite(force) and 0 < force <= MAX_FORCE_N):
        raise ConstraintGenerationError(f"force must be a number of newtons in (0, {MAX_FORCE_N:g}], got {force!r}")
    ops = [o for o in (obj.annotations.operations if obj.annotations else []) if o.operation == "press"]
    if not ops:
        raise ConstraintGenerationError(f"{obj.type_name} has no press annotation, so nothing to press to a force; "
                                        f"actions for it: {', '.join(target_actions.actions_of(obj))}")
    k, _ = target_actions.push_index(obj, "press")
    gen = push(env, side, obj.type_name, obj.obj_id, k, 1.0 if openness is None else openness)
    if gen.follow is None:
        raise ConstraintGenerationError(f"{obj.type_name} {obj.obj_id}'s {ops[0].point} is on no moving part")
    deepest = FORCE_PAST_STOP if openness is None else float(openness)
    gen.follow = replace(gen.follow, q_target=gen.follow.articulation.joint_position(deepest), force=float(force))
    gen.notes.append(f"pressing {obj.type_name} {obj.obj_id}'s {ops[0].point} until the fingertip pushes with "
                     f"{force:g} N" + (f", no deeper than openness {openness:g}" if openness is not None else ""))
    return gen


def contact_force(model: mujoco.MjModel, data: mujoco.MjData, side: Side, part_body: int) -> float:
    """The summed normal force (N) of the contacts between `side`'s hand (fingers and palm) and the body."""
    f6 = np.zeros(6)
    total = 0.0
    for i in range(data.ncon):
        c = data.contact[i]
        b1, b2 = model.geom_bodyid[c.geom1], model.geom_bodyid[c.geom2]
        for mine, other in ((b1, b2), (b2, b1)):
            if other == part_body and hand_part(model, mine, side) is not None:
                mujoco.mj_contactForce(model, data, i, f6)
                total += abs(f6[0])
                break
    return total


@dataclass
class Watch:
    """The presses to a force of one move: the force each has reached (and the most it measured)."""

    presses: dict[Side, PartFollow]
    part_bodies: dict[Side, int]
    start: dict[Side, float]
    reached: dict[Side, float] = field(default_factory=dict)  # side -> the force at which its move stopped
    most: dict[Side, float] = field(default_factory=dict)
    rows: dict[Side, int] = field(default_factory=dict)  # side -> the path row whose targets the arm has now

    @classmethod
    def of(cls, ctx, targets: dict) -> Watch | None:
        presses = {s: t.follow for s, t in targets.items() if t.follow is not None and t.follow.force is not None}
        if not presses:
            return None
        m = ctx.env.model
        bodies = {s: int(m.jnt_bodyid[m.joint(f.joint).id]) for s, f in presses.items()}
        return cls(presses, bodies, {s: follow_openness(ctx.env, f) for s, f in presses.items()})

    def run(self, ctx, samples: dict) -> None:
        """The move's rows until each press reaches its force, then HOLD_S of holding it: the arm, which lags its
        targets, would otherwise push on well past the force (12.6 N for 5 N asked on a toaster's lever), so each
        step the targets move one row back along the path where the finger pushes too hard, one on where too
        softly."""
        ctx.run_arm_samples(samples, stop=self.stop)
        for _ in range(int(round(HOLD_S * ctx.env.control_hz))):
            for side in self.reached:
                rows, force = samples[side], self.presses[side].force
                now = contact_force(ctx.env.model, ctx.env.data, side, self.part_bodies[side])
                k = self.rows[side]
                k = max(0, k - 1) if now > force * (1 + HOLD_BAND) else \
                    min(len(rows) - 1, k + 1) if now < force * (1 - HOLD_BAND) else k
                self.rows[side] = k
                ctx.action[ARM_SLICE[side]] = rows[k][:7]
            ctx.step()

    def stop(self, ctx, side: Side) -> bool:
        """Whether `side`'s press has reached its force (checked after every control step of the move)."""
        if side not in self.presses or side in self.reached:
            return False
        self.rows[side] = self.rows.get(side, -1) + 1  # the row the arm was given this step
        now = contact_force(ctx.env.model, ctx.env.data, side, self.part_bodies[side])
        self.most[side] = max(self.most.get(side, 0.0), now)
        if now >= self.presses[side].force:
            self.reached[side] = now
            return True
        return False

    def report(self, ctx) -> None:
        """After the move has settled: an event per press, or the error of one that never got its force."""
        for side, f in self.presses.items():
            obj = ctx.env.scene.object(*f.obj)
            label = f"{obj.type_name} {obj.obj_id}"
            now = contact_force(ctx.env.model, ctx.env.data, side, self.part_bodies[side])
            at = follow_openness(ctx.env, f)
            if side in self.reached and now >= HELD_SHARE * f.force:
                ctx.events.append(f"the {side} fingertip pressed {label} with {now:.1f} N ({f.force:g} N asked), "
                                  f"the part at openness {at:.2f}")
                continue
            most = max(self.most.get(side, 0.0), now)
            raise PlanningError("move_to_pose_with_screw", (
                f"the {side} fingertip pressed {label} with at most {most:.1f} N of the {f.force:g} N asked (now "
                f"{now:.1f} N, the part at openness {at:.2f}, from {self.start[side]:.2f}). Suggestion: "
                + (f"ask for no more than {0.8 * most:.1f} N" if most > 0.5 else
                   "the finger never pushed the part: put the fingertip on the press point first "
                   "(action='press' without force), then press")))
