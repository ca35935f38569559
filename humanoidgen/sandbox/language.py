"""The plan language as data: which Python constructs plan code may use, what it may import and name, and whether
names carry over from one step to the next. One source for both sides of the contract:

- the checker (`checker.py`) allows the syntax nodes of the allowed constructs here and refuses those of the
  refused ones with the messages here (`allowed_nodes`, `refused_nodes`);
- the prompts state the rules from this data (`rules_text`), so a rule cannot be in the prompt without being here;
- tests/test_plan_language.py runs every example below through the checker as a plan step: each example of an
  allowed construct must be accepted and each example of a refused one refused, and the carry-over rule is run
  in a worker.

The checker remains the friendly first layer, not the security boundary (the locked-down worker is); what this
data refuses is what plans never need.
"""

from __future__ import annotations

import ast
import builtins
from dataclasses import dataclass
from typing import Literal

from humanoidgen.sandbox.vocabulary import ALLOWED_IMPORTS, SAFE_BUILTINS

PromptKind = Literal["script", "mcts"]


@dataclass(frozen=True)
class Construct:
    """A rule of the plan language. `examples` are plan steps using it: tests check that the checker accepts them
    when `allowed`, refuses them otherwise. `nodes`: the syntax nodes it stands for (the checker's allow-list is
    the union of the allowed constructs' nodes; a refused construct's nodes get `message`)."""

    name: str  # as the prompt writes it
    allowed: bool
    examples: tuple[str, ...]
    nodes: tuple[type[ast.AST], ...] = ()
    message: str = ""  # a refused construct: what the checker says, with what to write instead
    group: Literal["core", "syntax", "import", "name"] = "syntax"  # which sentence of the prompt states it


# The context managers `with` may open: numpy's print and floating-point settings, which change nothing outside
# the block. Anything else (a file, the planner, a lock) is refused with WITH_MESSAGE.
WITH_CONTEXTS = ("np.printoptions", "np.errstate")
WITH_MESSAGE = (f"`with` is available only on {' and '.join(f'`{c}(...)`' for c in WITH_CONTEXTS)} in plan code "
                "(plans cannot open files or hold the planner); write the statements without it")

_ASYNC = "`async`/`await` is not available in plan code; planner calls are ordinary calls, call them directly"

