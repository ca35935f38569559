"""A held part the arm can move only partway: let go, grip it again and go on, or stop where it stays.

close_box_hard seed 1 starts with the lid nearly upright (openness 0.9); one grasp of its front carries it only to
about 0.5 before the wrist runs out, and there the free-running lid neither stays nor falls shut. The move then
lets go, grasps it again and takes it to the openness asked. A laptop's screen stays where it is left (its hinge's
friction holds it): a move that gets it most of the way stops there with an event. A part that, let go, goes on to
the openness asked by itself (a screen let go at 0.17 on its way shut falls shut) is not gripped again; one that fell
on toward it and stopped short is pushed the rest of the way where the task defines a push that way.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from humanoidgen.planning.part_joint import part_stays
from humanoidgen.planning.recoveries.grip_again import arrived
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene
from plan_runs import run_plan

CORPUS = Path(__file__).parents[1] / "bench" / "foreign_plans"

# Written as the paper's prompt teaches: grasp the part, move it to an openness, let go.
CLOSE_BY_GRASP = '''
def step(planner):
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints(obj_name="{obj}", obj_id=0, action="grasp", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_grasp("right", grasp_object="{obj}", obj_id=0)

def step(planner):
    c = planner.generate_constraints(obj_name="{obj}", obj_id=0, action="grasp", hand_name="right", openness=0.3)
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="{obj}", object_id=0)
    planner.open_hand("right")
'''


def _corpus(plan: str, seed: int):
    """A plan of bench/foreign_plans (written apart from the planner), run as the corpus bench runs it."""
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    result, _ = run_task_episode(EpisodeRequest(plan.split("/")[0], seed, plan_path=str(CORPUS / plan)))
    return result


def _run(tmp_path, task: str, obj: str, seed: int):
    result = run_plan(tmp_path, task, seed, CLOSE_BY_GRASP.format(obj=obj))
    assert all(s.ok for s in result.steps), [s.error for s in result.steps]
    return result


def test_whether_a_part_stays_where_it_is_let_go():
    _, env = build_scene(load_task("close_box_hard"), 1)
    box = env.scene.object("box", 0)
    joint = f"{box.body}_{box.annotations.articulation.joint}"
    art = box.annotations.articulation
    assert not part_stays(env, joint, art.joint_position(0.3))  # a free-running lid falls from low down
    _, env = build_scene(load_task("close_laptop_hard"), 1)
    laptop = env.scene.object("laptop", 0)
    art = laptop.annotations.articulation
    assert part_stays(env, f"{laptop.body}_{art.joint}", art.joint_position(0.5))  # a screen's hinge holds it


@pytest.mark.slow
def test_a_lid_beyond_one_grasp_is_gripped_again_and_closed_but_not_in_one_hold(tmp_path):
    # Letting go and gripping again takes time: this plan needs 27-29 s, past the task's 25 s but within the plan's
    # budget (episodes.replay.PLAN_TIME_FACTOR times it).
    result = _run(tmp_path, "close_box_hard", "box", 1)
    assert any("grips it again" in e for e in result.events), result.events
    shut = next(c for c in result.checks if c["predicate"] == "openness_at_most")
    assert shut["ok"], result.checks  # the lid closed
    # The task asks more than the lid shut: lowered to 0.35 within one hold, as the paper words it ("while
    # maintaining its grasp"). Gripped again twice on the way (at 0.63 and 0.52), no one hold did that: the
    # episode is not a success, and the check says how far the longest hold went.
    held = next(c for c in result.checks if c["predicate"] == "moved_while_held")
    assert not held["ok"] and "longest hold moved it" in held["detail"], held
    assert not result.success


def test_a_screen_that_stays_is_gripped_again_or_left_where_the_arm_ends(tmp_path):
    # Most of the way there and staying put, a second grip is tried but its failure is not the move's.
    result = _run(tmp_path, "close_laptop_hard", "laptop", 1)
    events = [e for s in result.steps for e in s.events]
    assert any("grips it again" in e for e in events), events
    openness = result.objects["laptop[0]"]["openness"]
    if any("stays at openness" in e for e in events):
        assert openness < 0.7  # it did move most of the way from ~0.84
    else:
        assert openness < 0.4  # taken on to the 0.3 asked


def test_a_part_let_go_near_the_openness_asked_has_arrived():
    assert arrived(now=0.0, wanted=0.0)  # a screen let go on its way shut fell shut
    assert arrived(now=0.04, wanted=0.0)  # within the tolerance
    assert not arrived(now=0.12, wanted=0.0)
    assert not arrived(now=0.14, wanted=0.3)  # past it: a lid resting on the fingers, gripped again as before
    assert not arrived(now=0.4, wanted=0.85)  # fell back


# A corpus plan (written outside the planner): pinch the screen's edge and turn it to openness 0, in one move.
PINCH_CLOSE = Path(__file__).resolve().parents[1] / "bench" / "foreign_plans" / "close_laptop_easy" / "alt_pinch_close.py"


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="since the grip anchor (part_grip.slid_since_grip) the hand carries this seed's "
                   "screen over 46% of its arc, not to 0.17: it is let go higher, gripped again and taken shut (the "
                   "plan succeeds), so the fall-shut case no longer arises here; it needs a new case")
def test_a_screen_that_falls_shut_when_let_go_is_not_gripped_again(tmp_path):
    """Seed 5: the arm's reach ends at 0.17 holding the screen; let go there it falls shut. Gripped again (lifted to
    0.25 with a fingertip to make room for the fingers) it was left at 0.20."""
    result = run_plan(tmp_path, "close_laptop_easy", 5, PINCH_CLOSE.read_text())
    assert result.success, result.message
    events = [e for s in result.steps for e in s.events]
    assert any("by itself when let go" in e and "not gripped again" in e for e in events), events


@pytest.mark.slow
def test_a_screen_that_falls_most_of_the_way_is_pushed_on_not_gripped_again(tmp_path):
    """Seed 6: let go at 0.25 the screen falls to 0.08. Gripped again, it was first lifted ajar to 0.24 for the
    fingers and the grip came off at 0.20; the task's fingertip push takes it from 0.08 to shut."""
    result = run_plan(tmp_path, "close_laptop_easy", 6, PINCH_CLOSE.read_text())
    assert result.success, result.message
    events = [e for s in result.steps for e in s.events]
    assert any("is pushed on to 0 with the fingertip" in e for e in events), events


