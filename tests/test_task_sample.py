"""A sample of the benchmark's tasks runs end to end from their reference plans and succeeds: single-arm and
bimanual, rigid and articulated. The whole benchmark is `hgen bench` (bench/ and the README's figures)."""

from __future__ import annotations

import numpy as np
import pytest

from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode
from humanoidgen.objects.hands import HAND_POSTURES, wrap_point
from humanoidgen.objects.library import annotations

SAMPLE = [
    ("dual_bottles_pick_easy", 2),  # bimanual, round bodies wrapped
    ("open_box_easy", 1),  # single arm, articulated
]


@pytest.mark.parametrize("task, seed", SAMPLE)
def test_reference_plan_succeeds(task, seed):
    result, _ = run_task_episode(EpisodeRequest(task, seed=seed))
    failed = result.failed_step
    assert result.success, (failed.error if failed else None, result.checks)


def test_round_bodies_declare_their_width_and_are_wrapped_past_the_thumb():
    for family in ("bottle", "can", "cup"):
        for op in annotations(family, 0).operations_of("grasp"):
            if op.approach_axis == "down":  # a grasp from above (a bottle's shoulder) is no wrap of the body
                assert op.width is None, (family, op)
                continue
            assert op.width is not None and 0.04 < op.width < 0.1, (family, op)
    assert all(op.width is None for op in annotations("cube", 0).operations_of("grasp"))
    thin, thick = wrap_point("left", 0.05), wrap_point("left", 0.08)
    assert thick[0] - thin[0] == pytest.approx(0.015)  # the wider body sits further out along the fingers
    assert np.sign(wrap_point("right", 0.05)[1]) == -np.sign(thin[1])  # out of each palm
    assert HAND_POSTURES["wrap"][4] < HAND_POSTURES["grasp"][4]  # ring and pinky only rest on the body


@pytest.mark.slow
@pytest.mark.parametrize("task, seed", [("dual_bottles_pick_hard", 0), ("block_handover", 0), ("open_drawer", 0),
                                        ("cup_pour_easy", 1), ("handover_and_storage", 0)])
def test_more_reference_plans_succeed(task, seed):
    result, _ = run_task_episode(EpisodeRequest(task, seed=seed))
    assert result.success, (result.failed_step.error if result.failed_step else None, result.checks)
