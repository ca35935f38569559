"""What plan code may name: the builtins it gets, the modules it may import, the names and attributes the
checker refuses (with what to write instead), and the `__builtins__` dict the plan worker installs
(`safe_builtins`). Data for the checker (`checker.py`) and the runner; the lists are known routes, not a wall.
"""

from __future__ import annotations

import builtins
import re
import sys
from collections.abc import Mapping
from types import ModuleType
from typing import Any

# Builtins plan code may use; `safe_builtins` installs exactly these (and a restricted `__import__`).
SAFE_BUILTINS: frozenset[str] = frozenset({
    "range", "len", "abs", "min", "max", "sum", "round", "float", "int", "bool", "str", "list", "tuple", "dict",
    "set", "enumerate", "zip", "print", "sorted", "reversed", "any", "all", "isinstance", "divmod", "map",
    "filter", "True", "False", "None",
    "Exception", "ValueError", "RuntimeError", "TypeError", "KeyError", "IndexError", "AssertionError",
    "ZeroDivisionError", "ArithmeticError", "AttributeError", "NotImplementedError", "LookupError", "OverflowError",
})

FORBIDDEN_NAMES: frozenset[str] = frozenset({
    "open", "exec", "eval", "compile", "getattr", "setattr", "delattr", "hasattr", "__import__", "globals",
    "locals", "vars", "dir", "input", "breakpoint", "help", "type", "object", "super", "memoryview", "id",
    "classmethod", "staticmethod", "property", "exit", "quit", "iter", "next", "aiter", "anext", "callable",
    "issubclass", "hash", "format", "chr", "ord", "bytes", "bytearray", "frozenset", "slice",
})

_NAME_HINTS: dict[str, str] = {
    "open": "plans cannot read or write files",
    **dict.fromkeys(("exec", "eval", "compile"), "plans cannot run code built from strings; write the code itself"),
    "getattr": "write the attribute itself (`obj.name`)",
    "setattr": "assign the attribute itself (`obj.name = value`)",
    "delattr": "plans cannot delete attributes",
    "hasattr": "use the attribute and catch `AttributeError` (`try: ... except AttributeError: ...`)",
    **dict.fromkeys(("globals", "locals", "vars", "dir"), "plans cannot inspect namespaces or objects; "
                    "use the planner API and the names you assigned"),
    "input": "plans cannot read input",
    **dict.fromkeys(("exit", "quit", "breakpoint", "help"), "to stop a step, raise an exception "
                    "(`raise RuntimeError('why')`)"),
    "type": "to test a type, use `isinstance(x, T)`",
    **dict.fromkeys(("object", "super", "classmethod", "staticmethod", "property"),
                    "plans cannot define classes; use functions, dicts and tuples"),
    **dict.fromkeys(("memoryview", "bytes", "bytearray", "chr", "ord"), "work with str, lists and numpy arrays"),
    **dict.fromkeys(("id", "hash"), "compare values with `==` (or `is None`)"),
    **dict.fromkeys(("iter", "next", "aiter", "anext"), "loop with `for`, or index a list"),
    **dict.fromkeys(("callable", "issubclass"), "use `isinstance(x, T)`"),
    "format": "use an f-string (f\"{x:.3f}\")",
    "frozenset": "use `set(...)` or `tuple(...)`",
    "slice": "index with `a[i:j]`",
    "__import__": "write `import numpy as np` or `import math`",
}

