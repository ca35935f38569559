"""The `deb` package kind: a Debian package, `apt-get download NAME=VERSION` (into the cache folder, never
installed; apt's lists must be there: `apt-get update`). Its files are those of its data archive, by their
installed path without the leading `./` (`usr/share/...`)."""

from __future__ import annotations

import bz2
import gzip
import io
import lzma
import tarfile
from pathlib import Path


class DebFiles:
    """The data archive of a .deb, read into memory once: the library takes a few files from it, at random."""

    def __init__(self, path: Path):
        data = _ar_member(Path(path).read_bytes(), "data.tar")
        self._tar = tarfile.open(fileobj=io.BytesIO(data), mode="r:")
        self._members = {m.name.removeprefix("./"): m for m in self._tar.getmembers() if m.isfile()}

    def namelist(self) -> list[str]:
        return list(self._members)

    def read(self, name: str) -> bytes:
        f = self._tar.extractfile(self._members[name])
        assert f is not None
        return f.read()

    def close(self) -> None:
        self._tar.close()


def _ar_member(blob: bytes, stem: str) -> bytes:
    """The (decompressed) member of an ar archive named `stem` or `stem.<compression>`."""
    if not blob.startswith(b"!<arch>\n"):
        raise ValueError("not a Debian package (no ar header)")
    pos = 8
    while pos + 60 <= len(blob):
        head = blob[pos:pos + 60]
        name = head[:16].decode().strip().rstrip("/")
        size = int(head[48:58].decode().strip())
        body = blob[pos + 60:pos + 60 + size]
        if name == stem or name.startswith(stem + "."):
            ext = name[len(stem):]
            if ext in ("", ".tar"):
                return body
            unpack = {".xz": lzma.decompress, ".gz": gzip.decompress, ".bz2": bz2.decompress}.get(ext)
            if unpack is None:
                raise ValueError(f"{name}: a compression this reader does not know")
            return unpack(body)
        pos += 60 + size + (size % 2)  # members are 2-byte aligned
    raise ValueError(f"no {stem} member in the package")


class DebKind:
    def command(self, package: str, version: str) -> list[str]:
        return ["apt-get", "download", f"{package}={version}"]

    def cached(self, package: str, version: str, folder: Path) -> Path | None:
        # apt writes an epoch's colon as %3a in the file name
        found = sorted(folder.glob(f"{package}_{version.replace(':', '%3a')}_*.deb"))
        return found[0] if found else None

    def open(self, path: Path) -> DebFiles:
        return DebFiles(path)

    def pin(self, package: str, version: str) -> str:
        return f"{package}={version} (deb)"
