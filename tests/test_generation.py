"""LLM-driven scene and script generation, end to end over real HTTP to a scripted loopback server."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import re  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402
from typer.testing import CliRunner  # noqa: E402

from humanoidgen.episodes.plans import load_plan  # noqa: E402
from humanoidgen.generation import evaluate, generate_scene, generate_script, prompts  # noqa: E402
from humanoidgen.generation.extract import extract_steps  # noqa: E402
from humanoidgen.generation.scene_gen import SceneGenerationError  # noqa: E402
from humanoidgen.generation.script_gen import step_names  # noqa: E402
from humanoidgen.generation.worker import setup as worker_setup  # noqa: E402
from humanoidgen.llm import LLMClient, LLMConfig  # noqa: E402
from humanoidgen.llm.fake_server import Response, ScriptedServer  # noqa: E402
from humanoidgen.sandbox import SandboxWorker, check_code, strip_api_imports  # noqa: E402
from humanoidgen.tasks.registry import SPECS_DIR, load_task  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402

PAPER = Path(__file__).resolve().parents[2] / "shared" / "seed" / "000_e9c4b55f5fa1a6bf.txt"

STACK_YAML = """name: two_cube_stack
description: With the right hand, put cube 1 on top of cube 0.
arms: single
horizon: short
objects:
  - {type: cube, type_id: 0, pos: [-0.32, -0.05]}
  - {type: cube, type_id: 1, pos: [-0.34, -0.19]}
randomization:
  position: [-0.01, 0.01, -0.02, 0.02]
  yaw_deg: [-15, 15]
success:
  - {type: stacked, objs: ["cube[0]", "cube[1]"]}
