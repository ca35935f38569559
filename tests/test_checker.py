"""The static checker of plan code: the friendly first layer (what it accepts, what it refuses and how it says so)."""

from __future__ import annotations

import math

import numpy
import pytest

from humanoidgen.sandbox.checker import (
    MAX_AST_NODES,
    SAFE_BUILTINS,
    CheckedCode,
    CodeRejected,
    Violation,
    check_code,
    safe_builtins,
    split_steps,
    strip_api_imports,
)
from humanoidgen.sandbox.format_fields import format_template_problems

NAMES = {"planner", "np", "math", "Constraint", "get_point_in_env"}
MODULES = {"numpy": numpy, "math": math}


def rejected(source: str, names: set[str] = NAMES) -> list[Violation]:
    with pytest.raises(CodeRejected) as e:
        check_code(source, names)
    assert e.value.violations and all(isinstance(v, Violation) for v in e.value.violations)
    return e.value.violations


def run(source: str, **namespace) -> dict:
    """Check and execute like a runner does (restricted builtins with `__import__`); the resulting namespace."""
    checked = check_code(source, set(namespace) | {"planner"})
    ns = {"planner": None, **namespace, "__builtins__": safe_builtins(MODULES)}
    exec(checked.compile(), ns)  # noqa: S102 - test of checked code
    return ns


# -- accepted -------------------------------------------------------------------------------------------
@pytest.mark.parametrize("source", [
    # helper functions: top level, nested in step, nested in helpers; defaults, *args, **kwargs, keyword-only
    "def helper(x, y=2, *rest, scale=1.0, **kw):\n    return (x + y + sum(rest)) * scale\nz = helper(1, 2, 3, scale=2)",
    "def step(planner):\n    def approach(hand, dz=0.1):\n        def lift(h):\n            return h\n"
    "        return lift(hand)\n    approach('left')",
    "def f(a, /, b, *, c):\n    return a + b + c\nf(1, 2, c=3)",
    "def f(x: float, hand: str = 'left') -> list[float]:\n    return [x]",  # any annotation: never evaluated
    "y: dict[str, list[int]] = {}\nz: int",
    "f = lambda x, k=1: x * k\ng = sorted([3, 1], key=lambda v: -v)",
    "i = 0\nwhile i < 3:\n    i += 1\nelse:\n    pass",
    "while True:\n    break",
    "try:\n    x = 1 / 0\nexcept ZeroDivisionError:\n    x = 0\nexcept (ValueError, KeyError) as e:\n    print(e)\n"
    "except Exception as e:\n    raise RuntimeError('failed') from e\nelse:\n    x = 2\nfinally:\n    print('done')",
    "try:\n    pass\nexcept* ValueError:\n    pass",
    "for k, v in {'a': 1}.items():\n    print(k, v)",
    "for p in planner.poses():\n    pass",
    "for i, x in enumerate(np.linspace(0, 1, 5)):\n    pass",
    "for c in 'abc':\n    continue",
    "def f():\n    if True:\n        return 1\n    return",
    "n = 0\ndef bump():\n    global n\n    n += 1",
    "def outer():\n    n = 0\n    def inner():\n        nonlocal n\n        n += 1\n    inner()\n    return n",
    "global n\nn = 1",  # a no-op at top level, harmless
    "x = [1, 2]\ny = {'a': 1}\ndel x[0]\ndel y['a'], x\ndel planner",
    "assert 1 < 2, 'ordered'",
    "x = 1 if planner else 2",
    "a = [x * 2 for x in range(3) if x]\nb = {x: x for x in a}\nc = {x for x in a}\nd = sum(x for x in a)",
    "if (n := len([1])) > 0:\n    pass",
    "import numpy as np",
    "import numpy",
    "import math",
    "import math as m",
    "from math import pi, sqrt",
    "from numpy import array",
    "import numpy.linalg as la",
    "import numpy.linalg",
    "import numpy.random",
    "from numpy.linalg import norm as n2",
    "dir = np.array([1, 0, 0])\ntype = 'grasp'\nprint(dir, type)",  # plan variables named like refused builtins
    "print('{0} {1:.3f} {name}'.format(1, 2.0, name='a'))",
    "print('{0[1]} {} {:>{w}}'.format([1, 2], 3, 4, w=5))",
    "x = '%s and %(a)s' % (1,)",  # %-formatting has no attribute paths
    "_, pose = 1, 2",
    "print(f'{planner!r:>10} {1 + 2:.3f}')",
])
def test_accepted(source: str) -> None:
    check_code(source, NAMES)


