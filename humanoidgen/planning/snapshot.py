"""Snapshots of a running episode: the full MuJoCo integration state plus the planner's bookkeeping (what each
hand holds and how, the commanded action, the ignore list, recent approach axes, events). Restoring one puts
the episode back exactly where it was, so a tree search can resume a branch without re-running it."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import mujoco
import numpy as np

from humanoidgen.planning.context import PlanningContext

# Everything the next step integrates from, the constraint solver's warm start included: restored from the
# physics alone, a contact-rich state stepped on 1.5e-9 rad off the original, enough to change a later hand-over.
STATE_SPEC = mujoco.mjtState.mjSTATE_INTEGRATION


@dataclass
class Snapshot:
    physics: np.ndarray
    action: np.ndarray
    holding: dict  # side -> (type_name, obj_id) or None
    grip: dict
    last_approach: dict  # side -> list or None
    ignored_bodies: list[int]
    events: list[str]
    closing: dict | None = None  # side -> finger posture the next grasp closes with

    def to_dict(self) -> dict:
        return {
            "physics": self.physics.tolist(), "action": self.action.tolist(),
            "holding": {k: list(v) if v else None for k, v in self.holding.items()}, "grip": dict(self.grip),
            "last_approach": self.last_approach, "ignored_bodies": list(self.ignored_bodies),
            "events": list(self.events), "closing": dict(self.closing or {}),
        }

    @classmethod
    def from_dict(cls, d: dict) -> "Snapshot":
        return cls(np.asarray(d["physics"], float), np.asarray(d["action"], float),
                   {k: tuple(v) if v else None for k, v in d["holding"].items()}, dict(d["grip"]),
                   dict(d["last_approach"]), list(d["ignored_bodies"]), list(d["events"]), dict(d.get("closing") or {}))


def take_snapshot(ctx: PlanningContext) -> Snapshot:
    env = ctx.env
    hands = ctx.hands
    size = mujoco.mj_stateSize(env.model, STATE_SPEC)
    physics = np.empty(size)
    mujoco.mj_getState(env.model, env.data, physics, STATE_SPEC)
    return Snapshot(
        physics=physics,
        action=ctx.action.copy(),
        holding={s: (h.held.type_name, h.held.obj_id) if h.held is not None else None for s, h in hands.items()},
        grip={s: h.grip for s, h in hands.items() if h.grip is not None},
        last_approach={s: np.asarray(h.last_approach).tolist() for s, h in hands.items() if h.last_approach is not None},
        ignored_bodies=sorted(ctx.collisions.ignored_bodies),
        events=list(ctx.events),
        closing={s: h.closing for s, h in hands.items() if h.closing is not None},
    )


def restore_snapshot(ctx: PlanningContext, snap: Snapshot) -> None:
    env = ctx.env
    mujoco.mj_setState(env.model, env.data, snap.physics, STATE_SPEC)
    mujoco.mj_forward(env.model, env.data)
    ctx.action[:] = snap.action
    for s, h in ctx.hands.items():
        v, a = snap.holding.get(s), snap.last_approach.get(s)
        h.held = env.scene.object(*v) if v else None
        h.grip = snap.grip.get(s)
        h.last_approach = np.asarray(a) if a is not None else None
        h.closing = (snap.closing or {}).get(s)
    ctx.collisions.ignored_bodies = set(snap.ignored_bodies)
    ctx.events = list(snap.events)
    ctx.kin.sync(env.data.qpos)
    for side in ctx.hands:
        ctx.kin.detach(side)


@contextmanager
def trial(ctx: PlanningContext, start: Snapshot | None = None) -> Iterator[None]:
    """Run the block as a trial in the simulation itself: nothing it does is recorded (the planner's step hook is
    off) and afterwards the planner is back at `start` (default: its state on entry), whatever the block did."""
    snap = start if start is not None else take_snapshot(ctx)
    hook, ctx.on_step = ctx.on_step, None
    try:
        yield
    finally:
        ctx.on_step = hook
        restore_snapshot(ctx, snap)
