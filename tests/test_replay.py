"""The verdict the plan cannot forge (episodes/replay.py, replay_judge.py): the robot's commands re-simulated
outside the plan's process decide success, and the recording comes from that replay.

In-process tests drive a planner with the worker's command log (`ActionLog`) and feed a `Replay`; the
end-to-end ones run cheating plans through `run_task_episode`, `collect` and `hgen generate script`."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from pathlib import Path  # noqa: E402

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from humanoidgen.episodes.action_log import ActionLog, packed, unpack  # noqa: E402
from humanoidgen.episodes.recorder import RecorderConfig  # noqa: E402
from humanoidgen.episodes.replay import CHANGED, PLAN_TIME_FACTOR, OverTime, Replay, over_time  # noqa: E402
from humanoidgen.episodes.replay_twin import TwinReplay  # noqa: E402
from humanoidgen.episodes.replay_judge import ReplayJudge  # noqa: E402
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode  # noqa: E402
from humanoidgen.planning.snapshot import trial  # noqa: E402
from humanoidgen.sim.fingerprint import fingerprint  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402
from plan_runs import run_plan, task_planner  # noqa: E402

TASK = "block_stack_single"


def _run(seed: int = 0):
    """The task's scene and a planner whose every command is logged, as in the plan worker."""
    spec = load_task(TASK)
    _, env = build_scene(spec, seed)
    log = ActionLog(env.data)
    return spec, env, log, task_planner(env, seed=seed, on_step=log)


def _replayed(spec, log: ActionLog, seed: int = 0, **kw) -> Replay:
    replay = Replay.build(spec, seed, **kw)
    replay.feed(log.array(), np.stack(log.qpos))
    return replay


def test_an_honest_run_with_trials_replays_bit_for_bit():
    """Simulated trials (the hand-over's and part release's kind: `snapshot.trial`) leave nothing in the log and
    the replay reaches the worker's very state, bit for bit."""
    spec, env, log, planner = _run()
    planner.hand_pre_pinch("right")
    with trial(planner.ctx):  # moves in the simulation itself, then undone: not the robot's commands
        planner.ctx.move_fingers(("right",), "pinch", seconds=0.4)
        planner.ctx.settle(0.2)
    n_trial = len(log)
    planner.hand_pre_grasp("left")
    planner.ctx.settle(0.3)
    assert len(log) > n_trial > 0
    replay = _replayed(spec, log)
    assert replay.problem is None
    assert np.array_equal(replay.env.data.qpos, env.data.qpos) and np.array_equal(replay.env.data.qvel, env.data.qvel)
    verdict = replay.finish(env.data.qpos.copy(), fingerprint(env.model, env.data))
    assert verdict.problem is None and verdict.steps == len(log)


def test_a_state_write_is_caught_where_it_happens_and_says_what_moved():
    spec, env, log, planner = _run()
    planner.hand_pre_pinch("right")
    m, d = env.model, env.data
    cube = m.jnt_qposadr[m.body("cube_1").jntadr[0]]
    d.qpos[cube + 2] += 0.04  # lift cube 1 by hand-writing its pose
    mujoco.mj_forward(m, d)
    planner.ctx.settle(0.1)
    replay = _replayed(spec, log)
    assert replay.problem is not None and replay.problem.startswith(CHANGED)
    assert "cube[1]" in replay.problem
    verdict = replay.finish()
    assert not verdict.ok and verdict.all_checks()[-1]["predicate"] == "replay"


def test_a_model_edit_is_named():
    spec, env, log, planner = _run()
    env.model.opt.gravity[:] = (0.0, 0.0, 3.0)  # cubes float up
    env.model.body_mass[env.model.body("cube_0").id] *= 10
    planner.ctx.settle(0.2)
    replay = _replayed(spec, log)
    verdict = replay.finish(env.data.qpos.copy(), fingerprint(env.model, env.data))
    assert not verdict.ok
    assert "opt.gravity" in verdict.problem and "body_mass" in verdict.problem


