"""Plan scripts: a sequence of steps, each a block of planner-API code.

Two file forms are read:
- ours: top-level code split into steps by `# step: <title>` comment lines;
- the paper's: a `def step(planner):` function (its import line is dropped); its body is split at
  `# Step N: ...` comments when it has them, else it is one step.
A plan can also be a folder of such files (upstream's layout: `step0.py ... stepN.py`), run in natural order.

Parsing untrusted text can exhaust the parser (deeply nested code): in the episode path it happens inside
the plan worker, and every parser failure becomes a PlanFormatError.
"""

from __future__ import annotations

import ast
import re
import textwrap
from dataclasses import dataclass
from pathlib import Path

STEP_MARK = re.compile(r"^#\s*step\s*:?\s*(.*)$", re.IGNORECASE)
PAPER_STEP_MARK = re.compile(r"^\s*#\s*Step\s+\d+\s*[:.-]?\s*(.*)$", re.IGNORECASE)
FILE_MARK = "# hgen-plan-file: "
API_IMPORT = re.compile(r"^\s*(from\s+humanoidgen[\w.]*\s+import\s+.*|import\s+humanoidgen[\w.]*.*)$")


class PlanFormatError(ValueError):
    pass


@dataclass(frozen=True)
class PlanStep:
    title: str
    code: str


@dataclass(frozen=True)
class Plan:
    steps: tuple[PlanStep, ...]
    source: str = ""

    def code(self) -> str:
        return "\n".join(f"# step: {s.title}\n{s.code.rstrip()}\n" for s in self.steps)


def _split_marked(lines: list[str], mark: re.Pattern) -> list[PlanStep]:
    steps: list[PlanStep] = []
    title, body = None, []
    for line in lines:
        m = mark.match(line.strip()) if mark is STEP_MARK else mark.match(line)
        if m:
            if title is not None or any(b.strip() for b in body):
                steps.append(PlanStep(title or f"step {len(steps) + 1}", "\n".join(body).strip("\n")))
            title, body = m.group(1).strip() or f"step {len(steps) + 1}", []
        else:
            body.append(line)
    if title is not None or any(b.strip() for b in body):
        steps.append(PlanStep(title or f"step {len(steps) + 1}", "\n".join(body).strip("\n")))
    return [s for s in steps if _has_code(s.code)]


def _has_code(code: str) -> bool:
    return any(line.strip() and not line.strip().startswith("#") for line in code.splitlines())


def parse_plan(text: str) -> Plan:
    """Read a plan from text in either form, or several files' text from `folder_plan_text`."""
    if text.startswith(FILE_MARK):
        steps: list[PlanStep] = []
        for chunk in text.split(FILE_MARK)[1:]:
            name, _, body = chunk.partition("\n")
            try:
                plan = _parse_one(body)
            except PlanFormatError as exc:
                raise PlanFormatError(f"{name.strip()}: {exc}") from None
            many = len(plan.steps) > 1
            steps += [PlanStep(f"{Path(name.strip()).stem}: {s.title}" if many or s.title == "step"
                               else s.title, s.code) for s in plan.steps]
        if not steps:
            raise PlanFormatError("the plan folder has no code")
        return Plan(tuple(steps), text)
    return _parse_one(text)


STEP_FILE = re.compile(r"step\d+")


def folder_plan_text(folder: Path) -> str:
    """The step files of a plan folder as one text, in natural order (step2 before step10).

    When the folder has upstream's `step<N>.py` files, only those are the plan: upstream runs `step0`, `step1`, ...
    by name, so a stray `step3 copy.py` or `notes.py` beside them is not a step. Otherwise every `*.py` is."""
    files = sorted(Path(folder).glob("*.py"), key=lambda p: [int(t) if t.isdigit() else t
                                                              for t in re.split(r"(\d+)", p.stem)])
    numbered = [p for p in files if STEP_FILE.fullmatch(p.stem)]
    files = numbered or files
    if not files:
        raise PlanFormatError(f"{folder}: no .py step files in the plan folder")
    return "".join(f"{FILE_MARK}{p.name}\n{p.read_text(encoding='utf-8', errors='replace')}\n" for p in files)


