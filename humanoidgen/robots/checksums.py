"""A robot's model-file checksums: `sha256sum` lines (`<hex>  ./path`), read and checked file by file."""

from __future__ import annotations

import hashlib
from pathlib import Path, PurePosixPath

_CHUNK = 1 << 16


def _safe_relpath(name: str) -> str:
    """Reject names that could write outside the robot folder (the sums file drives writes)."""
    path = PurePosixPath(name)
    if (
        not name
        or "\\" in name
        or path.is_absolute()
        or ".." in path.parts
        or (path.parts and ":" in path.parts[0])  # e.g. a Windows drive 'C:'
    ):
        raise ValueError(f"unsafe file name in sums file: {name!r}")
    return path.as_posix()


def parse_sums(text: str) -> dict[str, str]:
    """Parse `sha256sum` output (`<hex>  ./path`) into {relative path: hex digest}."""
    sums: dict[str, str] = {}
    for lineno, line in enumerate(text.splitlines(), 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        digest, sep, name = line.strip().partition(" ")
        name = name.lstrip(" *")  # '*' marks binary mode in sha256sum output
        if not sep or len(digest) != 64 or any(c not in "0123456789abcdefABCDEF" for c in digest):
            raise ValueError(f"bad line {lineno} in sums file: {line!r}")
        if name.startswith("./"):
            name = name[2:]
        sums[_safe_relpath(name)] = digest.lower()
    return sums


def sha256_file(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        # Chunked so memory stays flat whatever the mesh size.
        for chunk in iter(lambda: f.read(_CHUNK), b""):
            h.update(chunk)
    return h.hexdigest()
