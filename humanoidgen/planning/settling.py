"""Letting the scene come to rest after a plan's last move, before the task is judged."""

from __future__ import annotations

from humanoidgen.planning.context import PlanningContext
from humanoidgen.sim.rest import MAX_REST_WAIT_S, moving_objects, object_dofs

__all__ = ["MAX_REST_WAIT_S", "wait_until_still"]


def wait_until_still(ctx: PlanningContext, max_s: float = MAX_REST_WAIT_S) -> list[str]:
    """Hold the robot's last command until no object moves (returns at once when none does, so a still scene
    gets no extra control steps), for at most `max_s`. The steps go through the planner, so a recording keeps
    them. Returns the objects still moving at the end (empty when all came to rest)."""
    env = ctx.env
    dofs = object_dofs(env.scene)
    moving = moving_objects(env.data.qvel, env.data.qacc, dofs)
    for _ in range(int(round(max_s * env.control_hz))):
        if not moving:
            break
        ctx.step()
        moving = moving_objects(env.data.qvel, env.data.qacc, dofs)
    return moving
