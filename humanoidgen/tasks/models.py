"""A task on other models of its objects' families (`hgen run|collect|bench TASK --model FAMILY=MODEL` and
`--randomize-models`): the task's spec with those objects' type_ids set, or with each episode drawing its model
from the family's imported ones, written as a task file the episode commands run like any other. Also what an
episode's record says of its models, so that it runs (and renders) again exactly."""

from __future__ import annotations

import math
import re
from pathlib import Path

import yaml

from humanoidgen.objects import library, stand_ins
from humanoidgen.objects.imported.model_file import FIRST_IMPORTED_TYPE_ID as _FIRST_IMPORTED
from humanoidgen.tasks.contents import moved, storage_shift
from humanoidgen.tasks.registry import load_task, plan_path
from humanoidgen.tasks.spec import TaskSpec

_TARGET = re.compile(r"^([a-z_]+)(?:\[(\d+)\])?$")


class ModelChoiceError(ValueError):
    """A --model that names no family (or object) of the task or no model of that family."""


def parse_models(values: list[str]) -> dict[str, str]:
    """["cup=my_mug", "bottle[1]=ketchup"] -> {"cup": "my_mug", "bottle[1]": "ketchup"}."""
    out = {}
    for v in values:
        target, sep, model = v.partition("=")
        if not sep or not model or _TARGET.match(target) is None:
            raise ModelChoiceError(f"--model {v!r}: expected FAMILY=MODEL or FAMILY[K]=MODEL (a model name or "
                                   "type_id; K: the K-th object of that family, from 0)")
        out[target] = model
    return out


def _refs(spec: TaskSpec) -> list[str]:
    """Each object's reference, in order: "cup[0]", "plate[0]", "cube[0]", "cube[1]"."""
    counts: dict[str, int] = {}
    out = []
    for o in spec.objects:
        counts[o.type] = counts.get(o.type, -1) + 1
        out.append(f"{o.type}[{counts[o.type]}]")
    return out


def with_models(spec: TaskSpec, models: dict[str, str], randomize: bool) -> TaskSpec:
    """`spec` with each object of a family (or each object) in `models` on that model; `randomize`: every other
    object of a family that has models to draw (`stand_ins.drawable_models`) draws one per episode."""
    refs = _refs(spec)
    types = {o.type for o in spec.objects}
    family_of = {t: _TARGET.match(t).group(1) for t in models}
    for target, model in models.items():
        if target not in types and target not in refs:
            what = "object" if "[" in target else "family"
            raise ModelChoiceError(f"--model {target}={model}: the task {spec.name} has no {what} {target} "
                                   f"(its objects: {', '.join(refs)})")
        try:
            library.model_named(family_of[target], model)
        except KeyError as exc:
            raise ModelChoiceError(str(exc).strip("'\"")) from None
    raw = spec.model_dump(mode="json", exclude_none=True)
    pinned = set()
    for o, ref in zip(raw["objects"], refs):
        choice = models.get(ref, models.get(o["type"]))
        if choice is not None:
            o["type_id"] = library.model_named(o["type"], choice).type_id
            pinned.add(ref)
    for o, authored in zip(raw["objects"], spec.objects):  # contents move with their container's storage point
        if authored.follow is not None:
            parent = spec.objects[authored.follow]
            shift = storage_shift(parent.type, parent.type_id, raw["objects"][authored.follow]["type_id"])
            if shift is not None:
                o["pos"] = list(moved(authored.pos, math.radians(parent.yaw_deg), shift))
    if randomize:  # the objects not pinned that have a model of about their size to draw
        free = [r for o, r in zip(spec.objects, refs)
                if r not in pinned and stand_ins.drawable_models(o.type, like=o.type_id)]
        # a family whose every object draws is named once; otherwise its free objects one by one
        whole = sorted(t for t in types if all(r in free for o, r in zip(spec.objects, refs) if o.type == t))
        raw["randomize_models"] = whole + [r for r in free if _TARGET.match(r).group(1) not in whole]
    return TaskSpec.model_validate(raw)


def task_with_models(task: str, models: list[str], randomize: bool, folder: Path) -> tuple[str, Path | None]:
    """The task file to run instead of `task` (unchanged when no model is chosen), and the reference plan."""
    if not models and not randomize:
        return task, None
    spec = load_task(task)
    derived = with_models(spec, parse_models(models), randomize)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{spec.name}.models.yaml"
    path.write_text(yaml.safe_dump(derived.model_dump(mode="json", exclude_none=True) | {"plan": None},
                                   sort_keys=False))
    return str(path), plan_path(spec)


def episode_models(spec: TaskSpec, seed: int | None) -> dict[str, dict] | None:
    """What an episode's record says of its models, when the task has imported ones (chosen or drawn; else
    None): for each object, its model's type_id and name (`--model REF=NAME` runs it on that model again) and,
    for an imported model, the sha256 of the files it was imported from."""
    layout = spec.sample_layout(seed)
    if not spec.randomize_models and all(r.type_id < _FIRST_IMPORTED for r in layout):
        return None
    out = {}
    for ref, r in zip(_refs(spec), layout):
        entry: dict = {"type_id": r.type_id, "model": str(r.type_id)}
        if r.type_id >= _FIRST_IMPORTED:
            info = next(i.info for i in library.family(r.type).imported() if i.info.type_id == r.type_id)
            entry.update(model=info.name, sha256=info.source.sha256)
        out[ref] = entry
    return out


def model_options(record_models: dict[str, dict]) -> list[str]:
    """The --model options that put an episode's objects on the models its record names."""
    return [f"{ref}={m['model']}" for ref, m in record_models.items()]
