"""The planner API reference that the prompts show and docs/guides/planner-api.md publishes (docs/hooks.py): one
text, generated from the public API only.

The verbs are the public methods of HumanoidMotionPlanner, with their signatures and docstrings from the code;
prompts/planner_api.yaml adds what each argument means (units), what the call returns and a short example, the
`action` values of generate_constraints, the plan's other names (Constraint, Const, get_point_in_env,
get_axis_in_env) and statements about what the calls accept, each with an example that tests/test_api_reference.py
runs. The hands' points and axes come with their descriptions (objects/hands.py). No internal module is named:
plan authors cannot open the package's files.
"""

from __future__ import annotations

import inspect
import typing
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import yaml

API_FILE = Path(__file__).resolve().parents[1] / "prompts" / "planner_api.yaml"


@dataclass(frozen=True)
class Entry:
    """One callable of the reference: its name as plans write it, signature, summary, arguments, return value
    and example."""

    name: str  # "planner.hand_grasp", "Constraint"
    signature: str
    summary: str
    args: dict[str, str]
    returns: str
    example: str


@cache
def data() -> dict:
    return yaml.safe_load(API_FILE.read_text(encoding="utf-8"))


def public_verbs() -> list[str]:
    """The planner's public methods (not its properties): what a plan can call on `planner`."""
    from humanoidgen.planning.planner import HumanoidMotionPlanner

    return [n for n, v in vars(HumanoidMotionPlanner).items() if not n.startswith("_") and inspect.isfunction(v)]


def parameters(fn: typing.Callable) -> list[str]:
    return [p for p in inspect.signature(inspect.unwrap(fn)).parameters if p != "self"]


def _param(p: inspect.Parameter) -> str:
    # Annotations are strings here (postponed evaluation); show them bare: `hand_name: str = 'all'`.
    text = p.name
    if p.annotation is not inspect.Parameter.empty:
        ann = p.annotation if isinstance(p.annotation, str) else inspect.formatannotation(p.annotation)
        text += f": {ann.replace('np.ndarray', 'array')}"
    if p.default is not inspect.Parameter.empty:
        text += f" = {p.default!r}" if p.annotation is not inspect.Parameter.empty else f"={p.default!r}"
    return text


def signature(fn: typing.Callable) -> str:
    params = [p for p in inspect.signature(inspect.unwrap(fn)).parameters.values() if p.name != "self"]
    return f"({', '.join(_param(p) for p in params)})"


def _summary(fn: typing.Callable) -> str:
    return " ".join((inspect.getdoc(fn) or "").split())


def verbs() -> list[Entry]:
    """The planner's verbs in the reference's order."""
    from humanoidgen.planning.planner import HumanoidMotionPlanner

    out = []
    for name, d in data()["verbs"].items():
        fn = getattr(HumanoidMotionPlanner, name)
        out.append(Entry(f"planner.{name}", signature(fn), _summary(fn), d["args"], d["returns"], d["example"]))
    return out


def functions() -> list[Entry]:
    """The plan's other callables (Constraint, Const, get_point_in_env, get_axis_in_env)."""
    namespace = _namespace()
    out = []
    for name, d in data()["functions"].items():
        fn = namespace[name]
        out.append(Entry(name, signature(fn), d.get("summary") or _summary(fn), d["args"], d["returns"], d["example"]))
    return out


def _namespace() -> dict:
    from humanoidgen.episodes.runner import step_namespace

    return step_namespace(None)  # type: ignore[arg-type]


def _entry(e: Entry) -> str:
    lines = [f"#### `{e.name}{e.signature}`", e.summary, ""]
    lines += [f"- `{k}`: {v}" for k, v in e.args.items()]
    lines.append(f"- returns: {e.returns}")
    lines.append(f"\nExample:\n```python\n{e.example.strip()}\n```")
    return "\n".join(lines)


def hands_section() -> str:
    from humanoidgen.objects.hands import HAND_AXIS_NAMES, HAND_POINT_NAMES, hand_description

    right = [n for n in HAND_POINT_NAMES + HAND_AXIS_NAMES if "right" in n]
    lines = ["### the hands' points and axes",
             "Given in the world at the hand's pose now (get_point_in_env / get_axis_in_env) and moving with the "
             "hand. Each exists for both hands: the names below are the right hand's; the left hand's say `left` "
             "instead of `right` (`pinch_point_base_left_hand`, `left_pinch_axis`).", ""]
    lines += [f"- `{n}`: {hand_description(n)}" for n in right]
    return "\n".join(lines)


def reference() -> str:
    """The whole reference (Markdown): the prompts' API section and the docs page's."""
    from humanoidgen.sim import layout

    d = data()
    out = ["### planner methods (call as `planner.<name>(...)`)", *(_entry(e) for e in verbs())]
    actions = [f"- {', '.join(f'`{a.strip()}`' for a in k.split(','))}: {v}" for k, v in d["actions"].items()]
    out.append("### `action` values of generate_constraints\n" + "\n".join(actions))
    out.append("### what the calls accept\n" + "\n".join(f"- {f['statement']}" for f in d["facts"]))
    out.append("### planner attributes\n" + "\n".join(f"- `{k}`: {v}" for k, v in d["attributes"].items()))
    out.append("### constraints and key points (for what the actions above do not cover)\n"
               f"`end_effector_frame` is {layout.HAND_BASE_FRAME['left']!r} for the left hand, "
               f"{layout.HAND_BASE_FRAME['right']!r} for the right.")
    out += [_entry(e) for e in functions()]
    out.append(hands_section())
    out.append("A planner call that cannot do its job raises an error naming the call and the reason; the "
               "program stops at that step.")
    return "\n\n".join(out)


def facts() -> list[dict]:
    """The statements about what the calls accept, each with its task, aliases and example."""
    return list(data()["facts"])
