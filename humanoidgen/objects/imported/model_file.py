"""An imported model's folder: `model.yaml` (what it is, where it came from, its links, joints and masses),
`meshes.npz` (visual and convex collision meshes per link, metres, object frame), `annotations.yaml` (the
transferred annotations), `transfer.yaml` (each point's confidence) and, where a point needs a hand,
`annotations.override.yaml` (positions that replace the transferred ones). Folders are found under
`<models folder>/<family>/<name>/` in the folders of $HGEN_FAMILIES_PATH and the fetched library."""

from __future__ import annotations

import os
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Literal

import numpy as np
import yaml
from pydantic import Field, ValidationError

from humanoidgen.objects.schema import Articulation, ObjectAnnotations, Vec3, _Strict, load_annotations, \
    validation_details

MODEL_FILE, MESH_FILE, ANNOTATION_FILE = "model.yaml", "meshes.npz", "annotations.yaml"
TRANSFER_FILE, OVERRIDE_FILE, PREVIEW_FILE = "transfer.yaml", "annotations.override.yaml", "preview.png"
LIBRARY_DIR = "object_library"  # under the assets root: the fetched library (hgen assets fetch --objects)
FIRST_IMPORTED_TYPE_ID = 100  # imported models' type_ids start here (the family's own files use 0-99)


class ModelFolderError(ValueError):
    """A model folder that cannot be read."""


class SourceInfo(_Strict):
    file: str
    sha256: str
    format: str
    package: str | None = None  # where the library's models came from (pip package==version)
    licence: str | None = None


class JointFile(_Strict):
    name: str
    kind: Literal["slide", "hinge"]
    axis: Vec3
    range: tuple[float, float]
    damping: float = Field(default=1.0, ge=0.0)
    frictionloss: float = Field(default=0.05, ge=0.0)


class LinkFile(_Strict):
    name: str
    parent: str | None = None
    pos: Vec3 = (0.0, 0.0, 0.0)  # the link's frame in its parent's (the root: the object frame)
    quat: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)
    joint: JointFile | None = None
    mass: float = Field(gt=0.0)
    collision_parts: int = Field(ge=1)
    textured: bool = False


# The import rules a model was written under. Bump it when a change to the importer (sizing, squaring a box to the
# axes, transfer) changes what an import writes from the same file: `hgen assets fetch --objects` imports again any
# library model written under other rules (0: written before the rules were numbered) instead of keeping it.
IMPORT_RULES = 3  # 3: a lid's front edge and outer face found on its surface, not from its bounds


