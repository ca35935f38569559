"""The `pip` package kind: a wheel from PyPI, `pip download --no-deps` (never installed)."""

from __future__ import annotations

import sys
import zipfile
from pathlib import Path


class PipKind:
    def command(self, package: str, version: str) -> list[str]:
        return [sys.executable, "-m", "pip", "download", "--no-deps", "--only-binary=:all:",
                "--disable-pip-version-check", "-q", f"{package}=={version}", "-d", "."]

    def cached(self, package: str, version: str, folder: Path) -> Path | None:
        found = sorted(folder.glob(f"{package.replace('-', '_')}-{version}-*.whl"))
        return found[0] if found else None

    def open(self, path: Path) -> zipfile.ZipFile:
        return zipfile.ZipFile(path)

    def pin(self, package: str, version: str) -> str:
        return f"{package}=={version}"
