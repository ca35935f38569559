"""A task judged on a process (tasks/watch.py, tasks/held_move.py): close_drawer is done when the left hand,
holding the handle, pushed the drawer shut, as the paper words it, not when the drawer is shut by whatever
(random joint targets knock it shut in most scenes). The trusted replay and the gym environment watch every
control step; a resumed replay goes back to what it had seen at the state it resumes from."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from types import SimpleNamespace  # noqa: E402

import pytest  # noqa: E402

from humanoidgen.episodes.action_log import ActionLog, packed  # noqa: E402
from humanoidgen.episodes.replay_judge import ReplayJudge  # noqa: E402
from humanoidgen.tasks import held_move  # noqa: E402
from humanoidgen.tasks.judge import judge  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402
from humanoidgen.tasks.watch import Watch  # noqa: E402
from plan_runs import task_planner  # noqa: E402

TASK = "close_drawer"


def _checks(report: dict) -> dict[str, bool]:
    return {c["predicate"]: c["ok"] for c in report["checks"]}


def _shut(grasp: bool, seed: int = 0):
    """The drawer shut by the left hand holding its handle (the reference plan's way), or pushed shut by the
    index fingertip on its front (the way the reference plan went before the task judged the process)."""
    spec = load_task(TASK)
    _, env = build_scene(spec, seed)
    log = ActionLog(env.data)
    planner = task_planner(env, seed=seed, on_step=log)
    marks = []
    if grasp:
        planner.hand_pre_grasp("left")
        c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left")
        planner.move_to_pose_with_screw(planner.generate_end_effector_pose(c, hand_name="left")[1], "left")
        planner.hand_grasp("left", grasp_object="drawer", obj_id=0)
        marks.append(len(log))
        c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="grasp", hand_name="left", openness=0)
        planner.move_to_pose_with_screw(planner.generate_end_effector_pose(c, hand_name="left")[1], "left",
                                        attach_obj=True, object_name="drawer", object_id=0)
        planner.open_hand("left")
    else:
        planner.hand_pre_grasp("left")
        c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left")
        planner.move_to_pose_with_screw(planner.generate_end_effector_pose(c, hand_name="left")[1], "left")
        planner.hand_press("left")
        planner.ignore_collision("drawer", 0)
        c = planner.generate_constraints(obj_name="drawer", obj_id=0, action="target1", hand_name="left", openness=0)
        planner.move_to_pose_with_screw(planner.generate_end_effector_pose(c, hand_name="left")[1], "left")
    return spec, log, marks


def test_pushed_shut_holding_the_handle_is_done_and_pushed_shut_by_a_fingertip_is_not():
    spec, log, marks = _shut(grasp=True)
    judge_ = ReplayJudge(spec, 0)
    full = _checks(judge_.report({"actions": packed(log.array())}))
    assert full == {"openness_at_most": True, "moved_while_held": True}
    # resumed from the kept state after the whole log, a shorter log (the handle grasped, not pushed yet) is
    # judged on what it saw itself, not on what the longer one did
    early = judge_.report({"actions": packed(log.array()[:marks[0]])})
    assert _checks(early) == {"openness_at_most": False, "moved_while_held": False}
    assert _checks(judge_.report({"actions": packed(log.array())})) == full  # and back again
    spec, log, _ = _shut(grasp=False)
    pushed = ReplayJudge(spec, 0).report({"actions": packed(log.array())})
    assert _checks(pushed) == {"openness_at_most": True, "moved_while_held": False}
    detail = next(c["detail"] for c in pushed["checks"] if c["predicate"] == "moved_while_held")
    assert "not done" in detail and "0.40 wanted" in detail


def _fake(monkeypatch, frames):
    """Openness and the left hand's touching fingers, frame by frame, without a simulation."""
    it = iter(frames)
    state = {}
    monkeypatch.setattr(held_move, "_obj", lambda env, ref: SimpleNamespace(body="part"))
    monkeypatch.setattr(held_move, "_openness", lambda m, d, obj, part: state["o"])
    monkeypatch.setattr(held_move, "finger_contacts", lambda m, d, side, body: state["touch"])

    def step():
        state["o"], state["touch"] = next(it)
    return step


def _watched(monkeypatch, pred, frames):
    """A task of `pred` alone, its watch having seen `frames`: (spec, env, watch)."""
    step = _fake(monkeypatch, frames)
    spec = SimpleNamespace(success=[pred])
    env = SimpleNamespace(model=None, data=SimpleNamespace(time=0.0))
    watch = Watch(spec, env)
    for _ in frames:
        step()
        watch.observe()
        env.data.time += 0.02  # a control step at 50 Hz
    return spec, env, watch


HELD, TIP = {"thumb", "index", "middle"}, {"index"}
LET_GO = [(0.3, set())] * 30  # 0.6 s without the thumb against a finger: longer than a grip's flicker


@pytest.mark.parametrize("frames,done", [
    ([(0.6, HELD), (0.3, HELD), (0.04, HELD), (0.02, set())], True),  # one hold, 0.56 of the way: done
    ([(0.6, TIP), (0.3, TIP), (0.02, TIP)], False),  # pushed by a fingertip: never held
    ([(0.6, HELD), (0.3, HELD), *LET_GO, (0.3, HELD), (0.04, HELD)], False),  # two holds of 0.3 and 0.26
    # one hold whose squeeze flickers (a fist pushing a handle): 0.1 s gaps do not end it
    ([(0.6, HELD), (0.45, {"pinky"}), *[(0.3, {"pinky"})] * 5, (0.3, HELD), (0.04, HELD)], True),
    ([(0.6, HELD), (0.45, {"pinky"}), *[(0.3, {"pinky"})] * 30, (0.3, HELD), (0.04, HELD)], False),  # 0.6 s: two
    ([(0.6, HELD), (0.45, set()), (0.3, set()), (0.3, HELD), (0.04, HELD)], False),  # off the handle: two holds
    ([(0.6, set()), (0.2, HELD), (0.04, HELD)], False),  # knocked most of the way, then held the last 0.16
    ([(0.6, HELD), (0.1, HELD), (0.1, HELD)], False),  # held 0.5 of the way but never at 0.05
])
def test_one_hold_must_move_the_part_the_whole_travel_and_reach_the_value(monkeypatch, frames, done):
    pred = held_move.MovedWhileHeld(obj="drawer[0]", side="left", toward="closed", value=0.05, travel=0.4)
    spec, env, watch = _watched(monkeypatch, pred, frames)
    assert judge(spec, env, watch)[0]["ok"] is done
    # judged on a state alone, nothing was watched: it does not hold
    unwatched = judge(spec, env)[0]
    assert unwatched["ok"] is False and "none was watched" in unwatched["detail"]


def test_the_gym_environment_watches_its_steps():
    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.policies.baseline_eval import blind

    env = HumanoidTaskEnv(TASK, config=blind(TaskEnvConfig()))
    obs, info = env.reset(seed=100_000)
    obs, _, _, _, info = env.step(obs["joint_pos"])
    held = next(c for c in info["checks"] if c["predicate"] == "moved_while_held")
    assert held["ok"] is False and "not done" in held["detail"]  # watched: it says what it saw
    env.close()


@pytest.mark.parametrize("frames,done", [
    # a lid lifted in stages on a fingertip, the finger off it for a moment between stages
    ([(0.15, TIP), (0.4, TIP), (0.4, set()), (0.4, TIP), (0.8, TIP), (1.0, TIP)], True),
    ([(0.15, TIP), (0.3, set()), (0.97, set()), (1.0, set())], False),  # flicked: it flew on without the hand
    ([(0.15, TIP), (0.5, TIP), (1.0, TIP), (0.9, TIP)], True),  # done once done: the watch keeps it
    ([(0.15, TIP), (0.8, TIP), (0.8, set()), (0.97, set())], False),  # carried 0.65, then it fell over alone
    # jiggled: up 0.5 under the hand, back down without it, up again: net 0.5 under the hand, not the 1.0 gone up
    ([(0.15, TIP), (0.65, TIP), (0.15, set()), (0.65, TIP), (0.97, set())], False),
])
def test_a_part_carried_by_the_hand_on_it_counts_and_one_flicked_does_not(monkeypatch, frames, done):
    pred = held_move.MovedWhileTouched(obj="box[0]", side="right", toward="open", value=0.95, travel=0.7)
    spec, env, watch = _watched(monkeypatch, pred, frames)
    assert judge(spec, env, watch)[0]["ok"] is done


def test_a_part_with_a_joint_of_its_own_is_measured_on_that_joint(monkeypatch):
    """rotate_safe_knob's knob turns on its own joint: the predicate reads that joint's openness, not the door's."""
    parts = []
    pred = held_move.MovedWhileHeld(obj="safe[0]", part="knob", side="right", toward="open", value=0.75, travel=0.5)
    step = _fake(monkeypatch, [(0.0, HELD), (0.4, HELD), (0.8, HELD)])
    real = held_move._openness
    monkeypatch.setattr(held_move, "_openness", lambda m, d, obj, part: parts.append(part) or real(m, d, obj, part))
    spec, env = SimpleNamespace(success=[pred]), SimpleNamespace(model=None, data=SimpleNamespace(time=0.0))
    watch = Watch(spec, env)
    for _ in range(3):
        step()
        watch.observe()
        env.data.time += 0.02
    check = judge(spec, env, watch)[0]
    assert check["ok"] is True and "safe 0's knob" in check["detail"]
    assert set(parts) == {"knob"}


@pytest.mark.parametrize("task,kind", [
    ("open_drawer", "moved_while_held"), ("rotate_safe_knob", "moved_while_held"),
    ("open_safe_door", "moved_while_held"), ("close_box_hard", "moved_while_held"),
    ("close_laptop_hard", "moved_while_held"), ("press_toaster", "moved_while_touched"),
    ("open_laptop_easy", "moved_while_touched"), ("open_box_hard", "moved_while_touched"),
])
def test_tasks_the_paper_words_as_a_process_judge_it(task, kind):
    """Each of these tasks' success also asks how the part got there (the paper's wording; a flail passed over 10%
    of scenes on the end state alone: docs/results/baselines.md), and judged on a state alone it does not hold."""
    spec = load_task(task)
    assert kind in [p.type for p in spec.success]
    _, env = build_scene(spec, 0)
    checks = judge(spec, env)
    assert not all(c["ok"] for c in checks)
    assert any(c["predicate"] == kind and "none was watched" in c["detail"] for c in checks)