# Attribute names that lead to interpreter internals, other modules or files without a leading underscore.
# Known routes (e.g. found by walking `np`'s public attributes, see tests/test_sandbox.py), not a complete list.
_INTERNAL_ATTRIBUTES = frozenset({
    "gi_frame", "gi_code", "gi_yieldfrom", "cr_frame", "cr_code", "cr_await", "ag_frame", "ag_code",
    "f_globals", "f_locals", "f_builtins", "f_back", "f_code", "tb_frame", "tb_next", "co_code", "mro",
    "func_globals", "format_map",
})
_MODULE_ATTRIBUTES = frozenset({
    "os", "sys", "subprocess", "builtins", "importlib", "ctypes", "ctypeslib", "pickle", "io", "shutil",
    "pathlib", "socket", "inspect", "types", "tempfile", "platform", "gc", "marshal", "runpy", "signal",
    "threading", "multiprocessing", "f2py", "testing", "distutils", "lib", "mmap", "glob", "urllib",
    "bltns", "enum", "re", "warnings", "operator", "functools",
    "core",  # numpy's private `_core` under a public name (np.core.arrayprint holds contextlib, sys, ...)
})
# Helpers that read or write attributes named by strings, and the modules holding them: with them a string
# reaches what the attribute check refuses (`update_wrapper(f, g, updated=('__globals__',))` merges a module's
# globals, `sys` and the real builtins, into the plan's namespace).
_BY_NAME_ATTRIBUTES = frozenset({
    "contextlib", "wraps", "update_wrapper", "WRAPPER_ASSIGNMENTS", "WRAPPER_UPDATES", "attrgetter",
    "methodcaller", "getattr_static", "get_type_hints", "typing", "dataclasses", "copyreg", "string",
})
_FILE_ATTRIBUTES = frozenset({
    "load", "loads", "save", "savez", "savez_compressed", "savetxt", "loadtxt", "genfromtxt", "fromfile",
    "fromregex", "tofile", "dump", "dumps", "memmap", "DataSource", "open_memmap",
})
BLOCKED_ATTRIBUTES: frozenset[str] = _INTERNAL_ATTRIBUTES | _MODULE_ATTRIBUTES | _FILE_ATTRIBUTES | _BY_NAME_ATTRIBUTES
# A string spelling a dunder name (`'__globals__'`, `'{0.__dict__}'`): only a by-name helper has a use for it.
_DUNDER = re.compile(r"__\w+__")

_NUMPY_OWN = "numpy._"  # numpy's private modules, e.g. numpy._core.arrayprint

# What `import` may bind (the runner's `safe_builtins(modules)` provides the modules themselves).
ALLOWED_IMPORTS: frozenset[str] = frozenset({"numpy", "math", "numpy.linalg", "numpy.random"})

def safe_builtins(modules: Mapping[str, ModuleType]) -> dict[str, Any]:
    """The `__builtins__` dict for plan code: `SAFE_BUILTINS` plus an `__import__` that only hands out `modules`.

    `modules` maps import names to modules, e.g. `{"numpy": numpy, "math": math}`; a submodule in
    `ALLOWED_IMPORTS` (`numpy.linalg`) is found as an attribute of its provided parent unless given itself.
    Any other import raises ImportError saying what is available.
    """
    out: dict[str, Any] = {name: getattr(builtins, name) for name in SAFE_BUILTINS if hasattr(builtins, name)}
    provided = dict(modules)

    def restricted_import(name: str, globals: Any = None, locals: Any = None, fromlist: Any = (),
                          level: int = 0) -> ModuleType:
        if level == 0 and isinstance(name, str) and name.startswith(_NUMPY_OWN) and name in sys.modules:
            # numpy's own lazy imports of its loaded modules, made from its C code through the caller's
            # `__import__` (printing an array imports numpy._core.arrayprint). Plan code cannot ask for these
            # itself: it cannot name `__import__`, and the checker refuses `_` names in its own imports.
            return sys.modules[name]
        module = _resolve_module(provided, name) if level == 0 and isinstance(name, str) else None
        refused = [str(n) for n in fromlist or ()
                   if not isinstance(n, str) or n == "*" or n.startswith("_") or n in BLOCKED_ATTRIBUTES]
        if module is None or refused:
            available = ", ".join(sorted(set(provided) | {m for m in ALLOWED_IMPORTS if _resolve_module(provided, m)}))
            what = f"`{', '.join(refused)}` from `{name}`" if module else f"`{'.' * level}{name}`"
            raise ImportError(f"{what} cannot be imported in plan code; available: {available or 'none'}; "
                              "the planner API names are already defined", name=name)
        # Python's protocol: `from a.b import x` gets `a.b`; `import a.b [as c]` gets `a` (then takes `.b` itself).
        return module if fromlist else _resolve_module(provided, name.partition(".")[0])

    out["__import__"] = restricted_import
    return out


def _resolve_module(provided: dict[str, ModuleType], name: str) -> ModuleType | None:
    if name in provided:
        return provided[name]
    parent, _, child = name.rpartition(".")
    if name not in ALLOWED_IMPORTS or not parent:
        return None
    module = getattr(_resolve_module(provided, parent), child, None)
    return module if isinstance(module, ModuleType) else None
