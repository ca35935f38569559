"""Static allow-list check of LLM-written plan steps before they are executed.

The check is the first of two layers: it rejects code that could reach the interpreter's internals (imports,
dunder attributes, `eval`/`getattr`, frames of generators, modules hanging off numpy), and code whose shape is
outside the paper's plan scripts (classes, `while`, `try`, ...). The second layer is `runner.SandboxWorker`:
a separate process with restricted builtins, a memory limit and a wall-time limit, which also covers what a
static check cannot (a long `range`, a slow planner call).

Allowed, per node: literals, names, arithmetic/boolean/comparison ops, attribute access (no name starting
with "_", none in `BLOCKED_ATTRIBUTES`), subscripts/slices, calls (incl. `*args`/`**kwargs`), assignments
(plain, tuple unpacking, augmented, annotated), list/tuple/dict/set displays, comprehensions, f-strings,
`x if c else y`, `if`/`elif`/`else`, `for` over `range(...)`, a list/tuple/set literal or a name, `break`,
`continue`, `pass`, `assert`, `raise`, and top-level `def step(planner):` (no decorators) with `return`.
Forbidden: everything else, notably `import`, `while`, `try`, `with`, `class`, `lambda`, `global`/`nonlocal`,
`del`, `yield`, `await`, `match`, nested functions.

Names: a name must be in `allowed_names` (the namespace the runner provides), in `SAFE_BUILTINS`, or bound
in the checked code itself; `FORBIDDEN_NAMES` and dunder names are rejected even if allowed elsewhere.
Annotations (`planner: HumanoidMotionPlanner`) need only be dotted names; they are removed before the code is
compiled, so they are never evaluated.
"""

from __future__ import annotations

import ast
import contextlib
import re
import textwrap
from dataclasses import dataclass, field

MAX_SOURCE_BYTES = 20_000
MAX_AST_NODES = 5_000
STEP_FUNCTION = "step"

# Builtins a plan step may use; the runner exposes exactly these as `__builtins__`. `type`, `getattr`, `vars`,
# `dir`, `iter`/`next` and friends are absent because they reach internals or build unbounded iteration.
SAFE_BUILTINS: frozenset[str] = frozenset({
    "range", "len", "abs", "min", "max", "sum", "round", "float", "int", "bool", "str", "list", "tuple", "dict",
    "set", "enumerate", "zip", "print", "sorted", "reversed", "any", "all", "isinstance", "divmod", "map",
    "filter", "True", "False", "None",
    "Exception", "ValueError", "RuntimeError", "TypeError", "KeyError", "IndexError", "AssertionError",
})

FORBIDDEN_NAMES: frozenset[str] = frozenset({
    "open", "exec", "eval", "compile", "getattr", "setattr", "delattr", "hasattr", "__import__", "globals",
    "locals", "vars", "dir", "input", "breakpoint", "help", "type", "object", "super", "memoryview", "id",
    "classmethod", "staticmethod", "property", "exit", "quit", "iter", "next", "aiter", "anext", "callable",
    "issubclass", "hash", "format", "chr", "ord", "bytes", "bytearray", "frozenset", "slice",
})

# Attribute names that lead to interpreter internals or the file system without a leading underscore:
# generator/frame/code objects, and modules reachable from numpy (found by walking `np`'s public attributes,
# see tests/test_sandbox.py::test_numpy_attribute_walk_reaches_no_dangerous_module).
BLOCKED_ATTRIBUTES: frozenset[str] = frozenset({
    # frames, code, generators, coroutines, tracebacks
    "gi_frame", "gi_code", "gi_yieldfrom", "cr_frame", "cr_code", "cr_await", "ag_frame", "ag_code",
    "f_globals", "f_locals", "f_builtins", "f_back", "f_code", "tb_frame", "tb_next", "co_code", "mro",
    "func_globals", "format_map",
    # modules that expose the OS, code loading or raw memory
    "os", "sys", "subprocess", "builtins", "importlib", "ctypes", "ctypeslib", "pickle", "io", "shutil",
    "pathlib", "socket", "inspect", "types", "tempfile", "platform", "gc", "marshal", "runpy", "signal",
    "threading", "multiprocessing", "f2py", "testing", "distutils", "lib", "mmap", "glob", "urllib",
    # numpy file I/O and pickling
    "load", "loads", "save", "savez", "savez_compressed", "savetxt", "loadtxt", "genfromtxt", "fromfile",
    "fromregex", "tofile", "dump", "dumps", "memmap", "DataSource", "open_memmap",
})

_ALLOWED_NODES: tuple[type[ast.AST], ...] = (
    ast.Module, ast.Expr, ast.Assign, ast.AugAssign, ast.AnnAssign, ast.If, ast.For, ast.Pass, ast.Break,
    ast.Continue, ast.Assert, ast.Raise, ast.Return, ast.FunctionDef, ast.arguments, ast.arg,
    ast.Constant, ast.Name, ast.Load, ast.Store, ast.Attribute, ast.Subscript, ast.Slice, ast.Starred,
    ast.Call, ast.keyword, ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Compare, ast.IfExp, ast.NamedExpr,
    ast.List, ast.Tuple, ast.Dict, ast.Set, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp,
    ast.comprehension, ast.JoinedStr, ast.FormattedValue,
    ast.operator, ast.unaryop, ast.boolop, ast.cmpop, ast.expr_context,
)

