"""Finding task specs: the built-in ones under `specs/` by name, or a user's YAML by path."""

from __future__ import annotations

import difflib
from pathlib import Path

import yaml
from pydantic import ValidationError

from humanoidgen.objects.schema import validation_details

from humanoidgen.tasks.spec import TaskSpec

SPECS_DIR = Path(__file__).parent / "specs"


class TaskSpecError(ValueError):
    """A task file that is not valid YAML or does not fit the schema; the message names file and field."""


def task_names() -> list[str]:
    return sorted(p.stem for p in SPECS_DIR.glob("*.yaml"))


def parse_task(raw: object, source: str = "<task>") -> TaskSpec:
    """Validate already-loaded YAML data; errors read `source: objects.1.type_id: ...`."""
    try:
        return TaskSpec.model_validate(raw)
    except ValidationError as exc:
        raise TaskSpecError(f"{source}: {validation_details(exc)}") from None


def load_task_file(path: Path) -> TaskSpec:
    path = Path(path)
    try:
        raw = yaml.safe_load(path.read_text())
    except yaml.YAMLError as exc:
        raise TaskSpecError(f"{path}: not valid YAML: {exc}") from None
    # A missing reference plan is no error: plans are written separately.
    return parse_task(raw, str(path))


def load_task(name_or_path: str | Path) -> TaskSpec:
    """A built-in task by name ("open_drawer") or a YAML file by path."""
    p = Path(name_or_path)
    if p.suffix in (".yaml", ".yml") or p.is_file():
        if not p.is_file():
            raise FileNotFoundError(f"no task file {p}")
        return load_task_file(p)
    name = str(name_or_path)
    names = task_names()
    if name not in names:
        close = difflib.get_close_matches(name, names, n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        raise KeyError(f"unknown task {name!r}.{hint} Valid tasks: {', '.join(names)}")
    return load_task_file(SPECS_DIR / f"{name}.yaml")


def list_tasks() -> list[TaskSpec]:
    return [load_task(n) for n in task_names()]


def plan_path(spec: TaskSpec) -> Path | None:
    """Where a built-in task's reference plan lives (it may not exist yet)."""
    return None if spec.plan is None else SPECS_DIR / spec.plan