def test_a_plan_that_stops_early_is_judged_once_the_scene_is_still():
    """The replay holds the robot's last command until every object is still (at most 1 s, counting what the
    log already held): a plan that ends with an object in flight is judged where it lands."""
    spec, env, log, planner = _run()
    m, d = env.model, env.data
    planner.ctx.settle(0.02)
    replay = _replayed(spec, log)
    cube = m.jnt_qposadr[m.body("cube_1").jntadr[0]]
    replay.env.data.qpos[cube + 2] += 0.02  # (the replay's own scene, as if the commands had tossed it)
    mujoco.mj_forward(replay.env.model, replay.env.data)
    verdict = replay.finish()
    assert verdict.events and "until the scene was still" in verdict.events[0]
    assert verdict.steps > len(log)
    del d


def test_the_replay_records_the_episode_arrays():
    spec, env, log, planner = _run()
    planner.hand_pre_pinch("right")
    replay = _replayed(spec, log, recorder=RecorderConfig(every=2, cameras=("head",)))
    verdict = replay.finish()
    arrays = verdict.arrays
    assert arrays is not None and len(arrays["action"]) == (len(log) + 1) // 2
    assert np.array_equal(arrays["qpos"], np.stack(log.qpos[::2]))  # the worker's states, simulated here
    assert np.array_equal(arrays["action"], log.array()[::2].astype(np.float32))
    assert verdict.configurations is not None and verdict.configurations.shape == (len(arrays["action"]), env.model.nq)


class _Channel:
    def __init__(self) -> None:
        self.posted: list = []

    def post(self, message, timeout_s: float) -> None:
        self.posted.append(message)


def test_the_time_budget_stops_the_feed():
    """The parent counts the commands as they arrive: one chunk past the plan's time budget (PLAN_TIME_FACTOR
    times the task's time limit, plus the second for the scene to come to rest) is never passed on, and
    OverTime stops the worker; the replay stops at the same count and says so."""
    spec = load_task(TASK)
    budget_s = PLAN_TIME_FACTOR * spec.time_limit_s
    channel = _Channel()
    feed = TwinReplay(channel, spec, 50.0)
    hold, where = np.zeros((50, 26)), np.zeros((50, 52))
    with pytest.raises(OverTime):
        for _ in range(int(budget_s) + 2):
            feed.feed({"actions": hold, "qpos": where})
    assert len(channel.posted) == int(budget_s) + 1
    flood = TwinReplay(_Channel(), spec, 50.0)  # empty or broken chunks are not passed on, and still end
    with pytest.raises(OverTime):
        for _ in range(10 * flood.max_steps):
            flood.feed({"actions": np.zeros((0, 26)), "qpos": np.zeros((0, 52))})
    assert flood.malformed and flood.channel.posted == []
    replay = Replay.build(spec, 0)
    replay.feed(np.tile(replay.env.init_action(), (replay.max_steps + 1, 1)))
    assert replay.problem == over_time(spec, 50.0) and not replay.finish().ok
    assert f"time budget ({budget_s:g} s of simulated time: {PLAN_TIME_FACTOR:g} x the task's time limit of " \
           f"{spec.time_limit_s:g} s" in replay.problem


def test_a_plan_idling_past_its_budget_is_stopped_saying_so(tmp_path: Path):
    """Honest commands that only open and close a hand, past the budget: the worker is stopped in the step,
    with the budget in seconds (a task limit of 2 s here: a budget of 2 x 2 s)."""
    code = "# step: idle\nfor i in range(100):\n    planner.hand_pre_grasp('right')\n    planner.hand_pre_pinch('right')\n"
    result = run_plan(tmp_path, TASK, 0, code, time_limit_s=2)
    assert not result.success
    assert result.steps[-1].title == "idle"
    assert f"time budget ({2 * PLAN_TIME_FACTOR:g} s of simulated time: {PLAN_TIME_FACTOR:g} x the task's " \
           "time limit of 2 s, plus 1 s for the scene to come to rest)" in result.steps[-1].error


