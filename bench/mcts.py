"""Tree-search overhead with a replayed model: time per expansion excluding the LLM (restore the node's
snapshot, run and judge the new steps), on block_stack_single. The scripted model first answers with a wrong
third step, then, once that action is prohibited, with the right continuation.

Usage: python bench/mcts.py
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

from humanoidgen.episodes.plans import load_plan  # noqa: E402
from humanoidgen.llm import LLMClient, LLMConfig  # noqa: E402
from humanoidgen.llm.fake_server import Response, ScriptedServer  # noqa: E402
from humanoidgen.mcts import search_plan  # noqa: E402
from humanoidgen.tasks.registry import SPECS_DIR  # noqa: E402

STEPS = [(s.title, s.code) for s in load_plan(SPECS_DIR / "block_stack_single.py").steps]


def fenced(steps):
    return "\n".join(f"```python\n# step: {t}\n{c}\n```" for t, c in steps)


BAD_THIRD = STEPS[:2] + [("pinch the other cube", 'planner.hand_pinch("right", pinch_object="cube", obj_id=0)')]


def model(request: dict) -> Response:
    prompt = request["messages"][-1]["content"]
    if 'pinch_object="cube", obj_id=0' in prompt.split("Prohibited", 1)[-1] or "PROHIBITED" in prompt and \
            'obj_id=0)' in prompt.split("PROHIBITED", 1)[-1]:
        return Response(fenced(STEPS[2:]))
    return Response(fenced(BAD_THIRD))


def main() -> None:
    with ScriptedServer([], default=model) as server, tempfile.TemporaryDirectory() as tmp:
        client = LLMClient(LLMConfig(base_url=server.base_url, model="scripted"))
        result = search_plan("block_stack_single", client, expansions=6, seed=0, out=Path(tmp) / "plan.py")
        runs = [e["run_seconds"] for e in result.tree.meta["expansions"] if "run_seconds" in e]
    print(f"search: {'success' if result.success else 'no plan'} after {result.expansions_run} expansions, "
          f"replay check {'passed' if result.verified else 'not passed'}")
    for i, r in enumerate(runs):
        print(f"  expansion {i}: {r:.2f} s without the LLM")


if __name__ == "__main__":
    main()
