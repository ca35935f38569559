"""The planning pipeline's shape: every recovery is one file behind the Recovery protocol, registered in
pipeline.py, which is the only module that imports them; recoveries import neither the API, the pipeline nor
each other; the docs' table is generated from the registry; and the pipeline runs them as documented."""

from __future__ import annotations

import ast
import importlib
import sys
from pathlib import Path

import pytest

from humanoidgen.planning import pipeline
from humanoidgen.planning.pipeline import RECOVERIES, Pipeline, design_table
from humanoidgen.planning.recovery import Recovery

PLANNING = Path(pipeline.__file__).resolve().parent
PACKAGE = PLANNING.parent
RECOVERY_FILES = sorted(p for p in (PLANNING / "recoveries").glob("*.py") if p.name != "__init__.py")


def _imports(path: Path) -> set[str]:
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module:
            out |= {node.module, *(f"{node.module}.{a.name}" for a in node.names)}
        elif isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
    return out


def test_every_recovery_file_holds_one_registered_recovery():
    registered = {type(r) for r in RECOVERIES}
    for path in RECOVERY_FILES:
        module = importlib.import_module(f"humanoidgen.planning.recoveries.{path.stem}")
        mine = [c for c in vars(module).values()
                if isinstance(c, type) and issubclass(c, Recovery) and c is not Recovery and c.__module__ == module.__name__]
        assert len(mine) == 1, f"{path.name}: {len(mine)} recoveries (one file, one recovery)"
        assert mine[0] in registered, f"{mine[0].__name__} is not registered in pipeline.RECOVERIES"
    assert len(registered) == len(RECOVERY_FILES) == len(RECOVERIES)


def test_only_the_pipeline_imports_recoveries():
    importers = [p.relative_to(PACKAGE).as_posix() for p in PACKAGE.rglob("*.py")
                 if "recoveries" not in p.parts and p.name != "pipeline.py"
                 and any(m.startswith("humanoidgen.planning.recoveries") for m in _imports(p))]
    assert importers == []


def test_a_recovery_imports_neither_the_api_nor_the_pipeline_nor_another_recovery():
    for path in RECOVERY_FILES:
        bad = {m for m in _imports(path) if m.startswith(("humanoidgen.planning.planner", "humanoidgen.planning.pipeline",
                                                          "humanoidgen.planning.recoveries"))}
        assert not bad, f"{path.name} imports {sorted(bad)}"


def test_every_recovery_says_what_it_answers_tries_and_leaves():
    for row in design_table():
        assert row["stage"] in ("goal", "transit", "move", "release") and row["trigger"] in ("failure", "before", "after")
        assert all(row[k].strip() for k in ("answers", "tries", "event")), row
        assert (PACKAGE.parent / "humanoidgen" / row["file"]).exists(), row["file"]


def test_the_docs_table_is_generated_from_the_registry():
    sys.path.insert(0, str(PACKAGE.parent / "docs"))
    try:
        hooks = importlib.import_module("hooks")
    finally:
        sys.path.pop(0)
    page = (PACKAGE.parent / "docs" / "design" / "planning.md").read_text()
    assert hooks.TABLE_MARK in page
    table = hooks.on_page_markdown(page, None, None, None)
    assert all(f"`{type(r).__name__}`" in table for r in RECOVERIES)


class _Failing(Exception):
    pass


def _recovery(stage, trigger, applies, result, calls):
    class R(Recovery):
        answers = tries = event = "x"

        def applies(self, ctx, request, failure):
            return applies

        def attempt(self, ctx, request, failure):
            calls.append(result)
            return result
    R.stage, R.trigger = stage, trigger
    return R()


def test_the_first_recovery_that_applies_answers_and_none_leaves_the_failure():
    calls: list = []
    pipe = Pipeline((_recovery("goal", "failure", False, "skipped", calls), _recovery("goal", "failure", True, "first", calls),
                     _recovery("goal", "failure", True, "second", calls), _recovery("transit", "failure", True, "other", calls)))
    assert pipe.recover(None, "goal", None, _Failing()) == "first" and calls == ["first"]
    with pytest.raises(_Failing):
        Pipeline(()).recover(None, "goal", None, _Failing())


def test_a_before_recovery_may_take_the_request_over():
    calls: list = []
    pipe = Pipeline((_recovery("release", "before", True, False, calls), _recovery("release", "before", True, True, calls),
                     _recovery("release", "before", True, True, calls)))
    assert pipe.before(None, "release", None) is True and calls == [False, True]
    assert Pipeline(()).before(None, "release", None) is False


def test_the_design_page_says_which_layer_every_planning_module_is_in():
    """The design page's layer table is where each module's rule is stated: a new module must take its place."""
    page = (PACKAGE.parent / "docs" / "design" / "planning.md").read_text()
    table = page[page.index("| layer | modules | rule |"):]
    table = table[:table.index("\n\n")]
    missing = [p.stem for p in PLANNING.glob("*.py") if p.stem != "__init__" and f"`{p.stem}`" not in table]
    assert not missing, f"planning modules not in the design page's layer table: {missing}"