def test_a_plan_slower_than_its_tasks_time_limit_but_within_the_budget_succeeds(tmp_path: Path):
    """The time limit is the policy's horizon, not a demonstration's pace: the reference plan, run against a
    limit it passes by a third (9 s; it takes about 12.5 s), succeeds and is judged by its replay."""
    from humanoidgen.tasks.registry import plan_path

    text = plan_path(load_task(TASK)).read_text()
    result = run_plan(tmp_path, TASK, 3, text, time_limit_s=9)
    assert result.success, result.failed_step or result.checks
    assert result.sim_seconds >= 1.3 * 9  # well past the task's limit
    assert all(c["predicate"] != "replay" for c in result.checks)


def test_malformed_logs_are_rejected_not_crashed():
    spec = load_task(TASK)
    replay = Replay.build(spec, 0)
    replay.feed(np.full((3, 26), np.nan))
    assert "not finite" in replay.problem
    replay = Replay.build(spec, 0)
    replay.feed([[0.0] * 26])
    assert "malformed" in replay.problem
    with pytest.raises(ValueError):
        unpack("not base64 at all!", 10)
    with pytest.raises(ValueError):
        unpack(packed(np.zeros((20, 26))), 10)  # longer than allowed


def test_the_judge_resumes_from_a_shared_prefix_and_agrees_with_a_fresh_replay():
    spec, env, log, planner = _run()
    planner.hand_pre_pinch("right")
    first = log.array()
    planner.hand_pre_grasp("left")
    judge = ReplayJudge(spec, 0)
    a = judge.report({"actions": packed(first)})
    b = judge.report({"actions": packed(log.array()), "qpos": env.data.qpos.copy()})  # resumes after `first`
    fresh = ReplayJudge(spec, 0).report({"actions": packed(log.array()), "qpos": env.data.qpos.copy()})
    assert a["checks"] and b == fresh
    assert all(c["predicate"] != "replay" for c in b["checks"])
    bad = judge.report({"actions": packed(log.array()), "qpos": env.data.qpos + 0.1})
    assert bad["checks"][-1]["predicate"] == "replay" and CHANGED in bad["checks"][-1]["detail"]


# -- end to end: the plan worker -----------------------------------------------------------------------------
def _plan(tmp_path: Path, code: str) -> str:
    path = tmp_path / "plan.py"
    path.write_text(code)
    return str(path)


TELEPORT = """# step: put cube 1 on cube 0 by writing the simulator state
env = planner.env
m, d = env.model, env.data
a0 = m.jnt_qposadr[m.body('cube_0').jntadr[0]]
a1 = m.jnt_qposadr[m.body('cube_1').jntadr[0]]
d.qpos[a1:a1 + 3] = d.qpos[a0:a0 + 3] + np.array([0.0, 0.0, 0.04])
d.qpos[a1 + 3:a1 + 7] = d.qpos[a0 + 3:a0 + 7]
d.qvel[:] = 0
planner.hand_pre_grasp("left")
"""


def test_a_teleporting_plan_is_judged_failed_with_its_reason(tmp_path: Path):
    result, arrays = run_task_episode(EpisodeRequest(TASK, 0, plan_path=_plan(tmp_path, TELEPORT),
                                                     recorder=RecorderConfig(every=5)))
    assert all(s.ok for s in result.steps)  # the plan ran through: only the replay tells
    assert not result.success
    replay = [c for c in result.checks if c["predicate"] == "replay"]
    assert replay and CHANGED in replay[0]["detail"] and "cube[1]" in replay[0]["detail"]
    assert not next(c for c in result.checks if c["predicate"] == "stacked")["ok"]


def test_a_plan_that_floods_the_step_hook_is_stopped_at_its_time_budget(tmp_path: Path):
    """Calling the planner's step hook without simulating used to make recorded frames for free; each call is
    now a command the replay simulates, and the worker is stopped once they pass the plan's time budget."""
    code = "# step: fake frames\nfor i in range(200000):\n    planner.on_step(planner.ctx.action)\n"
    result, _ = run_task_episode(EpisodeRequest(TASK, 0, plan_path=_plan(tmp_path, code), step_timeout_s=60))
    assert not result.success
    assert result.steps[-1].error == over_time(load_task(TASK), 50.0)
    assert result.steps[-1].seconds < 30


