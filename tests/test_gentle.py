"""A lid brought down, not slammed (tasks/gentle.py): the part's speed over every 0.1 s window of the episode,
watched every control step; close_box_easy and close_laptop_easy ask it beside the lid shut, since random joint
targets slam their lids shut in over 10% of scenes."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from types import SimpleNamespace  # noqa: E402

import pytest  # noqa: E402

from humanoidgen.tasks import gentle  # noqa: E402
from humanoidgen.tasks.judge import judge  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402
from humanoidgen.tasks.watch import Watch  # noqa: E402

DT = 0.02  # a control step at 50 Hz


def _watched(monkeypatch, pred, openings):
    """The predicate's verdict after a watch saw the part at `openings`, one control step apart."""
    state = {}
    monkeypatch.setattr(gentle, "_obj", lambda env, ref: SimpleNamespace(body="part"))
    monkeypatch.setattr(gentle, "_openness", lambda m, d, obj, part: state["o"])
    spec = SimpleNamespace(success=[pred])
    env = SimpleNamespace(model=None, data=SimpleNamespace(time=0.0))
    watch = Watch(spec, env)
    for o in openings:
        state["o"] = o
        watch.observe()
        env.data.time += DT
    return judge(spec, env, watch)[0], watch


def _ramp(start, end, seconds):
    n = round(seconds / DT)
    return [start + (end - start) * k / n for k in range(n + 1)]


@pytest.mark.parametrize("openings,ok", [
    (_ramp(0.5, 0.0, 1.0), True),  # pressed shut over a second: 0.5 of its range a second
    (_ramp(0.5, 0.0, 0.25), False),  # slammed shut in a quarter second: 2 a second
    (_ramp(0.5, 0.5, 0.5) + _ramp(0.5, 0.45, 0.02) + _ramp(0.45, 0.45, 0.5), True),  # a 0.05 jolt: 0.5 a second
    (_ramp(0.5, 0.2, 0.1) + _ramp(0.2, 0.0, 2.0), False),  # knocked down 0.3 in 0.1 s, then pressed gently
])
def test_a_part_brought_down_gently_passes_and_a_slammed_one_does_not(monkeypatch, openings, ok):
    pred = gentle.MovedGently(obj="box[0]", max_speed=1.0)
    check, _ = _watched(monkeypatch, pred, openings)
    assert check["ok"] is ok, check["detail"]
    assert ("within" if ok else "over") in check["detail"]


def test_what_it_saw_goes_back_with_a_resumed_replay(monkeypatch):
    pred = gentle.MovedGently(obj="box[0]", max_speed=1.0)
    _, watch = _watched(monkeypatch, pred, _ramp(0.5, 0.4, 0.2))
    kept = watch.saved()
    watch.memory[0].fastest = 9.0
    watch.restore(kept)
    assert watch.memory[0].fastest == pytest.approx(0.5, abs=0.05)


@pytest.mark.parametrize("task", ["close_box_easy", "close_laptop_easy"])
def test_the_easy_close_tasks_ask_it_and_a_state_alone_does_not_meet_it(task):
    spec = load_task(task)
    assert "moved_gently" in [p.type for p in spec.success]
    _, env = build_scene(spec, 0)
    check = next(c for c in judge(spec, env) if c["predicate"] == "moved_gently")
    assert check["ok"] is False and "none was watched" in check["detail"]
