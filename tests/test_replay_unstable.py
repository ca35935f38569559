"""A replay that goes unstable is rejected (episodes/replay.py, UNSTABLE): MuJoCo answers NaN or huge values in
qpos/qvel/qacc by resetting the simulation to the model's qpos0 and carrying on, and for the closing tasks qpos0
is the goal (drawer, box, laptop shut). Found by the unseen cheating battery (tests/cheats_unseen/034, 035):
without this rule, a replay that blew up once would be judged a success."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from humanoidgen.episodes.replay import UNSTABLE, Replay  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402


@pytest.fixture(autouse=True)
def _elsewhere(tmp_path, monkeypatch):
    """MuJoCo writes its warnings to MUJOCO_LOG.TXT in the working directory: not into the checkout."""
    monkeypatch.chdir(tmp_path)


def _blown_up_replay(task: str) -> Replay:
    """The task's replay after one command in a simulation that was made to blow up (the replay's own scene,
    as if the commands had made it unstable)."""
    replay = Replay.build(load_task(task), 0)
    hold = replay.env.joint_positions()
    replay.feed(np.stack([hold] * 5))
    replay.env.data.qvel[:] = 1e30  # (trusted side: stands in for commands that drive the physics unstable)
    replay.feed(np.stack([hold] * 30))
    return replay


def test_the_reset_would_close_the_drawer():
    """What the rule guards against is real: after MuJoCo's reset the drawer is judged shut."""
    replay = _blown_up_replay("close_drawer")
    verdict = replay.finish(settle=False)
    shut = next(c for c in verdict.checks if c["predicate"] == "openness_at_most")
    assert shut["ok"], verdict.checks  # the end state alone says "closed" (no hold pushed it: that one says no)
    assert verdict.problem is not None and verdict.problem.startswith(UNSTABLE)
    assert not verdict.ok
    assert "huge velocities" in verdict.all_checks()[-1]["detail"]


def test_the_replay_stops_at_the_unstable_step():
    replay = _blown_up_replay("close_drawer")
    assert replay.steps == 6  # the step that blew up is the last one applied
    assert "t=0.1" in replay.problem


def test_an_honest_hold_is_not_unstable():
    replay = Replay.build(load_task("close_drawer"), 0)
    hold = replay.env.joint_positions()
    replay.feed(np.stack([hold] * 50))
    verdict = replay.finish()
    assert verdict.problem is None
    assert not verdict.ok  # the drawer is still open: the task is not done, and nothing says otherwise
