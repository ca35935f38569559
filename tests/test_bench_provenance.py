"""bench/provenance.py: the commit a benchmark result says it came from, marked "+changes" where tracked files differ
from it (untracked ones do not count), "unknown" outside a checkout; and the machine in a few words."""

from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

import pytest
from bench_scripts import load_bench


def _provenance():
    return load_bench("provenance")


@pytest.fixture(autouse=True)
def _git_env(monkeypatch, tmp_path):
    """git as in a plain shell (a git hook running these tests sets GIT_DIR and the like), and never looking above
    tmp_path for a checkout (were tmp_path inside one, a plain folder there would be in it)."""
    for name in [k for k in os.environ if k.startswith("GIT_")]:
        monkeypatch.delenv(name)
    monkeypatch.setenv("GIT_CEILING_DIRECTORIES", str(tmp_path))


def _git(where: Path, *args: str) -> str:
    return subprocess.run(["git", *args], cwd=where, check=True, capture_output=True, text=True).stdout.strip()


@pytest.fixture
def repo(tmp_path: Path) -> Path:
    where = tmp_path / "repo"
    where.mkdir()
    _git(where, "init", "-q")
    _git(where, "config", "user.email", "bench@example.com")
    _git(where, "config", "user.name", "bench")
    _git(where, "config", "commit.gpgsign", "false")
    (where / "code.py").write_text("x = 1\n")
    _git(where, "add", "code.py")
    _git(where, "commit", "-q", "-m", "one")
    return where


def test_this_repository_has_a_commit():
    assert re.fullmatch(r"[0-9a-f]{7,}(\+changes)?", _provenance().commit())


def test_a_fresh_repository_is_its_commit_until_a_tracked_file_changes(repo):
    prov = _provenance()
    assert prov.commit(repo) == _git(repo, "rev-parse", "--short", "HEAD")
    (repo / "results.json").write_text("{}")  # untracked: what a benchmark writes, not the code that ran
    assert prov.commit(repo) == _git(repo, "rev-parse", "--short", "HEAD")
    (repo / "code.py").write_text("x = 2\n")
    assert prov.commit(repo) == _git(repo, "rev-parse", "--short", "HEAD") + "+changes"


def test_full_is_the_whole_hash(repo):
    full = _provenance().commit(repo, full=True)
    assert re.fullmatch(r"[0-9a-f]{40}", full) and full == _git(repo, "rev-parse", "HEAD")


def test_a_folder_outside_any_checkout_is_unknown(tmp_path):
    outside = tmp_path / "plain"
    outside.mkdir()
    assert _provenance().commit(outside) == "unknown"


def test_a_missing_folder_is_unknown_not_an_error(tmp_path):
    assert _provenance().commit(tmp_path / "gone") == "unknown"


def test_without_git_it_is_unknown_not_an_error(repo, monkeypatch):
    monkeypatch.setenv("PATH", str(repo))  # no git there
    assert _provenance().commit(repo) == "unknown"


def test_machine_says_how_many_cpus():
    text = _provenance().machine()
    assert f"{os.cpu_count()} CPUs" in text and "Python" in text
