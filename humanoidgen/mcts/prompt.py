"""The expansion prompt: the task, the scene at set-up, the code executed to reach the node, what happened
(planner events, success conditions), the failure that ended the last branch here and the actions already
tried from here (prohibited as the next action). Options for minimal guidance: no operation annotations for
cubes (nor what their points mean) and short task descriptions."""

from __future__ import annotations

from humanoidgen.generation import context, prompts
from humanoidgen.mcts.tree import Node, Tree
from humanoidgen.sandbox import language

TEMPLATE = "mcts_expand.md"
SHORT_DESCRIPTIONS = {
    "block_stack_single": "Stack cube 1 on cube 0.",
    "blocks_stack_easy": "Stack the two cubes using both hands.",
    "blocks_stack_hard": "Stack the three cubes: 0 at the bottom, then 1, then 2.",
    "pyramid_stack": "Build a pyramid: cubes 0 and 1 side by side, cube 2 on top.",
}
MINIMAL_HIDDEN_TYPES = ("cube",)  # families whose operation annotations minimal guidance hides


def task_description(name: str, description: str, short: bool) -> str:
    return SHORT_DESCRIPTIONS.get(name, description) if short else description


def attributes(scene: dict, minimal: bool) -> list[dict]:
    """The scene's attribute entries; minimal guidance drops the cubes' operation annotations (how to pick
    them up), leaving the model to find out by trial."""
    out = []
    for a in scene["attributes"]:
        if minimal and a.get("type") in MINIMAL_HIDDEN_TYPES:
            a = {k: v for k, v in a.items() if k != "operations"}
        out.append(a)
    return out


def _fenced(steps: list[tuple[str, str]]) -> str:
    return "\n".join(f"```python\n# step: {' '.join(t.split())}\n{c.rstrip()}\n```" for t, c in steps)


def tried_actions(tree: Tree, node: Node) -> list[str]:
    """Code of every action already tried from `node`: its children's units and the failed first steps."""
    out = [_fenced(tree.nodes[c].unit.steps) for c in node.children]
    seen = set(out)
    for f in node.failures:
        text = _fenced([(f["title"], f["code"])])
        if text not in seen:
            seen.add(text)
            out.append(text)
    return out


def expansion_prompt(tree: Tree, node: Node, names: list[str], minimal: bool = False,
                     short: bool = False) -> str:
    meta = tree.meta
    scene, hands = meta["scene"], meta["hands"]
    ex_task, ex_plan = context.example_plan("open_drawer" if minimal else "block_stack_single")
    executed = tree.plan(node)
    last = node.failures[-1] if node.failures else None
    error = ("(none)" if last is None else
             f"The step after the executed ones failed:\n{_fenced([(last['title'], last['code'])])}\n{last['error']}")
    tried = tried_actions(tree, node)
    return prompts.render(
        prompts.load(TEMPLATE), LAYOUT=context.layout_text(),
        ATTRIBUTES=context.compact_json(attributes(scene, minimal)), VOCABULARY=prompts.scene_vocabulary(
            scene, MINIMAL_HIDDEN_TYPES if minimal else ()),
        LANGUAGE=language.rules_text("mcts"),
        STATUS=context.compact_json(node.status or scene["status"]), HANDS=context.hands_text(hands),
        NAMES=", ".join(f"`{n}`" for n in names), API=context.api_reference(), EXAMPLE_TASK=ex_task,
        EXAMPLE=ex_plan, DESCRIPTION=task_description(meta["task"], meta["description"], short).strip(),
        EXECUTED=_fenced(executed) if executed else "(none: the scene is as it was set up)",
        EVENTS="\n".join(f"- {e}" for e in node.events) or "- (none)",
        CHECKS="\n".join(f"- [{'ok' if c['ok'] else 'not met'}] {c['predicate']}: {c['detail']}"
                         for c in node.checks) or "- (not judged)",
        ERROR=error, PROHIBITED="\n".join(tried) if tried else "(none)")


def root_prompt(view, names: list[str], minimal: bool = False, short: bool = False) -> str:
    """The tree search's first expansion prompt for a scene (`prompt_preview.SceneView`): no step run yet."""
    tree = Tree(meta={"task": view.task, "description": view.description, "seed": view.seed,
                      "spec": view.spec_data, "scene": view.scene, "hands": view.hands, "expansions": []})
    tree.add(None, None, None)
    return expansion_prompt(tree, tree.root, names, minimal, short)
