"""A script of bench/ in a test. The scripts run as `python bench/x.py`, not as a package, so a test loads one from
its file: a fresh module each call (tests monkeypatch their globals), registered under its name so that the
dataclasses it defines find their module."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

BENCH = Path(__file__).resolve().parents[1] / "bench"


def load_bench(name: str, module_name: str | None = None) -> ModuleType:
    """bench/<name>.py as a module (named `module_name`, default bench_<name>)."""
    spec = importlib.util.spec_from_file_location(module_name or f"bench_{name}", BENCH / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod
