"""Snapshots of a running episode: the full MuJoCo integration state plus the planner's bookkeeping (what each
hand holds and how, the commanded action, the ignore list, recent approach axes, events). Restoring one puts
the episode back exactly where it was, so a tree search can resume a branch without re-running it."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import mujoco
import numpy as np

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


def take_snapshot(planner) -> Snapshot:
    env = planner.env
    size = mujoco.mj_stateSize(env.model, STATE_SPEC)
    physics = np.empty(size)
    mujoco.mj_getState(env.model, env.data, physics, STATE_SPEC)
    return Snapshot(
        physics=physics,
        action=planner.action.copy(),
        holding={s: (o.type_name, o.obj_id) if o is not None else None for s, o in planner.holding.items()},
        grip=dict(planner.grip),
        last_approach={s: (np.asarray(a).tolist() if a is not None else None) for s, a in planner.last_approach.items()},
        ignored_bodies=sorted(planner.collisions.ignored_bodies),
        events=list(planner.events),
        closing=dict(planner.closing),
    )


def restore_snapshot(planner, snap: Snapshot) -> None:
    env = planner.env
    mujoco.mj_setState(env.model, env.data, snap.physics, STATE_SPEC)
    mujoco.mj_forward(env.model, env.data)
    planner.action[:] = snap.action
    planner.holding = {s: (env.scene.object(*v) if v else None) for s, v in snap.holding.items()}
    planner.grip = dict(snap.grip)
    planner.last_approach = {s: (np.asarray(a) if a is not None else None) for s, a in snap.last_approach.items()}
    planner.collisions.ignored_bodies = set(snap.ignored_bodies)
    planner.events = list(snap.events)
    planner.closing = dict(snap.closing or {})
    planner.kin.sync(env.data.qpos)
    for side in planner.holding:
        planner.kin.detach(side)


@contextmanager
def trial(planner, start: Snapshot | None = None) -> Iterator[None]:
    """Run the block as a trial in the simulation itself: nothing it does is recorded (the planner's step hook is
    off) and afterwards the planner is back at `start` (default: its state on entry), whatever the block did."""
    snap = start if start is not None else take_snapshot(planner)
    hook, planner.on_step = planner.on_step, None
    try:
        yield
    finally:
        planner.on_step = hook
        restore_snapshot(planner, snap)