# Statements and expressions plan code may use. The first entry is the plain core every program needs.
ALLOWED: tuple[Construct, ...] = (
    Construct("assignments, expressions and calls", True,
              ("x = planner.env\ny, z = [1, 2]\ny += abs(-1) * 2 ** 3 % 5\nplanner.hand_pre_grasp('right')\npass",
               "y, z = 1, 2\nlabel = 'cube' if y > 1 else 'can'\nitems = {'a': [1, 2][0]}\nflag = not (y < 2 and z)",
               "x: float = 1.0"),
              (ast.Module, ast.Expr, ast.Assign, ast.AugAssign, ast.AnnAssign, ast.Pass, ast.Constant, ast.Name,
               ast.Load, ast.Store, ast.Del, ast.Attribute, ast.Subscript, ast.Slice, ast.Starred, ast.Call,
               ast.keyword, ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Compare, ast.IfExp, ast.List, ast.Tuple,
               ast.Dict, ast.Set, ast.operator, ast.unaryop, ast.boolop, ast.cmpop, ast.expr_context),
              group="core"),
    Construct("`if`/`elif`/`else`", True, ("x = 1\nif x > 1:\n    y = 1\nelif x < 0:\n    y = 2\nelse:\n    y = 3",),
              (ast.If,)),
    Construct("`for`", True, ("for i, hand in enumerate(['left', 'right']):\n    print(i, hand)",), (ast.For,)),
    Construct("`while`", True, ("i = 0\nwhile i < 3:\n    i += 1",), (ast.While,)),
    Construct("`break`/`continue`", True, ("for i in range(5):\n    if i == 1:\n        continue\n    if i > 2:\n"
                                           "        break",), (ast.Break, ast.Continue)),
    Construct("`try`/`except`/`else`/`finally`", True,
              ("try:\n    x = 1 / 0\nexcept ZeroDivisionError as e:\n    x = 0\nelse:\n    x = 2\nfinally:\n"
               "    print('done')",), (ast.Try, ast.TryStar, ast.ExceptHandler)),
    Construct("`raise`", True, ("raise RuntimeError('the cube is out of reach')",), (ast.Raise,)),
    Construct("`assert`", True, ("assert 1 < 2, 'ordered'",), (ast.Assert,)),
    Construct("helper functions (`def`, `return`, `global`, `nonlocal`)", True,
              ("def lift(p, dz=0.1, *rest, **kw):\n    return [p[0], p[1], p[2] + dz]\nq = lift([0, 0, 0])",
               "n = 0\ndef bump():\n    global n\n    n += 1\nbump()",
               "def outer():\n    k = 0\n    def inner():\n        nonlocal k\n        k += 1\n    inner()\n"
               "    return k"),
              (ast.FunctionDef, ast.arguments, ast.arg, ast.Return, ast.Global, ast.Nonlocal)),
    Construct("`lambda`", True, ("by_height = sorted([3, 1, 2], key=lambda v: -v)",), (ast.Lambda,)),
    Construct(f"`with` on {' or '.join(f'`{c}(...)`' for c in WITH_CONTEXTS)}", True,
              ("import numpy as np\nwith np.printoptions(precision=3, suppress=True):\n    print(np.array([0.12345]))",
               "import numpy as np\nwith np.errstate(divide='ignore'):\n    r = np.array([1.0]) / np.array([0.0])",
               "import numpy\nwith numpy.printoptions(precision=2) as opts:\n    print(opts)"),
              (ast.With, ast.withitem)),
    Construct("comprehensions", True, ("a = [x * 2 for x in range(3) if x]\nb = {x: x for x in a}\nc = {x for x in a}\n"
                                       "d = sum(x for x in a)",),
              (ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp, ast.comprehension)),
    Construct("f-strings", True, ("x = 0.5\nprint(f'openness {x:.2f}')",), (ast.JoinedStr, ast.FormattedValue)),
    Construct("`:=`", True, ("if (n := len([1, 2])) > 1:\n    print(n)",), (ast.NamedExpr,)),
    Construct("`del`", True, ("x = [1, 2]\ndel x[0]\ndel x",), (ast.Delete,)),
    Construct("imports of numpy and math", True,
              ("import numpy as np", "import math", "from math import pi, sqrt", "import numpy.linalg as la",
               "from numpy.linalg import norm", "import numpy.random", "from numpy import array"),
              (ast.Import, ast.ImportFrom, ast.alias), group="import"),
    Construct("a `from humanoidgen... import *` line (ignored: the API names are already defined)", True,
              ("from humanoidgen.env.solver_env import *\nplanner.hand_pre_grasp('left')",), group="import"),
    Construct("names starting with one `_` (`_, pose = ...`)", True, ("_, pose = 1, 2\n_tmp = pose",), group="name"),
)

# Constructs plan code may not use; each is refused before the step runs, with a message naming the line.
REFUSED: tuple[Construct, ...] = (
    Construct("`class`", False, ("class Grip:\n    pass",), (ast.ClassDef,),
              "`class` definitions are not available in plan code; use functions, dicts and tuples"),
    Construct("`with` on anything else", False,
              ("with planner as p:\n    pass", "with open('x.txt') as f:\n    pass",
               "with np.printoptions(precision=3), planner:\n    pass", "ctx = np.printoptions()\nwith ctx:\n    pass"),
              message=WITH_MESSAGE),
    Construct("`yield`", False, ("def gen():\n    yield 1",), (ast.Yield,),
              "`yield` is not available in plan code (no generator functions); build and return a list"),
    Construct("`yield from`", False, ("def gen():\n    yield from [1]",), (ast.YieldFrom,),
              "`yield from` is not available in plan code (no generator functions); build and return a list"),
    Construct("`async`/`await`", False, ("async def f():\n    pass",),
              (ast.AsyncFunctionDef, ast.AsyncFor, ast.AsyncWith, ast.Await), _ASYNC),
    Construct("`match`", False, ("x = 1\nmatch x:\n    case 1:\n        pass",), (ast.Match,),
              "`match` is not available in plan code; use `if`/`elif`/`else`"),
    Construct("decorators (`@...`)", False, ("def d(f):\n    return f\n@d\ndef g():\n    pass",)),
    Construct("names starting with `__`", False, ("__x = 1", "print(__builtins__)"), group="name"),
    Construct("attributes starting with `_`", False, ("planner._env", "x = ().__class__"), group="name"),
    Construct("files, the operating system and the interpreter (`open`, `eval`, `exec`, `getattr`, `type`, "
              "`np.load`, `np.save`, ...)", False,
              ("open('/etc/passwd')", "eval('1 + 1')", "exec('x = 1')", "getattr(planner, 'env')",
               "x = type(planner)", "np.load('x.npy')", "np.save('x.npy', [1])", "np.lib", "math.sys"),
              group="name"),
    Construct("other modules", False, ("import os", "import scipy", "from pathlib import Path", "import numpy.f2py"),
              group="import"),
    Construct("`import *` of numpy or math", False, ("from math import *", "from numpy import *"), group="import"),
    Construct("imports from humanoidgen (but the ignored `import *` line)", False,
              ("from humanoidgen.planning.planner import HumanoidMotionPlanner",), group="import"),
)