def test_accepted_constructs_run_with_safe_builtins() -> None:
    ns = run("import numpy as np\nimport math\nfrom math import pi, sqrt\nimport numpy.linalg as la\n"
             "from numpy.linalg import norm\nimport numpy\n"
             "def length(v, *, squared=False):\n    s = sum(x * x for x in v)\n    return s if squared else sqrt(s)\n"
             "r = length(np.array([3.0, 4.0]))\nk = 0\nwhile k < 3:\n    k += 1\n"
             "try:\n    bad = 1 / 0\nexcept ZeroDivisionError as e:\n    bad = str(e)\n"
             "twice = (lambda v: 2 * v)(pi)\nn = la.norm([3.0, 4.0]) + norm([6.0, 8.0])\n")
    assert ns["np"] is numpy and ns["numpy"] is numpy and ns["math"] is math and ns["la"] is numpy.linalg
    assert ns["r"] == 5.0 and ns["k"] == 3 and "division" in ns["bad"] and ns["twice"] == 2 * math.pi
    assert ns["n"] == 15.0


def test_step_function_with_helpers() -> None:
    src = "def helper(h):\n    return h * 2\ndef step(planner):\n    def inner():\n        return helper(1)\n" \
          "    return inner()\n"
    checked = check_code(src, NAMES)
    assert checked.defines_step and {"helper", "step", "inner"} <= checked.bound_names
    assert not check_code("def helper(planner):\n    pass", NAMES).defines_step
    ns = run(src)
    assert ns["step"](None) == 2


# -- refused, with line, column and what to do instead ------------------------------------------------------
@pytest.mark.parametrize("source, line, needles", [
    ("x = 1\nf = open('/etc/passwd')", 2, ["`open` is not available in plan code", "read or write files"]),
    ("eval('1')", 1, ["`eval`", "write the code itself"]),
    ("exec('x = 1')", 1, ["`exec`"]),
    ("compile('1', 's', 'eval')", 1, ["`compile`"]),
    ("getattr(planner, 'x')", 1, ["`getattr`", "obj.name"]),
    ("setattr(planner, 'x', 1)", 1, ["`setattr`"]),
    ("globals()", 1, ["`globals`"]),
    ("x = type(planner)", 1, ["`type`", "isinstance"]),
    ("\n\n__import__('os')", 3, ["`__import__`", "import numpy as np"]),
    ("print(__builtins__)", 1, ["`__builtins__`", "'__'"]),
    ("__x = 1", 1, ["`__x`"]),
    ("def f(__a):\n    pass", 1, ["`__a`"]),
    ("x = ().__class__", 1, ["`__class__`", "isinstance"]),
    ("planner._env", 1, ["`_env`", "private"]),
    ("np.f2py", 1, ["`f2py`", "module"]),
    ("np.random.bit_generator.re.enum.bltns", 1, ["`re`"]),
    ("np.load('x.npy')", 1, ["`load`", "files"]),
    ("g = (i for i in [1])\ng.gi_frame", 2, ["`gi_frame`", "internals"]),
    ("x = 1\nimport os", 2, ["`import os`", "import numpy as np", "import math",
                             "the planner API names (planner, Constraint, get_point_in_env, math, ...)"]),
    ("import numpy, os", 1, ["`import os`"]),
    ("import numpy.f2py", 1, ["`import numpy.f2py`"]),
    ("from os import path", 1, ["`from os import ...`", "from ... import"]),
    ("from . import x", 1, ["`from . import ...`"]),
    ("from math import *", 1, ["`from math import *`", "import the names you need"]),
    ("from numpy import load", 1, ["`load` cannot be imported from `numpy`"]),
    ("from numpy import _core", 1, ["`_core`"]),
    ("import humanoidgen.sandbox as h", 1, ["not needed", "already defined"]),
    ("from humanoidgen.api import Constraint", 1, ["not needed"]),
    ("class A:\n    pass", 1, ["`class`", "functions, dicts"]),
    ("@planner.wrap\ndef f():\n    pass", 1, ["decorators"]),
    ("def gen():\n    yield 1", 2, ["`yield`", "list"]),
    ("def gen():\n    yield from [1]", 2, ["`yield from`"]),
    ("async def f():\n    pass", 1, ["`async`"]),
    ("def f():\n    x = [1]\n    return [y async for y in x]", 3, ["`async`"]),
    ("with planner as p:\n    pass", 1, ["`with`"]),
    ("match planner:\n    case 1:\n        pass", 1, ["`match`", "if"]),
    ("del planner.x", 1, ["`del` of an attribute"]),
    ("x = 1\nreturn x", 2, ["`return` outside a function"]),
    ("nonlocal x", 1, ["`nonlocal` is only allowed inside a function"]),
    ("for i in range(3):\n    pass\nbreak", 3, ["'break' outside loop"]),
    ("def f():\n    nonlocal q", 2, ["nonlocal", "global"]),
    ("x = (", 1, ["syntax error"]),
    ("def step(planner, extra):\n    pass", 1, ["exactly one parameter"]),
    ("foo(1)", 1, ["unknown name `foo`"]),
    ("plannr.hand_pre_grasp('left')", 1, ["unknown name `plannr`", "did you mean `planner`?"]),
    ("Constrant()", 1, ["did you mean `Constraint`?"]),
    ("x = true", 1, ["did you mean `True`?"]),
    ("x = hex(1)", 1, ["the Python builtin `hex` is not available"]),
])
def test_refused(source: str, line: int, needles: list[str]) -> None:
    violations = rejected(source)
    hit = [v for v in violations if all(n in v.message for n in needles)]
    assert hit, violations
    assert hit[0].line == line and hit[0].col >= 0
    assert str(hit[0]).startswith(f"line {line}:")