# The paper's scripts start with `from humanoidgen.<...>.solver_env import *`; only that exact form is stripped.
_API_IMPORT = re.compile(r"^[ \t]*(from[ \t]+humanoidgen(\.\w+)*[ \t]+import[ \t]+\*|import[ \t]+humanoidgen(\.\w+)*)"
                         r"[ \t]*(#.*)?$")
_FENCE = re.compile(r"```[ \t]*(?:python|py)?[ \t]*\n(.*?)```", re.DOTALL | re.IGNORECASE)


@dataclass(frozen=True)
class Violation:
    line: int
    col: int
    message: str

    def __str__(self) -> str:
        return f"line {self.line}:{self.col}: {self.message}"


class CodeRejected(Exception):
    def __init__(self, violations: list[Violation]) -> None:
        self.violations = violations
        super().__init__("; ".join(str(v) for v in violations))


@dataclass
class CheckedCode:
    """Source that passed the check, and its AST with annotations removed (ready to `compile`)."""

    source: str
    tree: ast.Module
    defines_step: bool  # the code is `def step(planner): ...`; the runner calls it after executing the code
    bound_names: set[str] = field(default_factory=set)

    def compile(self, filename: str = "<step>"):
        return compile(self.tree, filename, "exec", dont_inherit=True)


def strip_api_imports(source: str) -> str:
    """Blank out the paper's `from humanoidgen... import *` / `import humanoidgen...` lines (line numbers kept)."""
    return "\n".join("" if _API_IMPORT.match(line) else line for line in source.split("\n"))


def split_steps(response_text: str) -> list[str]:
    """Plan steps from an LLM response.

    Each fenced ```python (or bare ```) block is one step, dedented (the paper's blocks are indented one level)
    and with API import lines stripped. If there are no fences, the text is taken as a whole script; if a
    fenced block or the script defines `def step(planner):`, that function's body is returned as the step
    instead (so `planner` is the namespace's planner and the body runs at top level).
    """
    blocks = _FENCE.findall(response_text) or [response_text]
    steps = []
    for block in blocks:
        code = strip_api_imports(textwrap.dedent(block)).strip("\n")
        body = _step_body(code)
        code = body if body is not None else code
        if code.strip():
            steps.append(code)
    return steps


def _step_body(code: str) -> str | None:
    try:
        tree = ast.parse(code)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and node.name == STEP_FUNCTION and node.body:
            lines = code.split("\n")
            # Keep comments between the header and the first statement when the header is one line.
            for start in (node.lineno, node.body[0].lineno - 1):
                body = textwrap.dedent("\n".join(lines[start:node.body[-1].end_lineno])).strip("\n")
                with contextlib.suppress(SyntaxError, ValueError, RecursionError, MemoryError):
                    ast.parse(body)
                    return body
            return None
    return None


def check_code(source: str, allowed_names: set[str] | frozenset[str]) -> CheckedCode:
    """Check `source` (API import lines already stripped) against the allow-list; raise `CodeRejected`."""
    if len(source.encode("utf-8", "replace")) > MAX_SOURCE_BYTES:
        raise CodeRejected([Violation(1, 0, f"source larger than {MAX_SOURCE_BYTES} bytes")])
    try:
        tree = ast.parse(source, "<step>", "exec")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as e:
        line = getattr(e, "lineno", None) or 1
        raise CodeRejected([Violation(line, getattr(e, "offset", None) or 0, f"syntax error: {e}")]) from None
    nodes = list(ast.walk(tree))
    if len(nodes) > MAX_AST_NODES:
        raise CodeRejected([Violation(1, 0, f"code has more than {MAX_AST_NODES} syntax nodes")])
    checker = _Checker(set(allowed_names))
    checker.visit_tree(tree, nodes)
    if checker.violations:
        raise CodeRejected(sorted(checker.violations, key=lambda v: (v.line, v.col)))
    tree = _StripAnnotations().visit(tree)
    ast.fix_missing_locations(tree)
    return CheckedCode(source, tree, checker.defines_step, checker.bound)


