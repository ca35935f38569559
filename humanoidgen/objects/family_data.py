"""Loading the family data files: `families/<family>/family.yaml` and one file per model, plus extra folders.

Adding a model of an existing family is adding one YAML (or JSON) file to its folder. Besides the packaged
folder (humanoidgen/objects/families/), the folders in `$HGEN_FAMILIES_PATH` (separated like PATH) are read:
each holds `<family>/<model>.yaml` files that add models to the packaged families (a family's code and its
`family.yaml` stay in the package). Every file is validated when its family is first used; an error names the
file and the field in one line. Loads are cached per set of folders, so changing the variable takes effect on
the next use.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import yaml
from pydantic import BaseModel, ValidationError

from humanoidgen.objects.params import FamilyFile, ModelFile, Num
from humanoidgen.objects.schema import validation_details

FAMILIES_DIR = Path(__file__).parent / "families"
ENV_FAMILIES_PATH = "HGEN_FAMILIES_PATH"
FAMILY_FILE = "family.yaml"
MATERIALS_FILE = "materials.yaml"
_SUFFIXES = (".yaml", ".yml", ".json")


class FamilyDataError(ValueError):
    """A family data file that cannot be read or does not fit the schema."""


@dataclass(frozen=True)
class ModelData:
    """One validated model: `params` are complete (family defaults filled in), `own` are the file's own keys."""

    type_id: int
    description: str
    params: dict[str, Any]
    own: frozenset[str]
    path: Path


@dataclass(frozen=True)
class FamilyData:
    info: FamilyFile
    models: dict[int, ModelData]  # by type_id, ascending
    path: Path


def search_path() -> tuple[Path, ...]:
    """The packaged folder, then the extra folders of $HGEN_FAMILIES_PATH in order."""
    extra = [Path(p).expanduser() for p in os.environ.get(ENV_FAMILIES_PATH, "").split(os.pathsep) if p]
    return (FAMILIES_DIR, *extra)


def extra_model_folders() -> list[Path]:
    """The `<folder>/<family>` folders of $HGEN_FAMILIES_PATH that exist, for the packaged families: what a plan
    worker may read to build them (never the extra folder itself, which may be anything, a home folder)."""
    names = sorted(p.name for p in FAMILIES_DIR.iterdir() if p.is_dir())
    return [(folder / n).resolve() for folder in search_path()[1:] for n in names if (folder / n).is_dir()]


def family_data(name: str, params_model: type[ModelFile]) -> FamilyData:
    """The family's `family.yaml` and every model of it in the packaged and extra folders, validated."""
    return _load(name, params_model, search_path())


@cache
def family_file(name: str) -> FamilyFile:
    """A packaged family's validated `family.yaml`: its annotation vocabulary (points and axes with their
    descriptions, operations, functions, what its openness moves)."""
    path = FAMILIES_DIR / name / FAMILY_FILE
    if not path.is_file():
        raise FamilyDataError(f"{path}: missing; every family needs its {FAMILY_FILE}")
    return _validated(FamilyFile, _read(path), path)


def material(name: str) -> tuple[float, float, float]:
    """A material's (sliding, torsional, rolling) friction from families/materials.yaml."""
    table = materials()
    if name not in table:
        raise KeyError(f"unknown material {name!r}; known: {', '.join(sorted(table))}")
    return table[name]


@cache
def materials() -> dict[str, tuple[float, float, float]]:
    path = FAMILIES_DIR / MATERIALS_FILE
    raw = _read(path)
    if not isinstance(raw, dict):
        raise FamilyDataError(f"{path}: expected a mapping of material name to friction")
    return {str(k): _validated(_Friction, {"friction": v}, path, prefix=f"{k}.").friction for k, v in raw.items()}


class _Friction(BaseModel):
    friction: tuple[Num, Num, Num]


