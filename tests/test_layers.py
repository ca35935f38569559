"""The package's layers, bottom to top: data flows one way (assets -> scene -> plan -> execute -> verify ->
record -> dataset -> policy). A module may import from its own package and from the packages below it, never
from one above: found by reading every import statement of every module (those inside functions and under
TYPE_CHECKING too, where an arrow back up likes to hide)."""

from __future__ import annotations

import ast
from pathlib import Path

import humanoidgen

ROOT = Path(humanoidgen.__file__).resolve().parent
LAYERS = ["robots", "assets", "sim", "objects", "scenes", "planning", "tasks", "llm", "sandbox", "episodes",
          "generation", "mcts", "envs", "policies", "cli"]
# Plan files and task specs are data that plan code reads, not modules of the package.
NOT_MODULES = ("tasks/specs/",)


def _imports(path: Path) -> list[tuple[int, str]]:
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            out.append((node.lineno, node.module))
        elif isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
    return [(line, m) for line, m in out if m == "humanoidgen" or m.startswith("humanoidgen.")]


def _package(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and (ROOT / parts[1]).is_dir() else None


def test_every_package_has_a_layer():
    packages = {p.name for p in ROOT.iterdir() if p.is_dir() and (p / "__init__.py").exists() or
                p.is_dir() and any(p.glob("*.py"))} - {"__pycache__"}
    assert packages <= set(LAYERS), f"packages without a layer: {sorted(packages - set(LAYERS))}"


def test_no_import_runs_back_up_a_layer():
    rank = {name: k for k, name in enumerate(LAYERS)}
    upward = []
    for path in sorted(ROOT.rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if rel.startswith(NOT_MODULES) or "/" not in rel:
            continue
        here = rel.split("/")[0]
        for line, module in _imports(path):
            there = _package(module)
            if there is not None and there != here and rank[there] > rank[here]:
                upward.append(f"{rel}:{line} ({here}) imports {module} ({there})")
    assert not upward, "imports that run back up a layer:\n" + "\n".join(upward)


def _module_of(path: Path) -> str:
    rel = path.relative_to(ROOT.parent).with_suffix("")
    parts = list(rel.parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _runtime_nodes(tree: ast.AST):
    """Every node of the module but those under `if TYPE_CHECKING:` (annotations only: such an import never runs)."""
    skip = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            skip |= {id(n) for stmt in node.body for n in ast.walk(stmt)}
    return [n for n in ast.walk(tree) if id(n) not in skip]


def _module_graph() -> dict[str, set[str]]:
    """module -> the package modules it imports (`from pkg import mod` counts as importing `pkg.mod`)."""
    paths = {_module_of(p): p for p in ROOT.rglob("*.py") if not p.relative_to(ROOT).as_posix().startswith(NOT_MODULES)}
    graph: dict[str, set[str]] = {}
    for name, path in paths.items():
        deps = set()
        for node in _runtime_nodes(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0 and node.module.startswith("humanoidgen"):
                for alias in node.names:
                    sub = f"{node.module}.{alias.name}"
                    deps.add(sub if sub in paths else node.module)
            elif isinstance(node, ast.Import):
                deps |= {a.name for a in node.names if a.name.startswith("humanoidgen")}
        graph[name] = {d for d in deps if d in paths and d != name and not paths[d].name == "__init__.py"}
    return graph


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_no_circle_of_imports_between_modules():
    """Every import that runs counted, those inside functions too: a circle hidden in a function is still a circle."""
    cycles = _cycles(_module_graph())
    assert not cycles, "modules that import each other in a circle:\n" + "\n".join(" <-> ".join(c) for c in cycles)


def test_the_cycle_finder_finds_a_circle():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def test_no_module_is_over_400_lines():
    """A module over ~400 lines is a sign to split it (the house's rule); each says its one job in a docstring."""
    long = {p.relative_to(ROOT).as_posix(): n for p in ROOT.rglob("*.py")
            if not p.relative_to(ROOT).as_posix().startswith(NOT_MODULES)
            and (n := len(p.read_text(encoding="utf-8").splitlines())) > 400}
    assert not long, f"modules over 400 lines: {long}"
    silent = [p.relative_to(ROOT).as_posix() for p in ROOT.rglob("*.py")
              if not p.relative_to(ROOT).as_posix().startswith(NOT_MODULES) and p.read_text(encoding="utf-8").strip()
              and not ast.get_docstring(ast.parse(p.read_text(encoding="utf-8")))]
    assert not silent, f"modules without a docstring: {silent}"