# Whether a name a step assigns is defined in the steps after it: what the runner does (one namespace per
# program run, steps executed in order) and what the tree search does (it continues from a saved scene, not by
# running the executed steps again). tests/test_plan_language.py runs the script case in a worker.
CARRY_OVER: dict[PromptKind, str] = {
    "script": ("Names a step assigns (variables, helper functions) stay defined in the steps after it: the steps run "
               "in order in one namespace. Objects move, though: compute constraints and poses in the step that uses "
               "them."),
    "mcts": ("The executed steps are not run again: the scene is restored from where they left it, so names they "
             "assigned may be missing or hold values from another attempt. Compute everything a step uses in that "
             "step."),
}


def with_context_allowed(expr: ast.expr) -> bool:
    """Whether a `with` item opens one of WITH_CONTEXTS: a call of `np.<name>(...)` or `numpy.<name>(...)`."""
    if not (isinstance(expr, ast.Call) and isinstance(expr.func, ast.Attribute)
            and isinstance(expr.func.value, ast.Name)):
        return False
    module = "np" if expr.func.value.id in ("np", "numpy") else expr.func.value.id
    return f"{module}.{expr.func.attr}" in WITH_CONTEXTS


def allowed_nodes() -> tuple[type[ast.AST], ...]:
    """The checker's allow-list of syntax nodes: those of the allowed constructs."""
    return tuple(dict.fromkeys(n for c in ALLOWED for n in c.nodes))


def refused_nodes() -> dict[type[ast.AST], str]:
    """Refused syntax nodes and the checker's message for each (what is inside them is not checked further)."""
    return {n: c.message for c in REFUSED for n in c.nodes}


def unavailable_builtins() -> list[str]:
    """Python's public builtins plan code cannot use (the checker refuses them unless the plan binds the name)."""
    return sorted(n for n in dir(builtins) if not n.startswith("_") and n not in SAFE_BUILTINS
                  and not n[0].isupper())


def rules_text(kind: PromptKind) -> str:
    """The plan-language rules as the prompts state them, one bullet each."""
    allowed = ", ".join(c.name for c in ALLOWED if c.group == "syntax")
    refused = "; ".join(c.name for c in REFUSED if c.group in ("syntax", "name"))
    modules = ", ".join(f"`{m}`" for m in sorted(ALLOWED_IMPORTS))
    names = sorted(SAFE_BUILTINS - {"True", "False", "None"}, key=lambda n: (n[0].isupper(), n))
    return "\n".join([
        f"- Plain Python is accepted: {allowed}.",
        f"- Not accepted (the step is refused before it runs, with a message naming the line): {refused}.",
        "- `np` (numpy) and `math` are already defined, with the planner API names. Imports of "
        f"{modules} (`import numpy as np`, `from math import pi`; not `import *`) are accepted; no other module "
        "can be imported, nor anything from humanoidgen (a `from humanoidgen... import *` line is ignored).",
        f"- Builtins: {', '.join(f'`{n}`' for n in names)}; no others "
        f"({', '.join(f'`{n}`' for n in ('open', 'getattr', 'type', 'iter', 'next', 'hex'))}, ... are not available).",
        f"- {CARRY_OVER[kind]}",
    ])