time_limit_s: 20
"""
BAD_YAML = STACK_YAML.replace("type: cube, type_id: 1", "type: teapot, type_id: 0")


def answer(yaml_text: str) -> str:
    return f"Two cubes within the right hand's reach.\n```yaml\n{yaml_text}```\n"


def fenced(steps: list[tuple[str, str]]) -> str:
    return "Plan:\n" + "\n".join(f"```python\n# step: {t}\n{c}\n```" for t, c in steps)


REFERENCE = [(s.title, s.code) for s in load_plan(SPECS_DIR / "block_stack_single.py").steps]
GOOD_PLAN = fenced(REFERENCE)
# Third step fails in the planner: the right hand closes where no cube is.
THIRD_STEP_FAILS = fenced([("ready", 'planner.hand_pre_pinch("right")'), ("note", "x = 1"),
                           ("close on cube 0", 'planner.hand_pinch("right", pinch_object="cube", obj_id=0)')])


def client_for(srv: ScriptedServer, **kw) -> LLMClient:
    return LLMClient(LLMConfig(base_url=srv.base_url, model="scripted", backoff_s=0.01, max_retries=2, **kw))


@pytest.fixture(scope="module")
def worker():
    with SandboxWorker(worker_setup) as w:
        yield w


# -- prompts -----------------------------------------------------------------------------------------------
def test_prompts_are_filled_from_live_data() -> None:
    text = prompts.scene_prompt("stack two cubes")
    assert "{{" not in text and "stack two cubes" in text
    assert "[-0.42, -0.19]" in text and "pinch@" in text and "`stacked`" in text  # ranges, annotations, predicates
    api = prompts.context.api_reference()
    for name in ("hand_pre_pinch", "generate_constraints", "move_to_pose_with_screw", "get_point_in_env",
                 "Constraint(", "point2point", "pinch_point_base_right_hand"):
        assert name in api
    with pytest.raises(prompts.TemplateError):
        prompts.render("{{A}} {{B}}", A="x")


# -- scene generation -------------------------------------------------------------------------------------
def test_valid_scene_is_accepted_saved_and_builds(tmp_path: Path) -> None:
    out = tmp_path / "task.yaml"
    with ScriptedServer([answer(STACK_YAML)]) as srv:
        spec, log = generate_scene("stack two cubes", client_for(srv), out=out)
        assert "stack two cubes" in srv.requests[0]["messages"][0]["content"]
    assert len(log) == 1 and log[0]["problems"] == [] and log[0]["tokens"]["total"] > 0
    loaded = load_task(out)  # `hgen run path/to/task.yaml` loads it this way
    assert loaded == spec and loaded.name == "two_cube_stack"
    scene, _ = build_scene(loaded, seed=0)
    assert [o.type_name for o in scene.objects] == ["cube", "cube"]


def test_unknown_asset_is_repaired_on_second_turn(tmp_path: Path) -> None:
    def second_turn(req: dict) -> str:
        last = req["messages"][-1]["content"]
        assert "unknown object type 'teapot'" in last and len(req["messages"]) == 3, last
        return answer(STACK_YAML)

    with ScriptedServer([answer(BAD_YAML), second_turn]) as srv:
        spec, log = generate_scene("stack two cubes", client_for(srv), out=tmp_path / "t.yaml")
        assert not srv.errors
    assert len(log) == 2 and "teapot" in log[0]["problems"][0] and log[1]["problems"] == []
    assert spec.objects[1].type == "cube"


def test_bad_layout_is_reported_and_repair_budget_bounded() -> None:
    crowded = STACK_YAML.replace("[-0.34, -0.19]", "[-0.32, -0.06]").replace("[-0.32, -0.05]", "[0.1, 0.5]")
    with ScriptedServer(default=answer(crowded)) as srv, pytest.raises(SceneGenerationError) as err:
        generate_scene("stack", client_for(srv), max_repairs=1)
    problems = err.value.log[0]["problems"]
    assert len(err.value.log) == 2 and any("operable range" in p for p in problems)


def test_rate_limit_then_success_is_retried() -> None:
    with ScriptedServer([Response.error(429), answer(STACK_YAML)]) as srv:
        spec, _ = generate_scene("stack two cubes", client_for(srv))
        assert len(srv.requests) == 2 and spec.name == "two_cube_stack"


# -- script generation ------------------------------------------------------------------------------------
def test_correct_plan_succeeds_and_replays(worker: SandboxWorker, tmp_path: Path) -> None:
    out, log = tmp_path / "plan.py", tmp_path / "log.json"
    with ScriptedServer([GOOD_PLAN]) as srv:
        result = generate_script("block_stack_single", client_for(srv), attempts=2, worker=worker, out=out,
                                 log_path=log)
        prompt = srv.requests[0]["messages"][0]["content"]
    assert result.success and len(result.attempts) == 1, result.attempts[-1].failure
    assert "cube" in prompt and "Right hand operable range" in prompt and "hand_pinch(" in prompt
    assert all(s.ok for s in result.attempts[0].steps) and all(c["ok"] for c in result.attempts[0].checks)
    assert [s.code for s in load_plan(out).steps] == [c for _, c in REFERENCE]  # `hgen run --script` format
    assert '"prompt"' in log.read_text() and result.attempts[0].tokens["prompt"] > 0


def test_failing_third_step_is_reported_and_replay_is_identical(worker: SandboxWorker, tmp_path: Path) -> None:
    rec = tmp_path / "rec.jsonl"
    with ScriptedServer([THIRD_STEP_FAILS, THIRD_STEP_FAILS]) as srv:
        live = generate_script("block_stack_single", client_for(srv, mode="record", recording_path=rec),
                               attempts=2, worker=worker)
        retry_prompt = srv.requests[1]["messages"][-1]["content"]
        url = srv.base_url
    first = live.attempts[0]
    assert not live.success and len(live.attempts) == 2
    assert [s.ok for s in first.steps] == [True, True, False]
    assert first.steps[2].error_type == "PlanningError" and "does not hold cube 0" in first.steps[2].message
    assert first.failure.startswith("Step 3 (close on cube 0) failed") and "does not hold cube 0" in retry_prompt
    # The server is gone: the recording answers, and every outcome is the same.
    replay = LLMClient(LLMConfig(base_url=url, model="scripted", mode="replay", recording_path=rec))
    replayed = generate_script("block_stack_single", replay, attempts=2, worker=worker)

    def essence(r):
        return [(a.prompt, a.response, a.tokens, a.failure, a.checks,
                 [(s.ok, s.error_type, s.message, s.line) for s in a.steps]) for a in r.attempts]

    assert essence(replayed) == essence(live) and all(a.cached for a in replayed.attempts)


def test_hostile_code_is_rejected_or_stopped_and_generation_goes_on(worker: SandboxWorker) -> None:
    hostile = fenced([("a", "import os"), ("b", "open('/etc/passwd')"), ("c", "x = ().__class__.__bases__")])
    loop = fenced([("spin", "for i in range(10**12):\n    pass")])
    bomb = fenced([("bomb", "x = [0] * (4 * 10**8)")])
    with ScriptedServer([hostile, loop, bomb, GOOD_PLAN]) as srv:
        result = generate_script("block_stack_single", client_for(srv), attempts=4, worker=worker,
                                 step_timeout_s=6.0)
    a1, a2, a3, a4 = result.attempts
    assert [s.error_type for s in a1.steps] == ["CodeRejected"] * 3 and "rejected before running" in a1.failure
    for needle in ("import", "open", "__class__"):
        assert needle in a1.failure
    assert a2.steps[0].error_type == "Timeout"
    assert a3.steps[0].error_type in {"MemoryError", "WorkerDied"}
    assert a4.success and result.success


# -- evaluation and CLI -----------------------------------------------------------------------------------
def test_evaluate_rows(worker: SandboxWorker) -> None:
    with ScriptedServer(default=THIRD_STEP_FAILS) as srv:
        rows = evaluate(["block_stack_single"], 2, client_for(srv), worker=worker)
    (row,) = rows
    assert row.task == "block_stack_single" and row.success_rate == 0 and row.tokens_per_success is None
    assert row.mean_tokens > 0


def test_cli_without_endpoint_says_so(monkeypatch) -> None:
    from humanoidgen.cli.generate_cmd import EXIT_NOT_CONFIGURED, app

    monkeypatch.delenv("OPENAI_BASE_URL", raising=False)
    res = CliRunner().invoke(app, ["eval", "--tasks", "block_stack_single", "--trials", "1"])
    assert res.exit_code == EXIT_NOT_CONFIGURED and "no LLM endpoint configured" in res.output


def test_cli_scene_and_unreachable(tmp_path: Path) -> None:
    from humanoidgen.cli.generate_cmd import app

    out = tmp_path / "task.yaml"
    with ScriptedServer([answer(STACK_YAML)]) as srv:
        res = CliRunner().invoke(app, ["scene", "stack", "--out", str(out), "--base-url", srv.base_url])
        port = srv.port
    assert res.exit_code == 0, res.output
    assert load_task(out).name == "two_cube_stack"
    res = CliRunner().invoke(app, ["scene", "stack", "--out", str(out), "--base-url",
                                   f"http://127.0.0.1:{port}/v1", "--retries", "0"])
    assert res.exit_code == 1 and "cannot reach" in res.output


# -- the paper's sample plans -----------------------------------------------------------------------------
def _paper_plans() -> list[str]:
    text = PAPER.read_text()
    out = []
    for title in ("Sample Demonstration Code for Open Drawer", "Sample Demonstration Code for Block Stack Hard"):
        start = text.index(r"\begin{mycodebox}", text.index(title))
        body = text[text.index("\n", start) + 1: text.index(r"\end{mycodebox}", start)]
        out.append(body)
    return out


@pytest.mark.skipif(not PAPER.is_file(), reason="paper text not available")
def test_paper_sample_plans_pass_the_checker() -> None:
    names = set(step_names())
    for body in _paper_plans():
        assert re.search(r"^from humanoidgen\S* import \*$", body, re.M)
        checked = check_code(strip_api_imports(body), names)
        assert checked.defines_step
        assert extract_steps(f"```python\n{body}```")  # and split into a step as an LLM answer
