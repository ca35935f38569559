"""Two arms moving at once that would touch are moved one after the other, in whichever order keeps them apart
(the right arm may be the one in the way: leaving a hand-over, it goes home first); where neither order does, the
error says what to do instead."""

from __future__ import annotations

import numpy as np
import pytest

from humanoidgen.planning import arm_moves
from humanoidgen.planning.context import CallRecord
from humanoidgen.planning.errors import PlanningError
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene
from plan_runs import task_planner


@pytest.fixture(scope="module")
def ctx():
    _, env = build_scene(load_task("block_handover"), 0)
    return task_planner(env).ctx


def _samples(ctx, n_left: int, n_right: int) -> dict:
    """Each arm from where it is to 0.2 rad further on its first joint: n rows of 7 arm targets."""
    out = {}
    for side, n in (("left", n_left), ("right", n_right)):
        q0 = ctx.kin.arm_q(side)
        out[side] = np.array([q0 + np.r_[0.2 * (k + 1) / n, np.zeros(6)] for k in range(n)])
    return out


def test_the_arms_go_one_after_the_other_in_the_order_that_keeps_them_apart(ctx, monkeypatch):
    ctx.kin.sync(ctx.env.data.qpos)
    start = {s: ctx.kin.arm_q(s) for s in ("left", "right")}
    samples = _samples(ctx, 5, 20)
    # They touch where the left arm has arrived while the right has not yet gone: together (the left is quicker)
    # and left first both do; right first does not.
    def distance() -> float:
        left_there = ctx.kin.arm_q("left")[0] - start["left"][0] > 0.19
        right_home = ctx.kin.arm_q("right")[0] - start["right"][0] < 0.1
        return 0.0 if left_there and right_home else 0.1

    monkeypatch.setattr(ctx.collisions, "arm_arm_distance", distance)
    ctx.log.append(CallRecord("move_to_pose_with_screw", {}, False, "", 0.0, 0.0))
    out = arm_moves.coordinate_arms(ctx, samples)
    assert len(out["left"]) == 25 and len(out["right"]) == 20  # the left moves once the right has arrived
    assert np.allclose(out["left"][: len(samples["right"])], samples["left"][0])  # the left waits at its start
    assert np.allclose(out["right"], samples["right"])
    assert "right first" in ctx.log[-1].message
    # Going into each other whatever the order (the signed distance falls below its start as either arm moves):
    # the error says what to do instead. Arms that start in contact may only come apart, not go deeper.
    def deeper() -> float:
        return -sum(abs(ctx.kin.arm_q(s)[0] - start[s][0]) for s in ("left", "right"))

    monkeypatch.setattr(ctx.collisions, "arm_arm_distance", deeper)
    with pytest.raises(PlanningError) as err:
        arm_moves.coordinate_arms(ctx, samples)
    assert "one after the other" in str(err.value) and "hand_init_pose" in str(err.value)
    # Starting in contact and coming apart (a giver's thumb still on the bottle the taker holds) is allowed.
    ctx.kin.sync(ctx.env.data.qpos)
    monkeypatch.setattr(ctx.collisions, "arm_arm_distance", lambda: -deeper() - 0.002)
    out = arm_moves.coordinate_arms(ctx, samples)
    assert len(out["left"]) == 5 and len(out["right"]) == 20  # together
