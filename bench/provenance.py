"""Which code and which machine a benchmark result came from, written into the result itself.

A result measured on uncommitted code must say so: the commit alone would credit (or blame) code that never ran.
So `commit()` marks a checkout whose tracked files differ from HEAD with "+changes" (untracked files, such as the
results being written, do not count), and says "unknown" rather than failing where git or the checkout is missing:
a benchmark's numbers are worth keeping even where its provenance cannot be read.

Scripts in bench/ run as `python bench/x.py` and are also loaded by tests from their file (bench/ not on sys.path),
so each puts its own folder on sys.path before `from provenance import commit`.
"""

from __future__ import annotations

import os
import platform
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]  # the repository this file belongs to


def _git(where: Path, *args: str) -> str:
    """git's stdout in `where` (stripped); raises OSError or CalledProcessError where git fails or is missing."""
    return subprocess.run(["git", *args], cwd=where, capture_output=True, text=True, check=True).stdout.strip()


def commit(where: Path | None = None, full: bool = False) -> str:
    """HEAD of the checkout at `where` (default: this repository), short or `full` (40 hex digits), with "+changes"
    when tracked files differ from it; "unknown" where it is not a checkout or git fails or is missing."""
    where = Path(where) if where is not None else ROOT
    try:
        head = _git(where, "rev-parse", "HEAD") if full else _git(where, "rev-parse", "--short", "HEAD")
        changed = _git(where, "status", "--porcelain", "--untracked-files=no")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    if not head:
        return "unknown"
    return head + ("+changes" if changed else "")


def machine() -> str:
    """The machine in a few words, e.g. "x86_64, 2 CPUs, Python 3.11.7"."""
    return f"{platform.machine()}, {os.cpu_count()} CPUs, Python {platform.python_version()}"