class ImportedModelFile(_Strict):
    format_version: Literal[1] = 1
    import_rules: int = 0
    family: str
    name: str = Field(pattern=r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")
    type_id: int = Field(ge=FIRST_IMPORTED_TYPE_ID)
    description: str
    source: SourceInfo
    scale: float = Field(gt=0.0)
    # the part of `scale` that brought the model into its family's size range (sizing.py); None: not fitted
    fitted: float | None = Field(default=None, gt=0.0)
    up: str
    material: str
    rgba: tuple[float, float, float, float]
    links: list[LinkFile] = Field(min_length=1)
    articulation: Articulation | None = None


@dataclass(frozen=True)
class ImportedModel:
    """A model folder read back: its file, its folder and its annotations (overrides applied)."""

    info: ImportedModelFile
    folder: Path
    annotations: ObjectAnnotations

    def meshes(self) -> dict[str, np.ndarray]:
        return _meshes(self.folder / MESH_FILE, (self.folder / MESH_FILE).stat().st_mtime_ns)


@lru_cache(maxsize=64)
def _meshes(path: Path, _mtime: int) -> dict[str, np.ndarray]:
    with np.load(path) as z:
        return {k: z[k] for k in z.files}


def save_model_file(info: ImportedModelFile, folder: Path) -> None:
    (folder / MODEL_FILE).write_text(yaml.safe_dump(info.model_dump(mode="json"), sort_keys=False))


def read_model(folder: Path) -> ImportedModel:
    path = folder / MODEL_FILE
    try:
        info = ImportedModelFile.model_validate(yaml.safe_load(path.read_text()))
    except ValidationError as exc:
        raise ModelFolderError(f"{path}: {validation_details(exc)}") from None
    except (OSError, yaml.YAMLError) as exc:
        raise ModelFolderError(f"{path}: cannot be read: {' '.join(str(exc).split())}") from None
    ann = load_annotations(folder / ANNOTATION_FILE)
    override = folder / OVERRIDE_FILE
    if override.is_file():
        ann = apply_override(ann, override)
    return ImportedModel(info, folder, ann)


class Override(_Strict):
    """The hand-fixed positions of points whose transfer was unsure (object frame, or the point's part's)."""

    points: dict[str, Vec3] = Field(default_factory=dict)
    widths: dict[str, float] = Field(default_factory=dict)


def apply_override(ann: ObjectAnnotations, path: Path) -> ObjectAnnotations:
    try:
        ov = Override.model_validate(yaml.safe_load(path.read_text()) or {})
    except ValidationError as exc:
        raise ModelFolderError(f"{path}: {validation_details(exc)}") from None
    names = {p.name for p in ann.points}
    unknown = sorted(set(ov.points) - names)
    if unknown:
        raise ModelFolderError(f"{path}: points {unknown} are not annotated (known: {sorted(names)})")
    points = [p.model_copy(update={"position": ov.points[p.name]}) if p.name in ov.points else p for p in ann.points]
    ops = [o.model_copy(update={"width": ov.widths[o.point]}) if o.point in ov.widths else o for o in ann.operations]
    return ann.model_copy(update={"points": points, "operations": ops})


def search_folders() -> tuple[Path, ...]:
    """Where model folders are looked for: $HGEN_FAMILIES_PATH's folders, then the fetched library."""
    from humanoidgen.objects.family_data import search_path

    folders = list(search_path()[1:])
    lib = library_dir()
    if lib is not None:
        folders.append(lib)
    return tuple(folders)


def library_dir() -> Path | None:
    """The fetched library's folder under the assets root, if there is one."""
    from humanoidgen.assets.robot_files import AssetsError, resolve_assets_root

    try:
        path = resolve_assets_root() / LIBRARY_DIR
    except AssetsError:
        return None
    return path if path.is_dir() else None


def imported_models(family: str) -> list[ImportedModel]:
    """Every imported model of `family`, by type_id; a type_id or name twice is an error naming both."""
    stamps = []
    for folder in search_folders():
        fam = folder / family
        if fam.is_dir():
            for sub in sorted(fam.iterdir()):
                f = sub / MODEL_FILE
                if f.is_file():
                    stamps.append((sub, f.stat().st_mtime_ns, _stamp(sub / OVERRIDE_FILE)))
    return _models(tuple(stamps))


def _stamp(path: Path) -> int:
    return path.stat().st_mtime_ns if path.is_file() else 0


@lru_cache(maxsize=32)
def _models(stamps: tuple) -> list[ImportedModel]:
    out: dict[int, ImportedModel] = {}
    names: dict[str, Path] = {}
    for folder, _, _ in stamps:
        m = read_model(folder)
        if m.info.type_id in out:
            raise ModelFolderError(f"{folder}: type_id {m.info.type_id} is already {out[m.info.type_id].folder}")
        if m.info.name in names:
            raise ModelFolderError(f"{folder}: name {m.info.name!r} is already {names[m.info.name]}")
        out[m.info.type_id] = m
        names[m.info.name] = folder
    return [out[k] for k in sorted(out)]


def next_type_id(family: str, taken: set[int] = frozenset()) -> int:
    used = {m.info.type_id for m in imported_models(family)} | set(taken)
    return max(used | {FIRST_IMPORTED_TYPE_ID - 1}) + 1


def models_root(out: Path | None) -> Path:
    """Where an import writes: --out, else the first folder of $HGEN_FAMILIES_PATH."""
    if out is not None:
        return Path(out).expanduser()
    from humanoidgen.objects.family_data import ENV_FAMILIES_PATH

    first = [p for p in os.environ.get(ENV_FAMILIES_PATH, "").split(os.pathsep) if p]
    if not first:
        raise ModelFolderError(f"no models folder: pass --out FOLDER or set ${ENV_FAMILIES_PATH}")
    return Path(first[0]).expanduser()
