"""The unseen cheating battery (tests/cheats_unseen/NNN_*.py): cheats written against the finished replay
verdict (issue 32) by a tester who had not read how it works, plus honest control plans.

Classes: physics made to blow up (MuJoCo's auto-reset to qpos0 shuts drawers), commands at the ends of the
ctrlrange, sub-tolerance nudges, state written only between control steps, contact options (override margin,
contacts off), geometry (geom_size/margin, the table's body_pos), actuator gains, springs and armature,
finite but absurd commands, odd command shapes and kinds (numpy subclasses, object arrays, strings), forged
events and stdout, event floods and deep nesting, a rewritten action log, idling past the time budget, the
clock rewound, a flood of step-hook calls, state fields a per-step comparison might not read (warmstart, act,
mocap, userdata, sensordata), unlogged env steps, the env's own reset, the worker's annotations, an abrupt end
(recursion), a filtered step hook, and console escape codes. Each `# task:`/`# cheat:` file must be judged a
failure with a reason by `run_task_episode`, kept by no `collect`, and reported as a failure by `hgen run`;
each `# honest: yes` file must succeed and be kept. `bench/cheats_unseen.py` runs all of them through
`hgen run --json` and `collect` and writes bench/results/cheats_unseen.json.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import json  # noqa: E402
import re  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from test_cheats import _reason, _request, _summary  # noqa: E402

DIR = Path(__file__).resolve().parent / "cheats_unseen"
_HEADER = re.compile(r"^#\s*(task|cheat|honest):\s*(.*?)\s*$")
# Run by default (the rest is marked slow): the auto-reset, sub-tolerance nudges, absurd commands, odd command
# shapes, a half-honest plan writing unobserved state fields; and the honest control with extras.
SAMPLE = ("034_cd_autoreset_blowup", "036_bss_subtolerance_nudges", "044_bss_huge_out_of_range_commands",
          "045_bss_on_step_odd_shapes", "053_bss_unobserved_state_fields", "093_bss_honest_extras")
COLLECT_CASES = ("053_bss_unobserved_state_fields", "042_cd_actuator_gain_bias")
CONSOLE_CASES = ("059_bss_console_escape_codes", "047_bss_fake_events_and_stdout")


def _plans() -> list[tuple[str, str, bool, Path]]:
    out = []
    for path in sorted(DIR.glob("[0-9][0-9][0-9]_*.py")):
        head = {}
        for line in path.read_text().splitlines()[:6]:
            if m := _HEADER.match(line):
                head[m.group(1)] = m.group(2)
        assert "task" in head and "cheat" in head, f"{path.name}: needs '# task:' and '# cheat:' header lines"
        out.append((path.stem, head["task"], head.get("honest") == "yes", path))
    return out


PLANS = _plans()
BY_NAME = {p[0]: p for p in PLANS}


def test_battery_is_complete():
    from humanoidgen.tasks.registry import load_task

    cheats = [p for p in PLANS if not p[2]]
    assert len(cheats) >= 20 and sum(p[2] for p in PLANS) >= 3
    assert len({p[0].split("_", 1)[0] for p in PLANS}) == len(PLANS), "numbers must be unique"
    old = {p.stem.split("_", 1)[0] for p in (DIR.parent / "cheats").glob("[0-9][0-9][0-9]_*.py")}
    assert not old & {p[0].split("_", 1)[0] for p in PLANS}, "numbers must not repeat tests/cheats'"
    for _, task, _, _ in PLANS:
        load_task(task)
    assert set(SAMPLE) | set(COLLECT_CASES) | set(CONSOLE_CASES) <= set(BY_NAME)


@pytest.mark.parametrize("name", [pytest.param(p[0], marks=() if p[0] in SAMPLE else pytest.mark.slow, id=p[0])
                                  for p in PLANS])
def test_judged_as_it_should_be(name):
    from humanoidgen.episodes.plans import PlanFormatError
    from humanoidgen.episodes.task_episode import run_task_episode

    _, task, honest, path = BY_NAME[name]
    try:
        result, arrays = run_task_episode(_request(task, path))
    except PlanFormatError as exc:
        assert not honest and str(exc).strip()
        return
    if honest:
        assert result.success is True, _summary(result)
        assert arrays is not None and len(arrays["action"]) > 0
        return
    assert result.success is False, f"{name} was judged a success: {_summary(result)}"
    assert _reason(result), f"{name} failed without a reason: {_summary(result)}"


@pytest.mark.parametrize("name", COLLECT_CASES)
def test_collect_keeps_none(name, tmp_path):
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.episodes.recorder import RecorderConfig

    _, task, _, path = BY_NAME[name]
    stats = collect(task, 1, tmp_path, seed=0, recorder=RecorderConfig(), plan_path=str(path), max_attempts=1)
    store = EpisodeStore(tmp_path)
    assert stats.kept == 0 and store.kept() == []
    [attempt] = store.attempts()
    assert not attempt["success"] and "changed the simulation" in attempt["error"], attempt


@pytest.mark.parametrize("name", CONSOLE_CASES)
def test_the_console_cannot_be_repainted(name, tmp_path):
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app

    _, task, _, path = BY_NAME[name]
    out = tmp_path / "run.json"
    res = CliRunner().invoke(app, ["run", task, "--seed", "0", "--script", str(path), "--json", str(out)])
    assert res.exit_code == 2 and "FAILURE" in res.output, res.output[-2000:]
    assert "\x1b" not in res.output and "\r" not in res.output and "\u202e" not in res.output
    d = json.loads(out.read_text())
    text = json.dumps(d, ensure_ascii=False)
    assert d["success"] is False and "\x1b" not in text and "\\u001b" not in text


def test_plain_text_drops_control_characters():
    from humanoidgen.sandbox.outcome import plain

    assert plain("a\x1b[2Kb\rc\u202ed\te\nf", 100) == "a\ufffd[2Kb\ufffdc\ufffdd\te\nf"
    assert plain("x\ny", 100, newlines=False) == "x y" and plain(3, 10) == "" and plain("abc", 2) == "ab"


def test_the_action_log_refuses_odd_commands_as_they_come():
    from humanoidgen.episodes.action_log import ActionLog
    from humanoidgen.sim.action import ActionError

    class _Data:
        qpos = np.zeros(3)

    log = ActionLog(_Data())
    for odd in (np.zeros(27), np.zeros((26, 1)), "1," * 26, np.full(26, np.nan), np.array([None] * 26)):
        with pytest.raises(ActionError):
            log(odd)
    log(np.zeros(26, np.float16))
    assert len(log) == 1 and log.actions[0].dtype == np.float64
