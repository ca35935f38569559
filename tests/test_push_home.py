"""A part let go on its way to near the end the task pushes it to, that came to rest just short of the openness
asked, is pushed home with the fingertip; "near" is not "there" where the task asks for at least that much.

The small box's lid pinched 1 cm in from its tab's tip (`lid_pinch`) and lifted toward 0.95 is let go where the
arm's reach ends (0.75) and swings on by itself to 0.94: within the arrival tolerance, so it was left there, and the
task (openness at least 0.95) failed (the existing corpus's open_box_easy/alt_folder, seed 2). A part to be shut is
left within that tolerance as before: the tasks judge shut to `SHUT`.
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

from humanoidgen.episodes.plans import folder_plan_text
from humanoidgen.planning.recoveries.grip_again import _short_of_push_end
from plan_runs import run_plan

CORPUS = Path(__file__).parents[1] / "bench" / "foreign_plans"


def _ctx(push_to: float | None):
    push = None if push_to is None else SimpleNamespace(spec=SimpleNamespace(push=SimpleNamespace(to=push_to)))
    return SimpleNamespace(targets=SimpleNamespace(push=lambda name, oid: push))


def _regrip(openness: float, reached: float):
    return SimpleNamespace(openness=openness, reached=reached)


OBJ = SimpleNamespace(type_name="box", obj_id=0)


def test_short_of_an_openness_near_the_push_end_is_short():
    assert _short_of_push_end(_ctx(1.0), OBJ, _regrip(0.95, 0.75), 0.94)
    assert not _short_of_push_end(_ctx(1.0), OBJ, _regrip(0.95, 0.75), 0.95)  # there
    assert not _short_of_push_end(_ctx(1.0), OBJ, _regrip(0.95, 0.75), 0.97)  # past it, toward the end
    assert not _short_of_push_end(_ctx(1.0), OBJ, _regrip(0.6, 0.75), 0.58)  # a stage in the middle
    assert not _short_of_push_end(_ctx(None), OBJ, _regrip(0.95, 0.75), 0.94)  # the task has no push
    assert not _short_of_push_end(_ctx(0.0), OBJ, _regrip(0.02, 0.3), 0.04)  # to be shut: shut enough


def test_a_lid_that_swung_on_short_of_the_openness_asked_is_pushed_home(tmp_path):
    folder = CORPUS / "open_box_easy" / "alt_folder"
    plan = folder_plan_text(folder)
    result = run_plan(tmp_path, "open_box_easy", 2, plan)
    events = [e for s in result.steps for e in s.events]
    assert result.success, [s.error for s in result.steps if not s.ok] or result.checks
    assert any("is pushed on to" in e and "instead of gripped again" in e for e in events), events
