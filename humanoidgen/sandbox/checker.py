"""Static check of plan code (LLM-written or user plans) before it runs: the friendly first layer.
Which constructs it accepts and refuses is the plan language's data (`language.py`), which the prompts state too.

The security boundary is the locked-down worker process that runs plan code (restricted builtins, memory and
time limits, OS-level lockdown). This check is not that boundary and is not complete (`BLOCKED_ATTRIBUTES` lists
known routes, not all). It turns mistakes and reaches into internals into line-numbered messages that say what to
write instead, before simulation time is spent, and it accepts the ordinary Python that LLMs write in plans:

Accepted: expressions of all kinds (calls with `*args`/`**kwargs`, comprehensions, f-strings, `lambda`, `:=`),
assignments of all kinds, `if`/`for`/`while` (any iterable or condition: the worker's time limit bounds loops),
`try`/`except [T as e]`/`else`/`finally`, `raise`, `assert`, `del name`/`del x[i]`, functions at top level and
nested (defaults, `*args`, keyword-only, `**kwargs`; `return`, `global`, `nonlocal` inside), and imports of the
modules `safe_builtins` provides: `import numpy [as np]`, `import math`, `import numpy.linalg [as la]`,
`import numpy.random`, `from math import pi, sqrt`, `from numpy import array`. The paper's
`from humanoidgen... import *` line is blanked by `strip_api_imports` (the planner API names are defined).

Refused, each with a message: other imports, `class`, decorators, `with` (plans cannot open files), `yield`,
`async`/`await`, `match` (use `if`/`elif`), `del` of attributes, names starting with `__`, attributes starting
with `_` or in `BLOCKED_ATTRIBUTES`, uses of `FORBIDDEN_NAMES` the plan does not bind itself (`dir = v` makes a plan
variable, not the builtin), `.format_map`, and `.format` except on a string literal whose fields neither read
attributes nor index with non-integer keys (`format_fields`), and strings that spell a dunder name.

By-name access is a class of its own: a helper that takes an attribute name as a string (operator.attrgetter,
functools.update_wrapper/wraps and their WRAPPER_* tuples, inspect.getattr_static, typing.get_type_hints,
string.Formatter) turns a string into the attribute this check refuses; `update_wrapper(f, g, updated=
('__globals__',))` merges a module's globals (`sys`, the real builtins) into the plan's. So the helpers and the
modules holding them are refused by name (`_BY_NAME_ATTRIBUTES`, `core` for numpy's private package), strings
spelling `__x__` are refused (a name built at run time gets past that; the helpers are the wall here), and
tests/test_sandbox.py walks everything reachable from `np`/`math`, lazily provided submodules included, and
fails if such a helper or module can be reached.

A name must be provided (`allowed_names`), a safe builtin, or bound in the code (scoping is flat). Annotations are
removed before compiling, so any annotation is accepted. The tree is compiled at the end, so what Python refuses
(`break` outside a loop, nesting too deep) comes back as a violation too; nothing raises but `CodeRejected`.
"""

from __future__ import annotations

import ast
import builtins
import difflib
from dataclasses import dataclass, field

from humanoidgen.sandbox import language
from humanoidgen.sandbox.format_fields import format_template_problems
from humanoidgen.sandbox.steps import STEP_FUNCTION, split_steps, strip_api_imports
from humanoidgen.sandbox.vocabulary import (
    _BY_NAME_ATTRIBUTES,
    _DUNDER,
    _FILE_ATTRIBUTES,
    _INTERNAL_ATTRIBUTES,
    _MODULE_ATTRIBUTES,
    _NAME_HINTS,
    ALLOWED_IMPORTS,
    BLOCKED_ATTRIBUTES,
    FORBIDDEN_NAMES,
    SAFE_BUILTINS,
    safe_builtins,
)

__all__ = ["BLOCKED_ATTRIBUTES", "FORBIDDEN_NAMES", "SAFE_BUILTINS", "STEP_FUNCTION", "CheckedCode", "CodeRejected",
           "Violation", "check_code", "safe_builtins", "split_steps", "strip_api_imports"]

MAX_SOURCE_BYTES = 20_000
MAX_AST_NODES = 5_000
MAX_NESTING = 200  # syntax-tree depth; far beyond plan code, well below what `compile` can recurse through

_IMPORTS_HELP = ("the only imports are `import numpy as np`, `import math` and `from ... import` of their "
                 "functions (e.g. `from math import pi, sqrt`); `numpy.linalg` and `numpy.random` may be imported too")
