"""`hgen generate prompt`: the exact prompt, printed without an endpoint, is the one generation sends."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

from pathlib import Path  # noqa: E402

from typer.testing import CliRunner  # noqa: E402

from humanoidgen.cli.generate_cmd import app  # noqa: E402
from humanoidgen.generation import generate_scene, generate_script  # noqa: E402
from humanoidgen.llm import LLMClient, LLMConfig  # noqa: E402
from humanoidgen.llm.fake_server import ScriptedServer  # noqa: E402


def _client(srv: ScriptedServer) -> LLMClient:
    return LLMClient(LLMConfig(base_url=srv.base_url, model="scripted", backoff_s=0.01, max_retries=0))


def test_script_prompt_is_the_one_generate_script_sends(monkeypatch, tmp_path: Path) -> None:
    monkeypatch.delenv("OPENAI_BASE_URL", raising=False)  # no endpoint needed to print it
    res = CliRunner().invoke(app, ["prompt", "block_stack_single", "--seed", "2", "--out", str(tmp_path / "p.md")])
    assert res.exit_code == 0, res.output
    printed = (tmp_path / "p.md").read_text()
    with ScriptedServer(["no code here"]) as srv:
        generate_script("block_stack_single", _client(srv), attempts=1, seed=2)
        sent = srv.requests[0]["messages"][0]["content"]
    assert printed == sent
    # Another seed moves the objects, so the printed prompt really comes from the seed's scene.
    other = CliRunner().invoke(app, ["prompt", "block_stack_single", "--seed", "3"])
    assert other.exit_code == 0 and other.output.strip() != printed.strip()


def test_scene_and_mcts_prompts_and_bad_input() -> None:
    res = CliRunner().invoke(app, ["prompt", "stack the yellow cube on the green one", "--kind", "scene"])
    assert res.exit_code == 0, res.output
    with ScriptedServer(["no yaml"] * 3) as srv:
        try:
            generate_scene("stack the yellow cube on the green one", _client(srv), max_repairs=0)
        except Exception:  # the scripted answer is not a scene; only the request matters here
            pass
        sent = srv.requests[0]["messages"][0]["content"]
    assert res.output.strip() == sent.strip()
    res = CliRunner().invoke(app, ["prompt", "open_drawer", "--kind", "mcts"])
    assert res.exit_code == 0, res.output
    assert "Prohibited next actions" in res.output and '"type": "drawer"' in res.output
    bad = CliRunner().invoke(app, ["prompt", "no_such_task"])
    assert bad.exit_code == 1 and "unknown task" in bad.output
    bad = CliRunner().invoke(app, ["prompt", "open_drawer", "--kind", "poem"])
    assert bad.exit_code == 1 and "unknown --kind" in bad.output
