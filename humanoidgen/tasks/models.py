"""A task on other models of its objects' families (`hgen run|collect TASK --model FAMILY=MODEL` and
`--randomize-models`): the task's spec with those objects' type_ids set, or with each episode drawing its model
from the family's imported ones, written as a task file the episode commands run like any other."""

from __future__ import annotations

from pathlib import Path

import yaml

from humanoidgen.objects import library
from humanoidgen.tasks.registry import load_task, plan_path
from humanoidgen.tasks.spec import TaskSpec


class ModelChoiceError(ValueError):
    """A --model that names no family of the task or no model of that family."""


def parse_models(values: list[str]) -> dict[str, str]:
    out = {}
    for v in values:
        family, sep, model = v.partition("=")
        if not sep or not family or not model:
            raise ModelChoiceError(f"--model {v!r}: expected FAMILY=MODEL (a model name or type_id)")
        out[family] = model
    return out


def with_models(spec: TaskSpec, models: dict[str, str], randomize: bool) -> TaskSpec:
    """`spec` with each object of a family in `models` on that model; `randomize`: every rigid family of the
    task that has imported models draws one per episode (except those pinned by `models`)."""
    types = {o.type for o in spec.objects}
    for family, model in models.items():
        if family not in types:
            raise ModelChoiceError(f"--model {family}={model}: the task {spec.name} has no {family} "
                                   f"(its objects: {', '.join(sorted(types))})")
        try:
            library.model_named(family, model)
        except KeyError as exc:
            raise ModelChoiceError(str(exc).strip("'\"")) from None
    raw = spec.model_dump(mode="json", exclude_none=True)
    for o in raw["objects"]:
        if o["type"] in models:
            o["type_id"] = library.model_named(o["type"], models[o["type"]]).type_id
    if randomize:
        raw["randomize_models"] = sorted(t for t in types - set(models)
                                         if any(m.type_id >= 100 for m in library.family(t).models()))
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