_NESTED = "code nested too deeply; split long expressions and deep nesting into variables or helper functions"


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
        """The code object; `CodeRejected` (never RecursionError/MemoryError/SyntaxError) if Python refuses."""
        try:
            return compile(self.tree, filename, "exec", dont_inherit=True)
        except SyntaxError as e:
            raise CodeRejected([_syntax_violation(e)]) from None
        except (RecursionError, MemoryError):
            raise CodeRejected([Violation(1, 0, _NESTED)]) from None


def check_code(source: str, allowed_names: set[str] | frozenset[str]) -> CheckedCode:
    """Check `source` (API import lines already stripped); raise `CodeRejected` with line-numbered violations."""
    if len(source.encode("utf-8", "replace")) > MAX_SOURCE_BYTES:
        raise CodeRejected([Violation(1, 0, f"source larger than {MAX_SOURCE_BYTES} bytes; split it into steps")])
    try:
        tree = ast.parse(source, "<step>", "exec")
    except SyntaxError as e:
        raise CodeRejected([_syntax_violation(e)]) from None
    except (RecursionError, MemoryError):  # the parser gives up on deep nesting (e.g. 15,000 unary minus)
        raise CodeRejected([Violation(1, 0, _NESTED)]) from None
    except ValueError as e:  # e.g. a null byte
        raise CodeRejected([Violation(1, 0, f"syntax error: {e}")]) from None
    try:
        if sum(1 for _ in ast.walk(tree)) > MAX_AST_NODES:
            raise CodeRejected([Violation(1, 0, f"code has more than {MAX_AST_NODES} syntax nodes; "
                                                "split it into steps")])
        checker = _Checker(set(allowed_names))
        checker.run(tree)
        if checker.violations:
            raise CodeRejected(sorted(set(checker.violations), key=lambda v: (v.line, v.col, v.message)))
        checked = CheckedCode(source, _strip_annotations(tree), checker.defines_step, checker.bound)
        checked.compile()  # what Python itself refuses (`break` outside a loop, ...) as a violation, too
    except (RecursionError, MemoryError):
        raise CodeRejected([Violation(1, 0, _NESTED)]) from None
    return checked


def _syntax_violation(e: SyntaxError) -> Violation:
    line, col = e.lineno or 1, max((e.offset or 1) - 1, 0)
    msg = e.msg or str(e)
    if "too many nested" in msg or "too many statically nested" in msg:
        return Violation(line, col, _NESTED)
    if "nonlocal" in msg:
        msg += ("; `nonlocal x` needs `x` assigned in an enclosing function (for a variable of the step's top "
                "level, write `global x`)")
    return Violation(line, col, f"syntax error: {msg}")


