"""The package's layers, bottom to top: data flows one way (assets -> scene -> plan -> execute -> verify ->
record -> dataset -> policy). A module may import from its own package and from the packages below it, never
from one above: found by reading every import statement of every module (those inside functions and under
TYPE_CHECKING too, where an arrow back up likes to hide)."""

from __future__ import annotations

import ast
from pathlib import Path

import humanoidgen

ROOT = Path(humanoidgen.__file__).resolve().parent
LAYERS = ["assets", "sim", "objects", "scenes", "planning", "tasks", "llm", "sandbox", "episodes", "generation",
          "mcts", "envs", "policies", "cli"]
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
