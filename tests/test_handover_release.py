"""A mid-air hand-over: the giving hand lets go only once the taking hand holds the object alone
(`planning/handover.py`).

block_handover seed 0: the right hand presents the block at the hand-over pose and the left hand pinches its free
end, as the task's reference plan does."""

from __future__ import annotations

import numpy as np
import pytest

from humanoidgen.planning.recoveries import hand_over as handover
from humanoidgen.planning.hand_ops import finger_contacts, is_held
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402


def _mid_air(close_left: bool = True):
    _, env = build_scene(load_task("block_handover"), 0)
    planner = task_planner(env, seed=0)
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints("cube", 0, "pinch", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    planner.hand_pinch("right", "cube", 0)
    c = planner.generate_constraints("cube", 0, "target", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=0)
    planner.hand_pre_pinch("left")
    c = planner.generate_constraints("cube", 0, "pinch", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left")
    cube = env.scene.object("cube", 0)
    if close_left:
        planner.hand_pinch("left", "cube", 0)
    else:  # the fingers stay open around the end: the left hand "holds" nothing
        planner.ctx.hands["left"].held, planner.ctx.hands["left"].grip = cube, "pinch"
    return env, planner, cube


@pytest.fixture(scope="module")
def taken():
    return _mid_air()


@pytest.mark.slow
def test_a_real_pinch_holds_alone_and_the_trial_changes_nothing(taken):
    env, planner, cube = taken
    qpos, action, events = env.data.qpos.copy(), planner.ctx.action.copy(), list(planner.events)
    approach = {s: None if a is None else np.array(a) for s, a in ((s, h.last_approach) for s, h in planner.ctx.hands.items())}
    assert handover.holds_alone(planner.ctx, "right", "left", cube)
    assert np.array_equal(env.data.qpos, qpos) and np.array_equal(planner.ctx.action, action)
    assert planner.events == events and planner.holding["right"] is cube and planner.holding["left"] is cube
    assert all((a is None and planner.ctx.hands[s].last_approach is None) or np.allclose(a, planner.ctx.hands[s].last_approach)
               for s, a in approach.items())


@pytest.mark.slow
def test_open_fingers_do_not_hold_alone():
    env, planner, cube = _mid_air(close_left=False)
    assert not handover.holds_alone(planner.ctx, "right", "left", cube)


@pytest.mark.slow
def test_a_grip_that_would_not_hold_is_taken_again_deeper(monkeypatch):
    env, planner, cube = _mid_air()
    verdicts = iter([False, True])
    monkeypatch.setattr(handover, "holds_alone", lambda *a: next(verdicts))
    axis = np.asarray(planner.ctx.hands["left"].last_approach, float)
    before = env.hand_pose("left")[0].copy()
    handover.secure_taker(planner.ctx, "right", cube)
    moved = env.hand_pose("left")[0] - before
    assert float(moved @ axis) == pytest.approx(handover.REGRIP_DEPTHS[0], abs=0.003)  # in along the way it came
    assert "took it again 6 mm deeper" in planner.events[-1]
    assert is_held(finger_contacts(env.model, env.data, "left", cube.body))


@pytest.mark.slow
def test_where_no_deeper_grip_holds_the_first_one_is_kept_and_said(monkeypatch):
    env, planner, cube = _mid_air()
    monkeypatch.setattr(handover, "holds_alone", lambda *a: False)
    qpos = env.data.qpos.copy()
    recorded = []
    planner.on_step = recorded.append
    handover.secure_taker(planner.ctx, "right", cube)
    assert np.array_equal(env.data.qpos, qpos)
    assert recorded == []  # the deeper grips tried were trials: no frame of them is recorded
    assert "may not hold cube 0 alone" in planner.events[-1]


@pytest.mark.slow
def test_open_hand_of_the_giver_asks_first(monkeypatch):
    env, planner, cube = _mid_air()
    asked = []
    monkeypatch.setattr(handover, "secure_taker", lambda p, giver, obj: asked.append((giver, obj.obj_id)))
    planner.open_hand("right")
    assert asked == [("right", 0)]
    planner.open_hand("left")  # nobody else holds it: no hand-over
    assert asked == [("right", 0)]


@pytest.mark.slow
def test_where_the_taker_would_drop_it_the_giver_keeps_it(monkeypatch):
    """No deeper grip holds alone and the trial lets the object fall out of the taker's fingers: open_hand fails
    with what the trial showed and a way to do it instead; the giver still holds the object and nothing moved."""
    from humanoidgen.planning.errors import PlanningError

    env, planner, cube = _mid_air()
    assert handover.release_trial(planner.ctx, "right", "left", cube)[1]  # the real pinch: held
    monkeypatch.setattr(handover, "holds_alone", lambda *a: False)
    monkeypatch.setattr(handover, "release_trial", lambda *a: (0.104, False))
    qpos = env.data.qpos.copy()
    with pytest.raises(PlanningError) as err:
        planner.open_hand("right")
    msg = str(err.value)
    assert "open_hand" in msg and "would not hold cube 0 alone" in msg and "no longer held it (it had moved 104 mm" in msg
    assert "through the table" in msg  # the one thing to do instead
    assert planner.holding["right"] is cube and np.array_equal(env.data.qpos, qpos)
