"""A mid-air hand-over ends with the object between the taker's thumb and index: a pinch held alone is one between
thumb and index (`hand_ops.is_pinched`), and where no deeper grip is, one further out is tried
(`recoveries/hand_over.py`); a giver that cannot back out is left by the taker pulling the object out of its
loosened fingers (`planning/back_away.py`), so the giver's next move does not drag the object in the pinch.

- block_handover seed 0, the reference plan's hand-over with the giver's way back blocked (as the right arm's was,
  out of reach, in handover_and_storage_cooperation alt_folder seed 1).
- handover_and_storage_cooperation/alt_folder seed 0 end to end: the left hand's pinch had ended on thumb and
  middle finger after the right hand's move home and the block fell on the carry into the drawer ("slipped
  325 mm"; see CHANGELOG)."""

from __future__ import annotations

from pathlib import Path

import pytest

from humanoidgen.episodes.plans import folder_plan_text
from humanoidgen.planning import arm_moves
from humanoidgen.planning.recoveries import hand_over
from humanoidgen.planning.hand_ops import finger_contacts, is_pinched
from plan_runs import run_plan
from test_handover_release import _mid_air

CORPUS = Path(__file__).parents[1] / "bench" / "foreign_plans"


def test_a_pinch_is_thumb_and_index():
    assert is_pinched({"thumb", "index"}) and is_pinched({"thumb", "index", "middle"})
    assert not is_pinched({"thumb", "middle"}) and not is_pinched({"index", "middle"})


@pytest.mark.slow
def test_a_pinch_held_alone_by_thumb_and_middle_is_not_held(monkeypatch):
    env, planner, cube = _mid_air()
    monkeypatch.setattr(hand_over, "_release_outcome", lambda *a: (0.002, {"thumb", "middle"}))
    assert planner.ctx.hands["left"].grip == "pinch"
    assert not hand_over.holds_alone(planner.ctx, "right", "left", cube)
    planner.ctx.hands["left"].grip = "grasp"  # a whole-hand grasp: thumb against any finger holds
    assert hand_over.holds_alone(planner.ctx, "right", "left", cube)


@pytest.mark.slow
def test_where_no_deeper_grip_holds_one_further_out_is_tried(monkeypatch):
    env, planner, cube = _mid_air()
    tried = []

    def closing(ctx, side, obj, axis, depth, posture, close=None):  # the grip itself is tested with the deeper ones
        tried.append(depth)
        return True

    monkeypatch.setattr(hand_over, "_close_deeper", closing)
    monkeypatch.setattr(hand_over, "holds_alone", lambda *a: bool(tried) and tried[-1] < 0)  # only further out
    hand_over.secure_taker(planner.ctx, "right", cube)
    assert tried == [0.006, 0.012, -0.006, -0.006]  # deeper first; the first that holds is then taken for real
    assert "took it again 6 mm further out" in planner.events[-1]


@pytest.mark.slow
def test_a_giver_that_cannot_back_out_is_pulled_clear_of(monkeypatch):
    env, planner, cube = _mid_air()
    monkeypatch.setattr(arm_moves, "retreat", lambda *a, **k: None)  # the way back out of reach
    planner.open_hand("right")
    events = " | ".join(planner.events)
    assert "the left hand pulled cube 0" in events, events
    assert finger_contacts(env.model, env.data, "right", cube.body) == set()
    assert is_pinched(finger_contacts(env.model, env.data, "left", cube.body))
    assert planner.holding["left"] is cube and planner.holding["right"] is None


@pytest.mark.slow
def test_the_cooperation_plans_hand_over_ends_in_a_pinch_that_carries(tmp_path):
    plan = folder_plan_text(CORPUS / "handover_and_storage_cooperation" / "alt_folder")
    result = run_plan(tmp_path, "handover_and_storage_cooperation", 0, plan)
    events = [e for s in result.steps for e in s.events]
    assert any("took it again 6 mm further out" in e for e in events), events
    assert result.success, [s.error for s in result.steps if not s.ok] or result.checks