def test_missing_numpy_name_suggests_the_import() -> None:
    (v,) = rejected("x = np.zeros(3)", {"planner"})
    assert "import numpy as np" in v.message
    (v,) = rejected("x = math.pi", {"planner"})
    assert "import math" in v.message


def test_one_message_per_refused_construct_and_sorted_lines() -> None:
    violations = rejected("x = 1\nclass A:\n    def __init__(self):\n        self.__x = open('f')\nplanner._y\n"
                          "import os\nos.listdir('/')\n")
    assert [v.line for v in violations] == [2, 5, 6]  # nothing from inside the class; `os` is bound by the import


def test_forbidden_names_are_refused_unless_the_plan_binds_them() -> None:
    rejected("print(dir)")
    check_code("for dir in [1, 2]:\n    print(dir)", NAMES)
    check_code("def format(x):\n    return str(x)\nformat(1)", NAMES)


# -- str.format field paths ----------------------------------------------------------------------------
@pytest.mark.parametrize("source, needle", [
    ("'{0.__class__}'.format(planner)", "`{0.__class__}` reads the attribute `.__class__`"),
    ("'{0.random}'.format(np)", "`{0.random}` reads the attribute `.random`"),
    ("'{0.random.mtrand.warnings.sys.modules[os].environ}'.format(np)", "reads the attribute `.random`"),
    ("x = {}\n'{a[os]}'.format(a=x)", "non-integer key `[os]`"),
    ("'{name.attr}'.format(name=planner)", "`.attr`"),
    ("'{0:{1.x}}'.format(1, planner)", "`{1.x}`"),  # nested format spec
    ("'{0[-1]}'.format([1])", "non-integer key"),
    ("'{0[}'.format([1])", "malformed"),
    ("fmt = '{0}'\nfmt.format(planner)", "only available on a string literal"),
    ("str.format('{0.x}', planner)", "only available on a string literal"),
    ("f = '{0.x}'.format\nf(planner)", "`.x`"),  # the bound method, not only calls
    ("f'{{0.x}}'.format(planner)", "only available on a string literal"),  # an f-string can build a template
    ("('{0' + '.x}').format(planner)", "only available on a string literal"),
    ("'{a}'.format_map({'a': 1})", "`.format_map(...)` is not available"),
])
def test_format_fields_refused(source: str, needle: str) -> None:
    violations = rejected(source)
    assert any(needle in v.message for v in violations), violations
    receiver_line = next(i for i, ln in enumerate(source.split("\n"), 1) if ".format" in ln)
    assert all(v.line == receiver_line for v in violations if needle in v.message)


