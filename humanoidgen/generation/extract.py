"""Pulling YAML specs and plan steps out of LLM answers, and writing plans in our `# step:` format."""

from __future__ import annotations

import re

from humanoidgen.episodes.plans import STEP_MARK
from humanoidgen.sandbox.checker import split_steps

_YAML_FENCE = re.compile(r"```[ \t]*(?:yaml|yml)[ \t]*\n(.*?)```", re.DOTALL | re.IGNORECASE)
_ANY_FENCE = re.compile(r"```[ \t]*\w*[ \t]*\n(.*?)```", re.DOTALL)
_TITLE = re.compile(r"^\s*#\s*step\s*\d*\s*[:.-]?\s*(.*)$", re.IGNORECASE)


class ExtractError(ValueError):
    pass


def extract_yaml(text: str) -> str:
    """The last ```yaml block (models often sketch a draft first); else the only fenced block."""
    blocks = _YAML_FENCE.findall(text)
    if not blocks:
        blocks = _ANY_FENCE.findall(text)
        if len(blocks) != 1:
            raise ExtractError("the answer has no ```yaml block with the task specification")
    return blocks[-1].strip() + "\n"


def extract_steps(text: str) -> list[tuple[str, str]]:
    """(title, code) per fenced python block; the title comes from a leading `# step: ...` comment."""
    out = []
    for i, code in enumerate(split_steps(text)):
        lines = code.splitlines()
        title = f"step {i + 1}"
        if lines and (m := _TITLE.match(lines[0])):
            title, lines = (m.group(1).strip() or title), lines[1:]
        body = "\n".join(lines).strip("\n")
        if body.strip():
            out.append((title, body))
    return out


def plan_text(steps: list[tuple[str, str]], header: str = "") -> str:
    """Our plan format: `# step: <title>` comment lines, each followed by the step's code."""
    head = "".join(f"# {ln}\n" for ln in header.splitlines())
    body = "\n".join(f"# step: {' '.join(t.split())}\n{_defuse(code).rstrip()}\n" for t, code in steps)
    return head + body


def _defuse(code: str) -> str:
    """A comment inside a step that reads like a step mark ("# Step 2: ...") would split the step on replay."""
    return "\n".join(re.sub(r"^(\s*)#", r"\1# -", ln, count=1) if STEP_MARK.match(ln.strip()) else ln
                     for ln in code.splitlines())