# A screen lifted in stages with one hold (the corpus's open_laptop_hard/alt_pinch_lift): after 0.3 and 0.6 the
# wrist is turned so far that the last stage gets only 0.63 -> 0.68 of the 0.85 asked, less than REGRIP_MIN_SHARE
# of the way; the move used to fail there ("can move it only from openness 0.63 to 0.68").


# Seed 0: the goal search finds the last stage's goal only partway (goal_search); seed 1: it solves the stage, but
# from the arm as it settled in the grip the move's own track of the screen ends at once (part_grip
# `_regrip_from_here`): both let go there and go on.
@pytest.mark.parametrize("seed", [0, 1])
def test_a_part_that_stays_is_gripped_again_where_the_grip_gets_hardly_any_further(seed):
    result = _corpus("open_laptop_hard/alt_pinch_lift.py", seed)
    events = [e for s in result.steps for e in s.events]
    assert any("grips it again" in e or "went on to openness" in e for e in events), events
    assert result.success, (result.failed_step.error if result.failed_step else None, result.checks)


# Pinch the screen's edge and turn it shut, as the paper's prompt teaches (the corpus's
# close_laptop_easy/alt_pinch_close). Taken shut in the fingers, the thumb ends between screen and base: every way
# of letting go dragged the screen, and the hand going home lifted it to 0.48 (seed 2). A part to be shut that
# is let go on its way (seed 2: where the arm's reach ends) or stops short in the hand (seed 7: at 0.17) is
# pushed shut with the task's fingertip push instead of gripped again.


@pytest.mark.parametrize("seed", [2, 7])
def test_a_part_to_be_shut_is_pushed_shut_not_taken_shut_in_the_fingers(seed):
    result = _corpus("close_laptop_easy/alt_pinch_close.py", seed)
    events = [e for s in result.steps for e in s.events]
    assert any("is pushed on to 0 with the fingertip" in e for e in events), events
    assert result.success, (result.failed_step.error if result.failed_step else None, result.checks)


# The corpus's open_box_easy/alt_folder: pinch the lid's tab, lift it to 0.5 then 0.95. Let go where the arm's
# reach ends (0.68), the lid went on to 0.82 and the fingertip pushed it on to 0.95 came to 0.90, just under the
# task's 0.9 on some seeds; asked that near the end of the task's push (1.0), it is pushed to the end.


def test_a_part_asked_near_the_end_of_the_tasks_push_is_pushed_to_that_end():
    result = _corpus("open_box_easy/alt_folder", 0)
    events = [e for s in result.steps for e in s.events]
    assert any("is pushed on to 1 with the fingertip" in e for e in events), events
    assert result.objects["box[0]"]["openness"] > 0.97
    assert result.success, result.checks


# The corpus's close_box_easy/alt_grasp_lid: grasp the lid's tab and turn it shut. Seed 0: taken shut in the
# fingers, every way of letting go dragged the lid back to 0.28 (now: let go at 0.2 and pushed shut). Seed 5: the
# tab slipped out of the fingers at once, "the grip came off" (then: the task's push shut it from there); since the
# grasp centres under the tab's tip (the box's lid_grip) it holds, and seed 5 goes as seed 0.


@pytest.mark.parametrize("seed, why", [(0, "not shut in its fingers"), (5, "not shut in its fingers")])
def test_a_lid_to_be_shut_is_let_go_short_of_shut_and_pushed_shut(seed, why):
    result = _corpus("close_box_easy/alt_grasp_lid.py", seed)
    events = [e for s in result.steps for e in s.events]
    assert any(why in e for e in events) and any("is pushed on to 0 with the fingertip" in e for e in events), events
    assert result.success, (result.failed_step.error if result.failed_step else None, result.checks)