# -- loading ---------------------------------------------------------------------------------------------------
@cache
def _load(name: str, params_model: type[ModelFile], folders: tuple[Path, ...]) -> FamilyData:
    home = folders[0] / name
    info_path = home / FAMILY_FILE
    if not info_path.is_file():
        raise FamilyDataError(f"{info_path}: missing; every family needs its {FAMILY_FILE}")
    info = _validated(FamilyFile, _read(info_path), info_path)
    if info.family != name:
        raise FamilyDataError(f"{info_path}: family: {info.family!r} but the folder is {name!r}")
    _check_family(info, info_path, params_model)
    models: dict[int, ModelData] = {}
    for folder in folders:
        for path in _model_files(folder / name, packaged=folder == folders[0]):
            m = _model(path, info, params_model)
            if m.type_id in models:
                raise FamilyDataError(f"{path}: type_id: {m.type_id} is already {models[m.type_id].path}")
            models[m.type_id] = m
    if not models:
        raise FamilyDataError(f"{home}: family {name!r} has no model files")
    return FamilyData(info, dict(sorted(models.items())), info_path)


def _check_family(info: FamilyFile, path: Path, params_model: type[ModelFile]) -> None:
    """What a family.yaml gets wrong is reported against it, not against the first model file that uses it."""
    unknown = sorted(set(info.defaults) - set(params_model.model_fields))
    if unknown:
        raise FamilyDataError(f"{path}: defaults: {unknown} are not parameters of {info.family} "
                              f"(known: {sorted(params_model.model_fields)})")
    axes = {a.name for a in info.axes}
    refs = [(f"operations.{i}.{f}", getattr(o, f)) for i, o in enumerate(info.operations)
            for f in ("approach_axis", "attach_axis", "parallel_axis")]
    refs += [(f"functions.{i}.axis", f.axis) for i, f in enumerate(info.functions)]
    for where, axis in refs:
        if axis not in axes:
            raise FamilyDataError(f"{path}: {where}: no axis {axis!r} in axes (known: {sorted(axes)})")
    named = {p.name for p in info.points} | {o.point for o in info.operations} | {f.point for f in info.functions}
    for i, rule in enumerate(info.usable):
        for point in filter(None, (rule.point, rule.from_point)):
            if point not in named:
                raise FamilyDataError(f"{path}: usable.{i}: no point {point!r} in the family's points "
                                      f"(known: {sorted(named)})")


def _model_files(folder: Path, packaged: bool) -> list[Path]:
    if not folder.is_dir():
        return []
    files = sorted(p for p in folder.iterdir() if p.suffix in _SUFFIXES and p.is_file())
    if not packaged and any(p.name == FAMILY_FILE for p in files):
        # An extra folder adds models; a family's shared data and code live in the package.
        raise FamilyDataError(f"{folder / FAMILY_FILE}: extra family folders hold model files only")
    return [p for p in files if p.name != FAMILY_FILE]


def _model(path: Path, info: FamilyFile, params_model: type[ModelFile]) -> ModelData:
    raw = _read(path)
    if not isinstance(raw, dict):
        raise FamilyDataError(f"{path}: expected a mapping of field to value, got {type(raw).__name__}")
    # A model's value replaces the family default for that key (a nested mapping as a whole).
    parsed = _validated(params_model, {**info.defaults, **raw}, path)
    if isinstance(getattr(parsed, "material", None), str):
        _check_material(path, parsed.material)
    params = parsed.model_dump(exclude={"type_id", "description"})
    return ModelData(parsed.type_id, parsed.description, params,
                     frozenset(raw) - {"type_id", "description"}, path)


def _check_material(path: Path, name: str) -> None:
    if name not in materials():
        raise FamilyDataError(f"{path}: material: unknown material {name!r}; known: {', '.join(sorted(materials()))}")


def _read(path: Path) -> Any:
    try:
        return yaml.safe_load(path.read_text())  # JSON is YAML too
    except yaml.YAMLError as exc:
        raise FamilyDataError(f"{path}: not valid YAML/JSON: {' '.join(str(exc).split())}") from None
    except OSError as exc:
        raise FamilyDataError(f"{path}: cannot be read: {exc.strerror}") from None


def _validated(model: type[BaseModel], raw: Any, path: Path, prefix: str = "") -> Any:
    try:
        return model.model_validate(raw)
    except ValidationError as exc:
        raise FamilyDataError(f"{path}: {prefix}{validation_details(exc)}") from None