def test_an_event_flood_is_capped(tmp_path: Path):
    code = "# step: talk a lot\nfor i in range(300000):\n    planner.events.append('x' * 100)\n"
    result, _ = run_task_episode(EpisodeRequest(TASK, 0, plan_path=_plan(tmp_path, code)))
    assert not result.success  # the task was not done
    assert len(result.events) <= 2000 and all(len(e) <= 500 for e in result.events)


def test_honest_episodes_match_their_replay_and_keep_their_recording():
    result, arrays = run_task_episode(EpisodeRequest(TASK, 1, recorder=RecorderConfig(every=10)))
    assert result.success, result.checks
    assert all(c["predicate"] != "replay" for c in result.checks)
    assert arrays is not None and len(arrays["action"]) > 10


def test_collect_keeps_no_episode_of_a_cheating_plan(tmp_path: Path):
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.dataset import EpisodeStore

    stats = collect(TASK, 1, tmp_path / "ds", plan_path=_plan(tmp_path, TELEPORT),
                    recorder=RecorderConfig(every=10), max_attempts=2)
    assert stats.kept == 0 and stats.tried == 2
    store = EpisodeStore(tmp_path / "ds")
    assert store.kept() == [] and all("outside the robot's commands" in a["error"] for a in store.attempts())


def test_collect_does_not_count_a_success_without_its_recording(monkeypatch, tmp_path: Path):
    from humanoidgen.episodes import collect as collect_mod
    from humanoidgen.episodes.result import EpisodeResult

    def fake(req, render=True, worker=None):
        return EpisodeResult(TASK, req.seed, True, [], [], 0.0, 0.0, 0.0, {}, []), None

    monkeypatch.setattr(collect_mod, "run_task_episode", fake)
    record, arrays = collect_mod.attempt(EpisodeRequest(TASK, 0, recorder=RecorderConfig()))
    assert record["success"] is False and arrays is None and "recorded nothing" in record["error"]


def test_generated_script_that_teleports_is_not_a_success(tmp_path: Path):
    """`hgen generate script` (and the tree search, through the same judge) replays the attempt's commands."""
    from humanoidgen.generation.script_gen import generate_script
    from humanoidgen.llm import LLMClient, LLMConfig
    from humanoidgen.llm.fake_server import ScriptedServer

    body = TELEPORT.split("\n", 1)[1]
    answer = f"Plan:\n```python\n# step: teleport\n{body}\n```\n"
    with ScriptedServer(default=answer) as srv:
        client = LLMClient(LLMConfig(base_url=srv.base_url, model="scripted", backoff_s=0.01, max_retries=1))
        result = generate_script(TASK, client, attempts=1, seed=0, out=tmp_path / "plan.py")
    assert not result.success and not (tmp_path / "plan.py").exists()
    assert CHANGED in result.attempts[0].failure


def test_the_tree_search_judges_a_teleport_by_its_replay():
    """The tree search's executor (one worker per scene, many judgements) asks the replay, not the worker."""
    from humanoidgen.mcts.executor import SandboxExecutor

    spec = load_task(TASK)
    ex = SandboxExecutor(step_timeout_s=60)
    try:
        ex.reset(spec.model_dump(mode="json"), 0)
        root = ex.judge()
        assert not any(c["predicate"] == "replay" for c in root["checks"])
        snap = ex.snapshot()
        assert ex.run_step(TELEPORT.split("\n", 1)[1]).ok
        verdict = ex.judge()
        assert verdict["checks"][-1]["predicate"] == "replay" and CHANGED in verdict["checks"][-1]["detail"]
        assert not all(c["ok"] for c in verdict["checks"])
        ex.restore(snap)  # a branch from the root: the log is the root's again, and honest
        assert ex.run_step('planner.hand_pre_pinch("right")').ok
        again = ex.judge()
        assert not any(c["predicate"] == "replay" for c in again["checks"])
    finally:
        ex.close()
