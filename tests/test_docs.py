"""The README is a short guide and the documentation site builds: no simulation, a few seconds.

- every relative link in README.md points to a file that exists;
- README.md has at most 220 lines (the guide; details belong in docs/);
- every page in mkdocs.yml's nav exists under docs/;
- `mkdocs build --strict` succeeds (skipped only where mkdocs is not installed; scripts/setup.sh installs it).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
MKDOCS_YML = ROOT / "mkdocs.yml"
README_MAX_LINES = 220

# [text](target) and ![alt](target); the target ends at whitespace or ')', an optional "title" after it.
_LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
_FENCE = re.compile(r"^\s*(```|~~~)")


def _markdown_links(text: str) -> list[str]:
    """Link targets outside fenced code blocks and inline code spans."""
    targets, in_fence = [], False
    for line in text.splitlines():
        if _FENCE.match(line):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        line = re.sub(r"`[^`]*`", "", line)
        targets.extend(_LINK.findall(line))
    return targets


def _is_relative(target: str) -> bool:
    return not (re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith(("#", "/")))


def _is_external(target: str) -> bool:
    return bool(re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*://", target))


def _nav_pages(node) -> list[str]:
    """Every page path in an mkdocs nav (strings, {title: page} and {title: [ ... ]} entries)."""
    if isinstance(node, str):
        return [] if _is_external(node) else [node]
    if isinstance(node, list):
        return [page for item in node for page in _nav_pages(item)]
    if isinstance(node, dict):
        return [page for value in node.values() for page in _nav_pages(value)]
    return []


def _mkdocs_config() -> dict:
    return yaml.safe_load(MKDOCS_YML.read_text())


def test_link_scanner_sees_links_and_skips_code():
    text = "see [a](docs/a.md) and ![p](img/p.png \"t\")\n`[no](x.md)`\n```\n[no](y.md)\n```\n[web](https://x.org)"
    assert _markdown_links(text) == ["docs/a.md", "img/p.png", "https://x.org"]


def test_readme_relative_links_exist():
    links = [t for t in _markdown_links(README.read_text()) if _is_relative(t)]
    assert links, "README.md links to no file: it should point to the docs pages"
    missing = [t for t in links if not (ROOT / t.split("#", 1)[0]).exists()]
    assert not missing, f"README.md links to files that do not exist: {missing}"


def test_readme_is_short():
    lines = README.read_text().count("\n")
    assert lines <= README_MAX_LINES, (
        f"README.md has {lines} lines (at most {README_MAX_LINES}): it is the short guide; move details to docs/"
    )


def test_readme_keeps_the_two_commands_first():
    head = README.read_text().splitlines()[:6]
    assert any(line.startswith("bash scripts/setup.sh") for line in head)
    assert any(line.startswith("python3 -m pytest -q") for line in head)


def test_nav_pages_exist():
    config = _mkdocs_config()
    docs_dir = ROOT / config.get("docs_dir", "docs")
    pages = _nav_pages(config["nav"])
    assert pages, "mkdocs.yml has no nav pages"
    missing = [p for p in pages if not (docs_dir / p).is_file()]
    assert not missing, f"mkdocs.yml's nav names pages that do not exist under {docs_dir.name}/: {missing}"


def test_mkdocs_build_strict(tmp_path):
    pytest.importorskip("mkdocs")
    pytest.importorskip("material")
    result = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file", str(MKDOCS_YML),
         "--site-dir", str(tmp_path / "site")],
        cwd=ROOT, capture_output=True, text=True, timeout=120,
        env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},
    )
    assert result.returncode == 0, f"mkdocs build --strict failed:\n{result.stdout}\n{result.stderr}"
    site = tmp_path / "site"
    assert (site / "index.html").is_file()
    # The hook serves bench/results' pictures; a results page shows them.
    assert (site / "results" / "img" / "hgen_bench_50.png").is_file()