class _Checker:
    def __init__(self, allowed: set[str]) -> None:
        self.allowed = allowed
        self.violations: list[Violation] = []
        self.bound: set[str] = set()
        self.defines_step = False
        self.annotations: set[int] = set()  # ids of annotation subtrees: only dotted names, never evaluated

    def bad(self, node: ast.AST, message: str) -> None:
        self.violations.append(Violation(getattr(node, "lineno", 1), getattr(node, "col_offset", 0), message))

    def visit_tree(self, tree: ast.Module, nodes: list[ast.AST]) -> None:
        # Pass 1: names the code binds itself (assignment targets, loop/comprehension variables, parameters).
        for node in nodes:
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
                self.bound.add(node.id)
            elif isinstance(node, ast.arg):
                self.bound.add(node.arg)
                if node.annotation is not None:
                    self.annotation(node.annotation)
            elif isinstance(node, ast.FunctionDef):
                self.bound.add(node.name)
                if node.returns is not None:
                    self.annotation(node.returns)
            elif isinstance(node, ast.AnnAssign):
                self.annotation(node.annotation)
        for stmt in tree.body:  # top-level only: `def step` here is fine, nowhere else
            if isinstance(stmt, ast.FunctionDef):
                self.function(stmt)
        # Pass 2: every node against the allow-list.
        top_defs = {id(s) for s in tree.body if isinstance(s, ast.FunctionDef)}
        for node in nodes:
            if not isinstance(node, _ALLOWED_NODES):
                # Helper nodes (alias, excepthandler, withitem, ...) only occur under a forbidden statement or
                # expression, which is reported already: report them only if their line has nothing yet.
                if isinstance(node, (ast.stmt, ast.expr)) or not any(
                        v.line == getattr(node, "lineno", 1) for v in self.violations):
                    self.bad(node, f"{_describe(node)} is not allowed")
            elif isinstance(node, ast.FunctionDef) and id(node) not in top_defs:
                self.bad(node, "functions may only be defined at top level (`def step(planner):`)")
            elif isinstance(node, ast.Name):
                self.name(node)
            elif isinstance(node, ast.Attribute):
                self.attribute(node)
            elif isinstance(node, ast.For):
                self.loop(node)
            elif isinstance(node, ast.Return) and not top_defs:
                self.bad(node, "`return` outside `def step`")

    def annotation(self, node: ast.expr) -> None:
        for sub in ast.walk(node):
            self.annotations.add(id(sub))
            if not isinstance(sub, (ast.Name, ast.Attribute, ast.Load, ast.Constant)):
                self.bad(sub, "annotations must be plain (dotted) names")
            elif isinstance(sub, ast.Attribute) and sub.attr.startswith("_"):
                self.bad(sub, f"attribute `{sub.attr}` is not allowed")

    def function(self, node: ast.FunctionDef) -> None:
        a = node.args
        if node.decorator_list:
            self.bad(node, "decorators are not allowed")
        if node.name != STEP_FUNCTION:
            self.bad(node, f"only `def {STEP_FUNCTION}(planner):` may be defined, not `{node.name}`")
        if a.posonlyargs or a.kwonlyargs or a.vararg or a.kwarg or a.defaults or len(a.args) != 1:
            self.bad(node, f"`{STEP_FUNCTION}` must take exactly one parameter, `planner`")
        self.defines_step = node.name == STEP_FUNCTION

    def name(self, node: ast.Name) -> None:
        if id(node) in self.annotations:
            return
        n = node.id
        if n in FORBIDDEN_NAMES or n.startswith("__"):
            self.bad(node, f"name `{n}` is not allowed")
        elif isinstance(node.ctx, ast.Load) and n not in self.allowed | self.bound | SAFE_BUILTINS:
            self.bad(node, f"unknown name `{n}`")

    def attribute(self, node: ast.Attribute) -> None:
        if node.attr.startswith("_") and id(node) not in self.annotations:
            self.bad(node, f"attribute `{node.attr}` is not allowed (names starting with '_' are private)")
        elif node.attr in BLOCKED_ATTRIBUTES and id(node) not in self.annotations:
            self.bad(node, f"attribute `{node.attr}` is not allowed")

    def loop(self, node: ast.For) -> None:
        it = node.iter
        if isinstance(it, (ast.List, ast.Tuple, ast.Set, ast.Name)):
            return
        if isinstance(it, ast.Call) and isinstance(it.func, ast.Name) and it.func.id == "range" and not it.keywords:
            return
        self.bad(node, "`for` may only loop over range(...), a list/tuple literal or a name")


class _StripAnnotations(ast.NodeTransformer):
    """Drop annotations so they are never evaluated (`planner: HumanoidMotionPlanner` needs no such name)."""

    def visit_arg(self, node: ast.arg) -> ast.arg:
        node.annotation = None
        return node

    def visit_FunctionDef(self, node: ast.FunctionDef) -> ast.FunctionDef:
        node.returns = None
        self.generic_visit(node)
        return node

    def visit_AnnAssign(self, node: ast.AnnAssign) -> ast.stmt:
        if node.value is None:
            return ast.copy_location(ast.Pass(), node)
        return ast.copy_location(ast.Assign(targets=[node.target], value=node.value), node)


def _describe(node: ast.AST) -> str:
    names = {ast.Import: "`import`", ast.ImportFrom: "`from ... import`", ast.While: "`while` loop",
             ast.Lambda: "`lambda`", ast.ClassDef: "`class`", ast.With: "`with`", ast.Try: "`try`",
             ast.Global: "`global`", ast.Nonlocal: "`nonlocal`", ast.Delete: "`del`", ast.Yield: "`yield`",
             ast.YieldFrom: "`yield from`", ast.Await: "`await`"}
    return names.get(type(node), f"`{type(node).__name__}`")
