"""The plan language is one contract: what the prompts state (sandbox/language.py's rules) is what the checker
and the worker do, in both directions (every allowed example accepted, every refused one refused)."""

from __future__ import annotations

import ast
import re

import pytest

from humanoidgen.generation import prompts
from humanoidgen.generation.extract import extract_steps
from humanoidgen.generation.script_gen import precheck, step_names
from humanoidgen.sandbox import SandboxWorker, language
from humanoidgen.sandbox.checker import _ALLOWED_NODES, _REFUSED
from humanoidgen.sandbox.vocabulary import SAFE_BUILTINS

NAMES = step_names()
ALLOWED = [(c.name, ex) for c in language.ALLOWED for ex in c.examples]
REFUSED = [(c.name, ex) for c in language.REFUSED for ex in c.examples]


def rejected(example: str) -> list:
    """The example as an LLM writes a step (a fenced block), through the extraction and the check that
    generation runs before any step: the violations (none: accepted)."""
    steps = extract_steps(f"```python\n# step: example\n{example}\n```")
    assert steps, example
    return precheck(steps, NAMES)


@pytest.mark.parametrize("name, example", ALLOWED)
def test_every_allowed_construct_is_accepted(name: str, example: str) -> None:
    assert rejected(example) == [], f"{name}: {example!r}"


@pytest.mark.parametrize("name, example", REFUSED)
def test_every_refused_construct_is_refused(name: str, example: str) -> None:
    out = rejected(example)
    assert out and out[0].error_type == "CodeRejected", f"{name}: {example!r} was accepted"


def test_the_checker_takes_its_syntax_from_the_language() -> None:
    assert set(_ALLOWED_NODES) == set(language.allowed_nodes())
    assert _REFUSED == language.refused_nodes()
    assert not set(_ALLOWED_NODES) & set(_REFUSED)
    # Every statement and expression kind of Python is either allowed or refused by a construct of the list, or
    # never reaches the checker as a node of its own (type parameters, interactive-mode roots, ...).
    known = set(_ALLOWED_NODES) | set(_REFUSED)
    for cls in (ast.stmt, ast.expr):
        left = [t.__name__ for t in cls.__subclasses__() if t not in known and t.__name__ not in ("TypeAlias",)]
        assert left == [], f"{cls.__name__} kinds neither allowed nor refused: {left}"
    assert all(c.examples for c in language.ALLOWED + language.REFUSED)
    assert all(c.message for c in language.REFUSED if c.nodes)


def test_builtins_stated_in_the_prompt_are_exactly_those_available() -> None:
    text = language.rules_text("script")
    listed = re.search(r"Builtins: (.*?); no others", text).group(1)
    names = set(re.findall(r"`(\w+)`", listed))
    assert names == SAFE_BUILTINS - {"True", "False", "None"}
    for n in sorted(names):
        assert rejected(f"x = {n}") == [], n
    for n in language.unavailable_builtins():
        assert rejected(f"x = {n}"), f"the builtin {n} is not stated but accepted"


def test_the_templates_state_no_language_rule_by_hand() -> None:
    """The rules come only from the data: a template that says `while` or "import" itself could contradict it."""
    words = [re.escape(w) for w in ("`while`", "`try`", "`with`", "`lambda`", "`class`", "import", "carry over")]
    for name in ("script.md", "mcts_expand.md"):
        text = prompts.load(name)
        assert "{{LANGUAGE}}" in text
        assert not [w for w in words if re.search(w, text)], name


def test_the_script_prompt_states_the_rules(tmp_path) -> None:
    scene = {"attributes": [{"type": "cube", "obj_id": 0, "type_id": 0}], "status": []}
    text = prompts.script_prompt("stack", scene, {"right": {"p": [0, 0, 0], "q": [1, 0, 0, 0]}}, NAMES)
    assert language.rules_text("script") in text
    assert "Variables do not carry over" not in text and "Do not import" not in text


def test_names_carry_over_between_steps_as_the_script_prompt_says() -> None:
    """The script prompt: a name a step assigns stays defined in the steps after it (one namespace per run)."""
    assert "stay defined in the steps after it" in language.CARRY_OVER["script"]
    with SandboxWorker(dict) as w:
        assert w.run_step("x = 2\ndef twice(v):\n    return 2 * v").ok
        out = w.run_step("y = twice(x)\nassert y == 4")
        assert out.ok, out.message
    # precheck, which runs before any step of a generated plan, agrees: the second step's names are known.
    assert precheck([("a", "x = 2"), ("b", "y = x + 1")], NAMES) == []
    assert precheck([("a", "y = x + 1")], NAMES), "an unassigned name is refused"


WITH_ALLOWED = next(c for c in language.ALLOWED if c.nodes and ast.With in c.nodes)
WITH_REFUSED = next(c for c in language.REFUSED if c.message == language.WITH_MESSAGE)


def test_with_runs_in_the_worker_on_the_contexts_the_prompt_names() -> None:
    """The prompt's `with` rule, fed to both sides: each allowed example passes the checker and runs in the
    locked-down worker; each refused one is refused with the message that names what `with` may open."""
    text = language.rules_text("script")
    assert WITH_ALLOWED.name in text and WITH_REFUSED.name in text
    assert all(f"`{c}(...)`" in WITH_ALLOWED.name for c in language.WITH_CONTEXTS)
    with SandboxWorker(dict) as w:
        for example in WITH_ALLOWED.examples:
            out = w.run_step(example)
            assert out.ok, (example, out.message)
    for example in WITH_REFUSED.examples:
        out = rejected(example)
        assert out and language.WITH_MESSAGE in out[0].message, example
