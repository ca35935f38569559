"""MCTS script generation (issue 7): DUCB arithmetic, STCR merging on an in-memory executor, and the search on
the real sandbox with a scripted loopback LLM (a model that needs the prohibited-actions list to get past a bad
third step, and one that succeeds at once), plan replay and tree-log round trips."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import math  # noqa: E402
from pathlib import Path  # noqa: E402
from types import SimpleNamespace  # noqa: E402

import pytest  # noqa: E402
from typer.testing import CliRunner  # noqa: E402

from humanoidgen.episodes.plans import load_plan  # noqa: E402
from humanoidgen.generation.worker import setup as worker_setup  # noqa: E402
from humanoidgen.llm import LLMClient, LLMConfig  # noqa: E402
from humanoidgen.llm.fake_server import ScriptedServer  # noqa: E402
from humanoidgen.mcts import (  # noqa: E402
    EXPAND, MCTS, FakeExecutor, MCTSConfig, SandboxExecutor, Tree, Unit, combine, discounted, ducb,
    evaluate_mcts, normalize_code, search_plan, truncate, write_outputs,
)
from humanoidgen.mcts.stcr import intrinsic_reward, valuable_events  # noqa: E402
from humanoidgen.mcts.prompt import attributes  # noqa: E402
from humanoidgen.sandbox import SandboxWorker  # noqa: E402
from humanoidgen.tasks.registry import SPECS_DIR  # noqa: E402

REFERENCE = [(s.title, s.code) for s in load_plan(SPECS_DIR / "block_stack_single.py").steps]
BAD_PINCH = 'planner.hand_pinch("right", pinch_object="cube", obj_id=0)'  # wrong cube: hand_pinch fails


def fenced(steps: list[tuple[str, str]]) -> str:
    return "Plan:\n" + "\n".join(f"```python\n# step: {t}\n{c}\n```" for t, c in steps)


def section(prompt: str, head: str) -> str:
    start = prompt.index(f"## {head}")
    end = prompt.find("\n## ", start + 3)
    return prompt[start: end if end >= 0 else None]


def steps_done(prompt: str) -> int:
    return section(prompt, "Steps already executed").count("# step:")


def stubborn_model(plan_ok: list[tuple[str, str]], bad: tuple[str, str], at: int):
    """Continues the plan from the executed steps; step `at` is `bad` unless the prompt prohibits it."""
    def answer(prompt: str) -> str:
        prohibited = bad[1] in section(prompt, "Prohibited next actions")
        plan = list(plan_ok)
        if not prohibited:
            plan[at] = bad
        return fenced(plan[steps_done(prompt):])
    return answer


class FakeClient:
    """LLMClient stand-in for pure tests: answer(prompt) -> text; records prompts."""

    def __init__(self, answer) -> None:
        self.answer, self.prompts = answer, []

    def chat(self, messages):
        self.prompts.append(messages[-1]["content"])
        return SimpleNamespace(text=self.answer(messages[-1]["content"]), usage=SimpleNamespace(total=10),
                               cached=False)


FAKE_SPEC = {"name": "fake", "description": "pinch then release"}


# -- pure ---------------------------------------------------------------------------------------------------
def test_ducb_and_discounted_counts_match_hand_computation() -> None:
    tree = Tree(gamma=0.5)
    root = tree.add(None, None, {})
    a = tree.add(root.id, Unit([("a", "x = 1")]), {})
    b = tree.add(root.id, Unit([("b", "x = 2")]), {})
    a.rewards, b.rewards, root.expand_rewards = [1, 0, 1], [0], [1]
    # W_A = 0.25*1 + 0.5*0 + 1*1, N_A = 1 + 0.5 + 0.25
    assert discounted(a.rewards, 0.5) == pytest.approx((1.25, 1.75))
    scores = dict(tree.scores(root))  # total N = 1.75 + 1 + 1 = 3.75
    assert scores[a.id] == pytest.approx(1.25 / 1.75 + math.sqrt(2 * math.log(3.75) / 1.75))  # 1.943
    assert scores[b.id] == pytest.approx(math.sqrt(2 * math.log(3.75)))  # 1.626
    assert scores[EXPAND] == pytest.approx(1 + math.sqrt(2 * math.log(3.75)))  # 2.626
    assert tree.select() == [root.id]
    # Virtual loss: the in-flight expansion counts as a newest visit with reward 0.
    tree.begin([root.id])
    assert discounted(root.expand_rewards, 0.5, running=1) == pytest.approx((0.5, 1.5))
    assert tree.select() == [root.id, a.id]  # A: 0.714 + 1.286 = 2.000 > expand: 0.333 + 1.389 > B: 1.701
    tree.backprop([root.id], 0.0)
    assert root.expand_running == 0 and root.expand_rewards == [1, 0]
    c = tree.add(root.id, Unit([("c", "x = 3")]), {})
    assert tree.select() == [root.id, c.id] and ducb(0, 0, 5) == math.inf  # unvisited edges first


def test_stcr_segment_truncate_combine() -> None:
    steps = [("pre", "planner.hand_pre_pinch('right')"), ("go", "planner.move_to_pose_with_screw(p, 'right')"),
             ("pinch", "planner.hand_pinch('right', 'cube', 1)"), ("lift", "planner.move_to_pose_with_screw(q)")]
    units = combine(steps)
    assert [len(u.steps) for u in units] == [3, 1] and units[0].title == "pinch"
    assert truncate(steps, [True, True, False]) == steps[:2]
    assert normalize_code("x  =  1  # c\n\n\ny=2") == normalize_code("x = 1\ny = 2")
    assert valuable_events(["pinched cube 1 with the right hand", "released cube 1 and it stayed on nothing",
                            "released cube 1 and it is still moving", "released cube 1 and it stayed on cube 0"]) \
        == ["pinched cube 1 with the right hand", "released cube 1 and it stayed on cube 0"]
    assert intrinsic_reward([], [{"ok": False}], [{"ok": True}]) == 1.0
    scene = {"attributes": [{"type": "cube", "operations": ["pinch@pinch"]}, {"type": "drawer", "operations": []}]}
    assert [("operations" in a) for a in attributes(scene, minimal=True)] == [False, True]


P = ("pinch", "planner.hand_pinch('right', 'cube', 1)\n# event: pinched cube 1 with the right hand")
L = ("lift", "planner.move_to_pose_with_screw(up)")
F = ("put", "planner.move_to_pose_with_screw(fail)")
G = ("put", "planner.move_to_pose_with_screw(above_cube_0)\nplanner.open_hand('right')\n"
     "# event: released cube 1 and it stayed on cube 0")


def test_repeated_branches_are_merged_and_prohibited_actions_listed() -> None:
    client = FakeClient(lambda p: fenced([P, L, F][steps_done(p):]))  # ignores prohibitions
    ex = FakeExecutor(goal=["above_cube_0"])
    result = MCTS(FAKE_SPEC, client, [ex], config=MCTSConfig(expansions=3, verify=False)).run()
    tree, log = result.tree, result.log
    assert not result.success and len(tree.nodes) == 3  # root, pinch, lift: the third answer merged
    assert [e["node"] for e in log] == [0, 2, 0] and log[2]["new_nodes"] == [] and log[2]["end_node"] == 2
    assert len(tree.nodes[2].failures) == 3 and [e["reward"] for e in log] == [1.0, 0.0, 1.0]
    assert "above_cube_0" not in section(client.prompts[1], "Prohibited") and "fail" in section(client.prompts[1],
                                                                                           "Prohibited")
    assert all(n.running == 0 and n.expand_running == 0 for n in tree.nodes)


def test_parallel_fake_search_solves_and_releases_virtual_loss(tmp_path: Path) -> None:
    client = FakeClient(lambda p: fenced([P, L, G][steps_done(p):]))
    exs = [FakeExecutor(goal=["above_cube_0"]) for _ in range(2)]
    result = MCTS(FAKE_SPEC, client, exs, config=MCTSConfig(expansions=4)).run()
    written = write_outputs(result, tmp_path / "plan.py")
    assert set(written) == {"plan", "log", "picture"} and "# step: put" in written["plan"].read_text()
    assert result.success and result.verified and [t for t, _ in result.plan] == ["pinch", "lift", "put"]
    assert all(n.running == 0 and n.expand_running == 0 for n in result.tree.nodes)
    assert 1 <= result.expansions_run <= 2  # a second one may be in flight when the first succeeds


# -- real sandbox, scripted loopback LLM --------------------------------------------------------------------
def client_for(srv: ScriptedServer) -> LLMClient:
    return LLMClient(LLMConfig(base_url=srv.base_url, model="scripted", backoff_s=0.01, max_retries=2))


@pytest.fixture(scope="module")
def executor():
    with SandboxWorker(worker_setup) as w:
        yield SandboxExecutor(w)


def test_search_gets_past_a_bad_step_and_tree_log_round_trips(executor: SandboxExecutor, tmp_path: Path) -> None:
    answer = stubborn_model(REFERENCE, ("close on cube 0", BAD_PINCH), at=2)
    plan_path = tmp_path / "plan.py"
    with ScriptedServer(default=lambda req: answer(req["messages"][-1]["content"])) as srv:
        first = search_plan("block_stack_single", client_for(srv), expansions=1, executors=[executor],
                            out=plan_path)
        assert not first.success and not plan_path.exists()
        log = plan_path.with_suffix(".tree.json")
        assert log.is_file() and plan_path.with_suffix(".tree.png").stat().st_size > 0
        tree = first.tree
        assert [n.unit.title for n in tree.nodes[1:]] == ["pinch cube 1 with the right hand", "lift cube 1"]
        assert "does not hold cube 0" in tree.nodes[2].failures[0]["error"]
        assert tree.nodes[1].rewards == [] and tree.root.expand_rewards == [1.0]  # "pinched cube 1": valuable
        # Continue from the saved log (snapshots included): the next expansion resumes at the lift node.
        second = search_plan("block_stack_single", client_for(srv), expansions=3, executors=[executor],
                             tree=log, out=plan_path)
        prompt = srv.requests[-1]["messages"][-1]["content"]
    assert second.success and second.expansions_run == 1 and len(second.log) == 2, second.log[-1]["failure"]
    assert BAD_PINCH in section(prompt, "Prohibited") and steps_done(prompt) == 2
    assert "does not hold cube 0" in section(prompt, "Last failure")
    assert [c for _, c in second.plan] == [c for _, c in REFERENCE]
    assert second.verified is True  # re-ran to success from a fresh reset
    assert [s.code for s in load_plan(plan_path).steps] == [c for _, c in REFERENCE]
    loaded = Tree.load(log)
    assert loaded.solution() is not None and loaded.meta["verified"] is True
    assert loaded.to_dict() == second.tree.to_dict()


def test_search_stops_after_one_expansion_when_the_first_answer_works(executor: SandboxExecutor) -> None:
    with ScriptedServer(default=fenced(REFERENCE)) as srv:
        rows = evaluate_mcts(["block_stack_single"], 1, client_for(srv), expansions=4, executors=[executor],
                             results=(runs := []))
        assert len(srv.requests) == 1
    (run,) = runs
    assert run.success and run.expansions_run == 1 and run.verified
    # Units: pinch | lift + put-and-release | back away (the end).
    assert [len(n.unit.steps) for n in run.tree.nodes[1:]] == [1, 2, 1]
    (row,) = rows
    assert row.success_rate == 1 and row.distinct_plans == 1 and row.tokens_per_success == row.tokens_per_run > 0


def test_cli_script_mcts_with_two_workers(tmp_path: Path) -> None:
    from humanoidgen.cli.generate_cmd import app

    answer = stubborn_model(REFERENCE, ("close on cube 0", BAD_PINCH), at=2)
    out = tmp_path / "plan.py"
    with ScriptedServer(default=lambda req: answer(req["messages"][-1]["content"])) as srv:
        res = CliRunner().invoke(app, ["script", "block_stack_single", "--mcts", "4", "--workers", "2", "--out",
                                       str(out), "--base-url", srv.base_url])
    assert res.exit_code == 0, res.output
    assert "replayed from a fresh reset: success" in res.output
    assert [s.code for s in load_plan(out).steps] == [c for _, c in REFERENCE]
    tree = Tree.load(out.with_suffix(".tree.json"))
    assert len(tree.nodes) == 5 and len(tree.meta["expansions"]) <= 4  # merged: one pinch node, one lift node
    assert out.with_suffix(".tree.png").is_file()
