"""Plan steps from an LLM's answer or a plan file (before the checker sees them): fenced blocks, the paper's
`def step(planner): ...` form, its `from humanoidgen... import *` lines. Split from `checker`, which re-exports
`split_steps` and `strip_api_imports`."""

from __future__ import annotations

import ast
import contextlib
import re
import textwrap

STEP_FUNCTION = "step"

# The paper's scripts start with `from humanoidgen.<...>.solver_env import *`; only that exact form is stripped.
_API_IMPORT = re.compile(r"^[ \t]*(from[ \t]+humanoidgen(\.\w+)*[ \t]+import[ \t]+\*|import[ \t]+humanoidgen(\.\w+)*)"
                         r"[ \t]*(#.*)?$")
_FENCE = re.compile(r"```[ \t]*(?:python|py)?[ \t]*\n(.*?)```", re.DOTALL | re.IGNORECASE)


def strip_api_imports(source: str) -> str:
    """Blank out the paper's `from humanoidgen... import *` / `import humanoidgen...` lines (line numbers kept)."""
    return "\n".join("" if _API_IMPORT.match(line) else line for line in source.split("\n"))


def split_steps(response_text: str) -> list[str]:
    """Plan steps from an LLM response.

    Each fenced ```python (or bare ```) block is one step, dedented (the paper's blocks are indented one level)
    and with API import lines stripped. If there are no fences, the text is taken as a whole script. A block or
    script that is just `def step(planner): ...` becomes that function's body (so `planner` is the namespace's
    planner and the body runs at top level), unless the body needs its function (a `return` in it); a block with
    more (helper functions, imports) is kept whole, without explicit `step(planner)` calls, since the runner
    calls `step` after executing it.
    """
    blocks = _FENCE.findall(response_text) or [response_text]
    steps = []
    for block in blocks:
        code = _as_step(strip_api_imports(textwrap.dedent(block)).strip("\n"))
        if code.strip():
            steps.append(code)
    return steps


def _as_step(code: str) -> str:
    try:
        tree = ast.parse(code)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return code
    defs = [n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == STEP_FUNCTION]
    if not defs:
        return code
    calls = [n for n in tree.body if isinstance(n, ast.Expr) and isinstance(n.value, ast.Call)
             and isinstance(n.value.func, ast.Name) and n.value.func.id == STEP_FUNCTION]
    others = [n for n in tree.body if n not in defs and n not in calls]
    if len(defs) == 1 and not others:
        body = _function_body(code, defs[0])
        if body is not None:
            return body
    lines = code.split("\n")
    for call in calls:  # blank the call's lines unless another statement shares them (`x = 1; step(planner)`)
        span = range(call.lineno, call.end_lineno + 1)
        if not any(n is not call and (n.lineno in span or n.end_lineno in span) for n in tree.body):
            lines[call.lineno - 1: call.end_lineno] = [""] * len(span)
    return "\n".join(lines).rstrip("\n")


def _function_body(code: str, node: ast.FunctionDef) -> str | None:
    lines = code.split("\n")
    # Keep comments between the header and the first statement when the header is one line.
    for start in (node.lineno, node.body[0].lineno - 1):
        body = textwrap.dedent("\n".join(lines[start:node.body[-1].end_lineno])).strip("\n")
        with contextlib.suppress(SyntaxError, ValueError, RecursionError, MemoryError, OverflowError):
            compile(body, "<step>", "exec", dont_inherit=True)  # not only parse: `return` needs its function
            return body
    return None