class _Checker:
    def __init__(self, allowed: set[str]) -> None:
        self.allowed = allowed
        self.violations: list[Violation] = []
        self.bound: set[str] = set()
        self.defines_step = False

    def bad(self, node: ast.AST, message: str) -> None:
        self.violations.append(Violation(getattr(node, "lineno", 1), getattr(node, "col_offset", 0), message))

    def run(self, tree: ast.Module) -> None:
        entries = _collect(tree)
        for node, _in_function, _skipped in entries:  # pass 1: the names the code binds itself
            self.bind(node)
        for node, in_function, skipped in entries:  # pass 2: every node
            if not skipped:
                self.check(node, in_function)
        for stmt in tree.body:
            if isinstance(stmt, ast.FunctionDef) and stmt.name == STEP_FUNCTION:
                self.step_function(stmt)

    def bind(self, node: ast.AST) -> None:
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            self.bound.add(node.id)
        elif isinstance(node, ast.arg):
            self.bound.add(node.arg)
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            self.bound.add(node.name)
        elif isinstance(node, ast.Import):  # bound even when refused: one message, not one per later use
            self.bound.update(a.asname or a.name.partition(".")[0] for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            self.bound.update(a.asname or a.name for a in node.names if a.name != "*")
        elif isinstance(node, ast.ExceptHandler) and node.name:
            self.bound.add(node.name)
        elif isinstance(node, (ast.Global, ast.Nonlocal)):
            self.bound.update(node.names)

    def check(self, node: ast.AST, in_function: bool) -> None:
        if type(node) in _REFUSED:
            self.bad(node, _REFUSED[type(node)])
        elif not isinstance(node, _ALLOWED_NODES):
            self.bad(node, f"`{type(node).__name__}` is not available in plan code")
        elif isinstance(node, ast.Name):
            self.name(node)
        elif isinstance(node, ast.Attribute):
            self.attribute(node)
        elif isinstance(node, ast.Constant) and isinstance(node.value, (str, bytes)):
            self.string(node)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            self.import_(node)
        elif isinstance(node, ast.FunctionDef):
            if node.decorator_list:
                self.bad(node.decorator_list[0], "decorators are not available in plan code; define the function "
                         "without `@...` and call what the decorator would have called yourself")
            self.binding(node, node.name)
        elif isinstance(node, ast.arg):
            self.binding(node, node.arg)
        elif isinstance(node, ast.ExceptHandler) and node.name:
            self.binding(node, node.name)
        elif isinstance(node, ast.Return) and not in_function:
            self.bad(node, "`return` outside a function: a step runs at top level; use `if`/`else` to skip the "
                     "rest, or put the step in `def step(planner):`")
        elif isinstance(node, (ast.Global, ast.Nonlocal)):
            if isinstance(node, ast.Nonlocal) and not in_function:
                self.bad(node, "`nonlocal` is only allowed inside a function (at top level, no declaration is needed)")
            for n in node.names:
                self.binding(node, n)
        elif isinstance(node, ast.withitem) and not language.with_context_allowed(node.context_expr):
            self.bad(node.context_expr, language.WITH_MESSAGE)
        elif isinstance(node, ast.comprehension) and node.is_async:
            self.bad(node.target, _REFUSED[ast.Await])

    def binding(self, node: ast.AST, name: str) -> None:
        if name.startswith("__"):
            self.bad(node, f"the name `{name}` is not available in plan code: names starting with '__' are Python "
                     "internals; pick another name")

    def name(self, node: ast.Name) -> None:
        n = node.id
        if n.startswith("__"):
            hint = _NAME_HINTS.get(n, "names starting with '__' are Python internals")
            self.bad(node, f"`{n}` is not available in plan code; {hint}")
        elif isinstance(node.ctx, ast.Store) or n in self.bound:
            return  # the plan's own variable (even `dir = ...`: then it is not the builtin)
        elif n in FORBIDDEN_NAMES:
            self.bad(node, f"`{n}` is not available in plan code; {_NAME_HINTS.get(n, 'it reaches internals')}")
        elif n not in self.allowed and n not in SAFE_BUILTINS:
            self.bad(node, f"unknown name `{n}`: {self.unknown_hint(n)}")

    def unknown_hint(self, n: str) -> str:
        if n in ("np", "numpy", "math"):
            return f"add `{'import numpy as np' if n == 'np' else 'import ' + n}` at the top of the step"
        known = {k for k in self.allowed | self.bound | SAFE_BUILTINS if not k.startswith("__")}
        close = difflib.get_close_matches(n, sorted(known), n=1, cutoff=0.75)
        if hasattr(builtins, n):
            text = f"the Python builtin `{n}` is not available in plan code"
        else:
            text = "it is not assigned in this step, and it is not a planner API name or an available builtin"
        return text + (f"; did you mean `{close[0]}`?" if close else "")

    def attribute(self, node: ast.Attribute) -> None:
        a = node.attr
        if a in ("format", "format_map"):
            self.format_call(node)
        elif a.startswith("_"):
            hint = " (to test a type, use `isinstance(x, T)`)" if a == "__class__" else ""
            self.bad(node, f"attribute `{a}` is not available in plan code: names starting with '_' are private or "
                     f"Python internals; use the public API{hint}")
        elif a in _FILE_ATTRIBUTES:
            self.bad(node, f"attribute `{a}` is not available in plan code: plans cannot read or write files")
        elif a in _MODULE_ATTRIBUTES:
            self.bad(node, f"attribute `{a}` is not available in plan code: it leads to a module outside the math "
                     "of numpy/math (plans cannot use the OS, files or the interpreter)")
        elif a in _BY_NAME_ATTRIBUTES:
            self.bad(node, f"attribute `{a}` is not available in plan code: it reaches attributes by name (a string "
                     "naming an attribute gets past this check); write the attribute itself (`obj.name`)")
        elif a in _INTERNAL_ATTRIBUTES:
            self.bad(node, f"attribute `{a}` is not available in plan code: it reaches interpreter internals")
        elif isinstance(node.ctx, ast.Del):
            self.bad(node, "`del` of an attribute is not available in plan code; only `del name` and `del x[i]`")

    def string(self, node: ast.Constant) -> None:
        text = node.value.decode("latin-1") if isinstance(node.value, bytes) else node.value
        if m := _DUNDER.search(text):
            self.bad(node, f"the string `{m.group()}` is not available in plan code: it names a Python internal, "
                     "which plans never need (as a string it would only be an attribute name for a by-name helper)")

    def format_call(self, node: ast.Attribute) -> None:
        if node.attr == "format_map":
            self.bad(node, "`.format_map(...)` is not available in plan code; use an f-string, or "
                     "`'...'.format(**mapping)` on a string literal")
        elif not (isinstance(node.value, ast.Constant) and isinstance(node.value.value, str)):
            self.bad(node, "`.format(...)` is only available on a string literal (`'{:.3f}'.format(x)`), not on a "
                     "template held in a variable or built by an expression; use an f-string instead: f\"{x:.3f}\"")
        else:
            for problem in format_template_problems(node.value.value):
                self.bad(node, f"in `'...'.format(...)`: {problem}")

    def import_(self, node: ast.Import | ast.ImportFrom) -> None:
        if isinstance(node, ast.ImportFrom):
            module = "." * node.level + (node.module or "")
            what, ok = f"from {module} import ...", node.level == 0 and module in ALLOWED_IMPORTS
        else:
            refused = [a.name for a in node.names if a.name not in ALLOWED_IMPORTS]
            module = refused[0] if refused else ""
            what, ok = f"import {module}", not refused
        if not ok:
            api = sorted((n for n in self.allowed if not n.startswith("_")), key=lambda n: (n != "planner", n))
            names = ", ".join(api[:4]) + (", ..." if len(api) > 4 else "")
            defined = f"the planner API names ({names}) are already defined" if api else "the planner API is defined"
            if module.lstrip(".").split(".")[0] == "humanoidgen":
                self.bad(node, f"`{what}` is not needed: {defined}; remove this line")
            else:
                self.bad(node, f"`{what}` is not available in plan code; {_IMPORTS_HELP}; {defined}")
            return
        for a in node.names:
            if isinstance(node, ast.ImportFrom) and a.name == "*":
                self.bad(node, f"`from {module} import *` is not available in plan code; import the names you "
                         f"need (`from {module} import a, b`) or use `import {module}`")
            elif isinstance(node, ast.ImportFrom) and (a.name.startswith("_") or a.name in BLOCKED_ATTRIBUTES):
                self.bad(node, f"`{a.name}` cannot be imported from `{module}` in plan code")
            self.binding(node, a.asname or a.name.partition(".")[0])

    def step_function(self, node: ast.FunctionDef) -> None:
        a = node.args
        if a.kwonlyargs or a.vararg or a.kwarg or a.defaults or len(a.posonlyargs) + len(a.args) != 1:
            self.bad(node, f"`def {STEP_FUNCTION}` must take exactly one parameter, `planner` (the runner calls "
                     f"`{STEP_FUNCTION}(planner)`); give helper functions another name")
        self.defines_step = True


# The syntax nodes plan code may use, and the refused constructs with their messages (what is inside a refused
# construct is not checked further: one message per construct): the plan language's data (`language.py`), which
# the prompts state too.
_ALLOWED_NODES: tuple[type[ast.AST], ...] = language.allowed_nodes()
_REFUSED: dict[type[ast.AST], str] = language.refused_nodes()


def _collect(tree: ast.Module) -> list[tuple[ast.AST, bool, bool]]:
    """(node, inside a function, inside a refused construct) for every node but annotations, iteratively
    (no recursion on hostile depth); raises CodeRejected beyond MAX_NESTING."""
    out, stack = [], [(tree, 0, False, False)]
    while stack:
        node, depth, in_function, skipped = stack.pop()
        if depth > MAX_NESTING:
            raise CodeRejected([Violation(getattr(node, "lineno", 1), getattr(node, "col_offset", 0), _NESTED)])
        out.append((node, in_function, skipped))
        inner = in_function or isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
        for name, value in ast.iter_fields(node):
            if name in ("annotation", "returns"):  # never evaluated: removed before compiling
                continue
            for child in value if isinstance(value, list) else [value]:
                if isinstance(child, ast.AST):
                    stack.append((child, depth + 1, inner, skipped or type(node) in _REFUSED))
    return out


def _strip_annotations(tree: ast.Module) -> ast.Module:
    """Drop annotations so they are never evaluated (`planner: HumanoidMotionPlanner` needs no such name)."""
    for node in list(ast.walk(tree)):
        if isinstance(node, ast.arg):
            node.annotation = None
        elif isinstance(node, ast.FunctionDef):
            node.returns = None
        for name in ("body", "orelse", "finalbody"):
            stmts = getattr(node, name, None)
            if isinstance(stmts, list):
                stmts[:] = [_plain_assign(s) if isinstance(s, ast.AnnAssign) else s for s in stmts]
    return ast.fix_missing_locations(tree)


def _plain_assign(node: ast.AnnAssign) -> ast.stmt:
    if node.value is None:
        return ast.copy_location(ast.Pass(), node)
    return ast.copy_location(ast.Assign(targets=[node.target], value=node.value), node)
