"""Prompt templates (files under `humanoidgen/prompts/`) and filling their `{{PLACEHOLDER}}`s from live data."""

from __future__ import annotations

import re
from pathlib import Path

from humanoidgen.generation import context
from humanoidgen.sandbox import language

PROMPTS_DIR = Path(__file__).resolve().parents[1] / "prompts"
_PLACEHOLDER = re.compile(r"\{\{([A-Z_]+)\}\}")


class TemplateError(KeyError):
    pass


def render(template: str, **values: str) -> str:
    """Fill `{{NAME}}` placeholders; a missing or unused value is an error (a template/code mismatch)."""
    names = set(_PLACEHOLDER.findall(template))
    missing, unused = names - set(values), set(values) - names
    if missing or unused:
        raise TemplateError(f"template placeholders missing: {sorted(missing)}, unused values: {sorted(unused)}")
    # One pass, so a value that happens to contain "{{X}}" is never expanded.
    return _PLACEHOLDER.sub(lambda m: values[m.group(1)], template)


def load(name: str) -> str:
    return (PROMPTS_DIR / name).read_text(encoding="utf-8")


def scene_prompt(description: str) -> str:
    example = "\n".join(ln for ln in context.example_spec_yaml().splitlines() if not ln.startswith("plan:"))
    return render(load("scene.md"), LAYOUT=context.layout_text(), ASSETS=context.assets_text(),
                  VOCABULARY=context.vocabulary_text(), PREDICATES=context.predicates_text(),
                  PUSH_FIELDS=context.push_fields_text(), EXAMPLE=example, DESCRIPTION=description.strip())


def scene_repair_prompt(errors: list[str]) -> str:
    return render(load("scene_repair.md"), ERRORS="\n".join(f"- {e}" for e in errors))


def script_prompt(description: str, scene: dict, hands: dict, names: list[str]) -> str:
    """`scene` is describe_scene(env, as_json=False); `hands` maps side -> {p, q} of the end effectors."""
    ex_task, ex_plan = context.example_plan()
    return render(load("script.md"), LAYOUT=context.layout_text(),
                  ATTRIBUTES=context.compact_json(scene["attributes"]), VOCABULARY=scene_vocabulary(scene),
                  STATUS=context.compact_json(scene["status"]), HANDS=context.hands_text(hands),
                  NAMES=", ".join(f"`{n}`" for n in names), API=context.api_reference(),
                  LANGUAGE=language.rules_text("script"), EXAMPLE_TASK=ex_task, EXAMPLE=ex_plan,
                  DESCRIPTION=description.strip())


def scene_vocabulary(scene: dict, leave_out: tuple[str, ...] = ()) -> str:
    """What the points, axes and openness of the scene's objects mean (`scene` as describe_scene gives it), but
    for the types in `leave_out`."""
    return context.vocabulary_text([(a["type"], a["type_id"]) for a in scene["attributes"]
                                    if a["type"] not in leave_out])


def script_retry_prompt(failure: str) -> str:
    return render(load("script_retry.md"), FAILURE=failure)