@pytest.mark.parametrize("template", [
    "{0} {1:.3f} {name}", "{0[1]}", "{}", "{{literal}}", "{0!r:>10}", "{0:{1}}", "{a[0][2]:{w}.{p}f}", "plain",
])
def test_format_templates_allowed(template: str) -> None:
    assert format_template_problems(template) == []


def test_allowed_format_calls_run() -> None:
    ns = run("a = '{0} {1:.3f} {name}'.format(1, 2.0, name='a')\nb = '{0[1]}'.format([1, 2])")
    assert ns["a"] == "1 2.000 a" and ns["b"] == "2"


# -- restricted __import__ -----------------------------------------------------------------------------
def test_safe_builtins_contents() -> None:
    b = safe_builtins(MODULES)
    assert set(b) == {n for n in SAFE_BUILTINS} | {"__import__"}
    assert b["len"] is len and b["True"] is True
    assert "open" not in b and "getattr" not in b and "eval" not in b


def test_restricted_import_hands_out_only_given_modules() -> None:
    ns = run("import numpy as np")
    assert ns["np"] is numpy
    imp = safe_builtins(MODULES)["__import__"]
    with pytest.raises(ImportError, match="`os` cannot be imported in plan code; available: math, numpy"):
        imp("os")
    for bad in [("os.path",), ("numpy.f2py",), ("numpy", None, None, ("f2py",)), ("numpy", None, None, ("_core",)),
                ("math", None, None, ("*",)), ("math", None, None, (), 1), ("numpy.linalg", None, None, (), 2)]:
        with pytest.raises(ImportError):
            imp(*bad)
    assert imp("numpy.linalg") is numpy and imp("numpy.linalg", None, None, ("norm",)) is numpy.linalg
    # Executed without the checker, the builtins still refuse what the checker would have.
    for src in ("import os", "from numpy import f2py", "import subprocess as s", "from math import *"):
        with pytest.raises(ImportError):
            exec(src, {"__builtins__": safe_builtins(MODULES)})  # noqa: S102
    # A module not provided is not available even if the checker allows its import.
    with pytest.raises(ImportError, match="available: math"):
        exec("import numpy", {"__builtins__": safe_builtins({"math": math})})  # noqa: S102


def test_explicit_submodule_and_missing_submodule() -> None:
    fake = type(math)("fake_numpy")  # a provided numpy without linalg
    imp = safe_builtins({"numpy": fake, "numpy.linalg": numpy.linalg})["__import__"]
    assert imp("numpy.linalg", None, None, ("norm",)) is numpy.linalg
    with pytest.raises(ImportError):
        safe_builtins({"numpy": fake})["__import__"]("numpy.random", None, None, ("rand",))


# -- hostile input: never an uncaught RecursionError / MemoryError -------------------------------------------
@pytest.mark.parametrize("source", [
    "x = " + "-" * 15_000 + "1",
    "x = " + "(" * 5_000 + "1" + ")" * 5_000,
    "x = " + "[" * 5_000 + "]" * 5_000,
    "x = " + "-" * 2_000 + "1",  # parses, but deeper than `compile` can recurse
    "x = " + " + ".join(["1"] * 1_500),  # a long, left-nested chain under the node cap
    "x = " + "not " * 3_000 + "1",
    "for i in range(2):\n" + "".join("    " * (k + 1) + f"for j{k} in range(2):\n" for k in range(25))
    + "    " * 26 + "pass",  # too many statically nested blocks for Python
])
def test_deep_nesting_is_a_violation(source: str) -> None:
    violations = rejected(source)
    assert any("nested too deeply" in v.message for v in violations), violations


def test_checked_code_compile_turns_recursion_into_rejection() -> None:
    import ast

    deep = ast.parse("x = " + "-" * 2_000 + "1")
    with pytest.raises(CodeRejected, match="nested too deeply"):
        CheckedCode("", deep, False).compile()


def test_caps() -> None:
    assert "bytes" in rejected("x = 1\n" * 5_000)[0].message
    assert "syntax nodes" in rejected("x = [" + "1, " * (MAX_AST_NODES + 100) + "]")[0].message
    assert "syntax error" in rejected("x = 1\0")[0].message


