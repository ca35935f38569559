"""Scene generation: an LLM writes a task spec (YAML); we validate it (schema, assets, reach, overlaps,
stability) and send the problems back for a bounded number of repairs."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from humanoidgen.generation import prompts
from humanoidgen.generation.extract import ExtractError, extract_yaml
from humanoidgen.generation.scene_image import SPEC_CAPTION
from humanoidgen.llm import LLMClient
from humanoidgen.llm.images import pngs, sha256, text_of, with_image
from humanoidgen.tasks.registry import TaskSpecError, parse_task
from humanoidgen.tasks.spec import TaskSpec

MAX_MOVE_M = 0.01  # an object that moves more than this while the scene settles is unstable
SETTLE_CHECK_S = 1.0  # simulated seconds the stability check runs after placing the objects
RANGE_TOL_M = 0.01


class SceneGenerationError(RuntimeError):
    """No valid spec within the repair budget; `log` holds every turn."""

    def __init__(self, message: str, log: list[dict]) -> None:
        super().__init__(message)
        self.log = log


def validate_spec(text: str) -> tuple[TaskSpec | None, list[str]]:
    """Parse and check a YAML spec; returns (spec, []) or (None or spec, problems). Cheap checks run first,
    the simulation only when they pass."""
    try:
        raw = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        return None, [f"not valid YAML: {exc}"]
    if isinstance(raw, dict):
        raw.pop("plan", None)  # a generated task has no reference plan file next to it
    try:
        spec = parse_task(raw, "spec")
    except TaskSpecError as exc:
        return None, [str(exc)]
    problems = _overlaps(spec)
    try:
        spec.sample_layout(0)
    except ValueError as exc:
        problems.append(f"randomization: {exc}")
    if problems:
        return spec, problems
    return spec, _simulate(spec)


def _label(spec: TaskSpec, i: int) -> str:
    o = spec.objects[i]
    n = sum(1 for p in spec.objects[:i] if p.type == o.type)
    return f"objects.{i} ({o.type}[{n}] at {list(o.pos)})"


def _overlaps(spec: TaskSpec) -> list[str]:
    from humanoidgen.tasks.scene import overlapping_pairs

    pairs = overlapping_pairs(spec.default_layout(), skip=spec._follow_pairs())
    return [f"{_label(spec, i)} and {_label(spec, j)}: footprints overlap on the table; move them apart"
            for i, j in pairs]


def _simulate(spec: TaskSpec) -> list[str]:
    """Build the scene, check each object is within a hand's reach and that nothing moves while it settles."""
    from humanoidgen.objects.queries import get_point_in_env
    from humanoidgen.sim.layout import OPERABLE_RANGE
    from humanoidgen.tasks.scene import build_layout

    problems: list[str] = []
    try:
        scene, env = build_layout(spec.default_layout(), settle_s=0.0)
    except Exception as exc:  # noqa: BLE001 - a spec that cannot be built is reported to the LLM
        return [f"the scene could not be built: {type(exc).__name__}: {exc}"]
    for i, obj in enumerate(scene.objects):
        ann = obj.annotations
        names = ["center"] + sorted({op.point for op in ann.operations} if ann else set())
        pts = [get_point_in_env(env, n, obj.type_name, obj.obj_id) for n in names]
        if not any(r.contains(p, RANGE_TOL_M) for p in pts for r in OPERABLE_RANGE.values()):
            where = "its centre" if len(names) == 1 else "none of its operation points"
            problems.append(f"{_label(spec, i)}: {where} is within either hand's operable range")
    start = {o.body: env.object_pose(o.body)[0] for o in scene.objects}
    action = env.init_action()
    for _ in range(round(SETTLE_CHECK_S * env.control_hz)):
        env.step(action)
    for i, obj in enumerate(scene.objects):
        moved = float(np.linalg.norm(env.object_pose(obj.body)[0] - start[obj.body]))
        if moved > MAX_MOVE_M:
            problems.append(f"{_label(spec, i)}: unstable, moved {moved * 100:.1f} cm while the scene settled "
                            f"(max {MAX_MOVE_M * 100:.0f} cm); it may rest on or inside another object")
    return problems


def spec_yaml(spec: TaskSpec) -> str:
    # Not exclude_defaults: it would drop the predicates' `type` discriminators.
    data = spec.model_dump(mode="json", exclude_none=True)
    return yaml.safe_dump(data, sort_keys=False, default_flow_style=None, width=110)


def generate_scene(description: str, client: LLMClient, max_repairs: int = 2,
                   out: Path | None = None, images: bool = False) -> tuple[TaskSpec, list[dict[str, Any]]]:
    """Ask for a spec, validate it, repair up to `max_repairs` times; write it to `out` when given.
    Raises SceneGenerationError (with the log) when no turn produced a valid spec. `images`: a repair prompt
    carries the annotated picture of the scene the last spec builds, when it builds (the first prompt has no
    scene to show)."""
    messages = [{"role": "user", "content": prompts.scene_prompt(description)}]
    log: list[dict[str, Any]] = []
    for turn in range(max_repairs + 1):
        t0 = time.perf_counter()
        result = client.chat(messages)
        try:
            text = extract_yaml(result.text)
            spec, problems = validate_spec(text)
        except ExtractError as exc:
            text, spec, problems = "", None, [str(exc)]
        sent = pngs(messages[-1:])
        log.append({"turn": turn, "prompt": text_of(messages[-1]["content"]), "response": result.text,
                    "reasoning": result.reasoning, "yaml": text, "problems": problems,
                    "tokens": _tokens(result), "seconds": round(time.perf_counter() - t0, 3),
                    "cached": result.cached, "image": sha256(sent[0]) if sent else None})
        if spec is not None and not problems:
            if out is not None:
                Path(out).parent.mkdir(parents=True, exist_ok=True)
                Path(out).write_text(spec_yaml(spec))
            return spec, log
        png = _picture(spec) if images and spec is not None and turn < max_repairs else None
        messages += [{"role": "assistant", "content": result.text},
                     {"role": "user", "content": with_image(prompts.scene_repair_prompt(problems), png, SPEC_CAPTION)}]
    raise SceneGenerationError(f"no valid task spec after {max_repairs} repair(s); last problems: "
                               f"{'; '.join(log[-1]['problems'])}", log)


def _picture(spec: TaskSpec) -> bytes | None:
    """The spec's scene as a picture, or None when it cannot be built (its problems say why)."""
    from humanoidgen.generation.scene_image import scene_png

    try:
        return scene_png(spec, None)
    except Exception:  # noqa: BLE001 - an LLM's spec may fail to build in many ways; the repair text reports it
        return None


def _tokens(result: Any) -> dict[str, Any]:
    u = result.usage
    return {"prompt": u.prompt, "completion": u.completion, "reasoning": u.reasoning, "total": u.total}