def _parse_one(text: str) -> Plan:
    lines = [ln for ln in text.splitlines() if not API_IMPORT.match(ln)]
    stripped = "\n".join(lines)
    try:
        tree = ast.parse(stripped)
    except SyntaxError as exc:
        raise PlanFormatError(f"the plan is not valid Python (line {exc.lineno}): {exc.msg}") from None
    except (MemoryError, RecursionError, ValueError):
        raise PlanFormatError("the plan is nested too deeply (or contains null bytes) to be parsed") from None
    funcs = [n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "step"]
    if funcs:
        return _paper_form(stripped, tree, funcs[-1], text)
    steps = _split_marked(stripped.splitlines(), STEP_MARK)
    if not steps:
        raise PlanFormatError("the plan has no code")
    return Plan(tuple(PlanStep(s.title, textwrap.dedent(s.code)) for s in steps), text)


def _paper_form(source: str, tree: ast.Module, fn: ast.FunctionDef, text: str) -> Plan:
    """Steps of a `def step(planner):` file.

    Its body is split at `# Step N:` comments when every piece is valid code on its own; what else the file
    defines (imports, helper functions, constants) runs first as a step of its own, so the body's steps
    see it. A body that `return`s early, or that cannot be split, stays one step: the file as it is, and
    the worker calls `step(planner)`. A call of `step(...)` the file makes itself is dropped (it would run
    the plan twice)."""
    lines = source.splitlines()
    extra = [n for n in tree.body if n is not fn and not _calls_step(n)]
    dropped = [n for n in tree.body if _calls_step(n)]
    if _returns(fn) or isinstance(fn.body[0], ast.Expr) and len(fn.body) == 1 and _only_docstring(fn):
        return Plan((PlanStep("step", _without(lines, dropped)),), text)
    first = fn.body[0].lineno - 1
    while first - 1 >= fn.lineno and lines[first - 1].strip().startswith("#"):
        first -= 1  # comments right above the first statement belong to the body
    body = textwrap.dedent("\n".join(lines[first:fn.end_lineno])).splitlines()
    steps = _split_marked(body, PAPER_STEP_MARK)
    marked = any(PAPER_STEP_MARK.match(ln) for ln in body)
    if not steps or not all(_parses(textwrap.dedent(s.code)) for s in steps):
        steps, marked = [PlanStep("step", textwrap.dedent("\n".join(body)).strip("\n"))], False
    if len(steps) == 1 and not marked:
        steps = [PlanStep("step", steps[0].code)]
    if extra:
        defs = "\n".join("\n".join(lines[_start(n) - 1:n.end_lineno]) for n in extra)
        steps = [PlanStep("definitions", defs), *steps]
    return Plan(tuple(PlanStep(s.title, textwrap.dedent(s.code)) for s in steps), text)


def _start(node: ast.stmt) -> int:
    decorators = getattr(node, "decorator_list", None) or []
    return min([node.lineno, *(d.lineno for d in decorators)])


def _calls_step(node: ast.stmt) -> bool:
    """`step(planner)` at top level, or an `if __name__ == "__main__":` block."""
    if isinstance(node, ast.Expr) and isinstance(node.value, ast.Call):
        f = node.value.func
        return isinstance(f, ast.Name) and f.id == "step"
    if isinstance(node, ast.If) and isinstance(node.test, ast.Compare):
        return isinstance(node.test.left, ast.Name) and node.test.left.id == "__name__"
    return False


def _returns(fn: ast.FunctionDef) -> bool:
    """A `return` of the step function itself (not of a function nested in it)."""
    todo = list(fn.body)
    while todo:
        node = todo.pop()
        if isinstance(node, ast.Return):
            return True
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            todo.extend(ast.iter_child_nodes(node))
    return False


def _only_docstring(fn: ast.FunctionDef) -> bool:
    v = fn.body[0].value if isinstance(fn.body[0], ast.Expr) else None
    return isinstance(v, ast.Constant) and isinstance(v.value, str)


def _without(lines: list[str], nodes: list[ast.stmt]) -> str:
    drop = {i for n in nodes for i in range(_start(n) - 1, n.end_lineno)}
    return "\n".join("" if i in drop else ln for i, ln in enumerate(lines)).strip("\n")


def _parses(code: str) -> bool:
    try:
        ast.parse(code)
    except (SyntaxError, ValueError, MemoryError, RecursionError):
        return False
    return True


def load_plan(path: Path) -> Plan:
    path = Path(path)
    if not path.exists():
        raise PlanFormatError(f"no plan file at {path}")
    try:
        return parse_plan(folder_plan_text(path) if path.is_dir() else path.read_text())
    except PlanFormatError as exc:
        raise PlanFormatError(f"{path}: {exc}") from None