# -- step splitting with helpers -------------------------------------------------------------------------
def test_split_steps_lone_step_function_becomes_its_body() -> None:
    (body,) = split_steps("```python\nfrom humanoidgen.x.solver_env import *\ndef step(planner):\n"
                          "    # Step 1\n    planner.hand_pre_grasp('left')\n```")
    assert body == "# Step 1\nplanner.hand_pre_grasp('left')"
    assert strip_api_imports("from humanoidgen.a.b import *\nx = 1") == "\nx = 1"


def test_split_steps_keeps_helpers_and_drops_explicit_step_call() -> None:
    (code,) = split_steps("```python\ndef helper(h):\n    return h\ndef step(planner):\n    helper('left')\n"
                          "step(planner)\n```")
    assert code == "def helper(h):\n    return h\ndef step(planner):\n    helper('left')"
    assert check_code(code, NAMES).defines_step


def test_split_steps_keeps_step_function_whose_body_returns() -> None:
    src = "def step(planner):\n    if planner is None:\n        return\n    x = 1"
    (code,) = split_steps(src)
    assert code == src and check_code(code, NAMES).defines_step


# -- by-name routes to `__globals__`, `__dict__`, the real builtins ----------------------------------------
# functools.update_wrapper copies (assigned) or merges (updated) attributes named by strings: with
# `updated=('__globals__',)` it merges a numpy module's globals (`sys`, the real `__builtins__`) into the
# plan's own namespace. numpy provides it through `contextlib.wraps` in the modules of `np.core`, its
# private package under a public name (tests/hostile/149_*, 150_*).
UPDATE_WRAPPER = ("def f():\n    pass\n"
                  "np.core.arrayprint.contextlib.wraps(np.core.arrayprint.get_printoptions, assigned=(), "
                  "updated=('__globals__',))(f)")


_BY_NAME = [
    (UPDATE_WRAPPER, 3, ["`core`"]),
    (UPDATE_WRAPPER, 3, ["`contextlib`"]),
    (UPDATE_WRAPPER, 3, ["`__globals__`"]),
    ("w = planner.wraps", 1, ["`wraps`", "by name"]),
    ("w = planner.update_wrapper", 1, ["`update_wrapper`"]),
    ("a = planner.WRAPPER_ASSIGNMENTS + planner.WRAPPER_UPDATES", 1, ["`WRAPPER_ASSIGNMENTS`"]),
    ("g = planner.attrgetter('x')", 1, ["`attrgetter`"]),
    ("g = planner.methodcaller('x')", 1, ["`methodcaller`"]),
    ("g = planner.getattr_static", 1, ["`getattr_static`"]),
    ("h = planner.get_type_hints", 1, ["`get_type_hints`"]),
    ("t = np.typing", 1, ["`typing`"]),
    ("m = np.ma.core", 1, ["`core`"]),
    ("names = ['__dict__']", 1, ["`__dict__`", "string"]),
    ("x = f'{1}__builtins__'", 1, ["`__builtins__`"]),
    ("b = b'__class__'", 1, ["`__class__`"]),
]


@pytest.mark.parametrize("source, line, needles", _BY_NAME, ids=[n[0].strip("`") for _, _, n in _BY_NAME])
def test_by_name_routes_are_refused(source: str, line: int, needles: list[str]) -> None:
    violations = rejected(source)
    assert [v for v in violations if v.line == line and all(n in v.message for n in needles)], violations


def test_update_wrapper_route_really_leaks_without_the_check() -> None:
    """The route is real (so the refusals above guard something): run unchecked, it lands `sys` and the real
    builtins in the plan's namespace."""
    import builtins
    import warnings

    ns = {"np": numpy, "__builtins__": safe_builtins(MODULES)}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # np.core is deprecated, not gone
        exec(compile(UPDATE_WRAPPER, "<step>", "exec"), ns)  # noqa: S102 - deliberately unchecked
    assert "sys" in ns and ns["__builtins__"]["open"] is builtins.open


def test_a_step_starts_with_the_safe_builtins_again() -> None:
    """The runner puts the restricted builtins back before every step: real ones a step smuggled into the
    namespace (by a route not known yet) do not carry over to the names of the next step."""
    from humanoidgen.sandbox.runner import _run

    safe = safe_builtins(MODULES)
    ns = {"planner": None, "np": numpy, "__builtins__": {"open": open}}
    out = _run("x = len([1])", ns, safe)
    assert out.ok and ns["__builtins__"] is safe
