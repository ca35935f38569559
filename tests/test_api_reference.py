"""The planner API reference (generation/api_reference.py + prompts/planner_api.yaml) is complete and true: every
public verb and argument has an entry, nothing internal is named, the examples pass the checker, and each
statement about what the calls accept is run on a task's scene."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import builtins  # noqa: E402
import re  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402

import humanoidgen  # noqa: E402
from humanoidgen.episodes.runner import step_namespace  # noqa: E402
from humanoidgen.generation import api_reference as api  # noqa: E402
from humanoidgen.generation import context, prompts  # noqa: E402
from humanoidgen.generation.extract import extract_steps  # noqa: E402
from humanoidgen.generation.script_gen import precheck, step_names  # noqa: E402
from humanoidgen.mcts.prompt import expansion_prompt  # noqa: E402
from humanoidgen.mcts.tree import Tree  # noqa: E402
from humanoidgen.objects import library  # noqa: E402
from humanoidgen.objects.describe import describe_scene  # noqa: E402
from humanoidgen.planning.constraint_gen import ACTIONS, PUSH_ACTIONS  # noqa: E402
from humanoidgen.planning.skills import PULL_ACTIONS  # noqa: E402
from humanoidgen.planning.planner import HumanoidMotionPlanner  # noqa: E402
from humanoidgen.tasks.registry import load_task, parse_task  # noqa: E402
from humanoidgen.tasks.spec import TaskSpec  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402
from humanoidgen.tasks.targets import PushSpec  # noqa: E402

PACKAGE = Path(humanoidgen.__file__).resolve().parent
REPO = PACKAGE.parent
NAMES = step_names()


# -- complete -------------------------------------------------------------------------------------------------
def test_every_public_verb_has_an_entry_and_every_entry_a_verb() -> None:
    assert list(api.data()["verbs"]) and set(api.data()["verbs"]) == set(api.public_verbs())


@pytest.mark.parametrize("entry", api.verbs() + api.functions(), ids=lambda e: e.name)
def test_each_entry_documents_exactly_the_arguments_of_its_signature(entry: api.Entry) -> None:
    fn = getattr(HumanoidMotionPlanner, entry.name.removeprefix("planner.")) if entry.name.startswith("planner.") \
        else step_namespace(None)[entry.name]  # type: ignore[arg-type]
    assert list(entry.args) == api.parameters(fn), entry.name
    assert entry.summary and entry.returns and entry.example.strip()
    assert all(v.strip() for v in entry.args.values())


def test_the_actions_documented_are_the_actions_accepted() -> None:
    documented = {a.strip() for k in api.data()["actions"] for a in k.split(",")}
    assert documented == set(ACTIONS + PUSH_ACTIONS + PULL_ACTIONS)


def test_the_documented_attributes_exist() -> None:
    scene, env = build_scene(load_task("block_stack_single"), 0)
    planner = HumanoidMotionPlanner(env, targets=scene.targets)
    ns = step_namespace(planner)
    for name in api.data()["attributes"]:
        eval(name, {"__builtins__": {}}, ns)  # noqa: S307 - our own data: `planner.env` and the like


def test_the_push_fields_in_the_scene_prompt_are_the_push_target_fields() -> None:
    assert set(context.PUSH_FIELDS) == set(PushSpec.model_fields)
    assert "see tasks/targets.py" not in prompts.scene_prompt("open the box")


@pytest.mark.parametrize("example", [e.example for e in api.verbs() + api.functions()]
                         + [f["example"] for f in api.facts()])
def test_every_example_passes_the_plan_checker(example: str) -> None:
    assert precheck(extract_steps(f"```python\n{example}\n```"), NAMES) == []


# -- nothing internal --------------------------------------------------------------------------------------------
def _internal_names() -> set[str]:
    """Module and package names of the package that a plan author cannot use: what the prompts must not name."""
    specs = PACKAGE / "tasks" / "specs"  # task plans: data, named by their task
    modules = {p.stem for p in PACKAGE.rglob("*.py") if p.stem != "__init__" and specs not in p.parents}
    modules |= {p.name for p in PACKAGE.rglob("*") if p.is_dir() and not p.name.startswith("__")}
    # Words that are also public: names plans use, arguments, builtins (the rules list refused ones), the fields of
    # a task specification and of the scene description, family names.
    public = set(NAMES) | set(api.public_verbs()) | set(dir(builtins)) | set(TaskSpec.model_fields)
    public |= {a for e in api.verbs() + api.functions() for a in e.args} | {"planner", "move", "pour"}
    public |= {"targets", "points", "axes", "operations", "functions", "aliases"} | set(library.families())
    return modules - public


def _folders() -> set[str]:
    """Folder names of the repository: a path through one of them is a file an LLM cannot open."""
    return {p.name for p in REPO.iterdir() if p.is_dir() and not p.name.startswith(".")} | \
        {p.name for p in PACKAGE.iterdir() if p.is_dir() and not p.name.startswith("__")}


def _problems(text: str) -> list[str]:
    internal, folders = _internal_names(), _folders()
    named = [m for m in sorted(internal) if re.search(rf"`{re.escape(m)}`|\b{re.escape(m)}\.py\b", text)
             or ("_" in m and re.search(rf"\b{m}\b", text))]  # an underscored name is never prose
    out = [f"names the module `{m}`" for m in named]
    out += [f"names the file {m.group()}" for m in re.finditer(r"\b[\w./-]+\.(?:py|ya?ml|md|json)\b", text)]
    out += [f"names the path {m.group()}" for m in re.finditer(r"\b(\w+)/[\w/.-]+", text) if m.group(1) in folders]
    out += [f"names the package path {m.group()}" for m in re.finditer(r"humanoidgen\.\w+", text)]
    return out


def _script_prompt(task: str) -> str:
    scene, env = build_scene(load_task(task), 0)
    planner = HumanoidMotionPlanner(env, targets=scene.targets)
    hands = {s: {"p": p.p.round(3).tolist(), "q": p.q.round(3).tolist()}
             for s, p in (("left", planner.left_hand_init_pose), ("right", planner.right_hand_init_pose))}
    return prompts.script_prompt(load_task(task).description, describe_scene(env, as_json=False), hands, NAMES)


def test_the_known_offenders_are_seen() -> None:
    assert _problems("set down as `placing` says (`move_action`), push_actions, see tasks/targets.py")
    assert not _problems("a `from humanoidgen... import *` line is ignored; target1/target2; grasp / pinch")


@pytest.mark.parametrize("which", ["reference", "scene", "script", "mcts"])
def test_no_prompt_names_an_internal_module_or_a_file(which: str) -> None:
    if which == "reference":
        text = api.reference()
    elif which == "scene":
        text = prompts.scene_prompt("open the safe's door")
    elif which == "script":
        text = _script_prompt("open_safe_door")
    else:
        scene, env = build_scene(load_task("block_stack_single"), 0)
        meta = {"task": "block_stack_single", "description": "stack", "scene": describe_scene(env, as_json=False),
                "hands": {"right": {"p": [0, 0, 0], "q": [1, 0, 0, 0]}}}
        tree = Tree(meta=meta)
        text = expansion_prompt(tree, tree.add(None, None, None), NAMES)
    assert _problems(text) == []
    assert not re.search(r"\b(placing|move_action|push_actions|constraint_gen)\b", text)


# -- the statements, run --------------------------------------------------------------------------------------------
def _scene_for(fact: dict, seed: int):
    spec = load_task(fact["task"]).model_dump(mode="json", exclude_none=True)
    spec.pop("plan", None)
    for alias, ref in (fact.get("aliases") or {}).items():
        type_name, k = ref.rstrip("]").split("[")
        index = [j for j, o in enumerate(spec["objects"]) if o["type"] == type_name][int(k)]
        spec["objects"][index].setdefault("aliases", []).append(alias)
    return build_scene(parse_task(spec, "<fact>"), seed)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("k", range(len(api.facts())))
def test_each_statement_holds_where_its_example_runs(k: int, seed: int) -> None:
    fact = api.facts()[k]
    scene, env = _scene_for(fact, seed)
    planner = HumanoidMotionPlanner(env, seed=seed, targets=scene.targets)
    exec(fact["example"], step_namespace(planner))  # noqa: S102 - our own data; its asserts are the statement


def test_path_constraints_of_both_hands_go_each_to_its_own_hand(monkeypatch) -> None:
    """The statement on hand_name="all" also says how the flat list is split: each hand plans with its own."""
    from humanoidgen.planning import arm_moves

    seen: dict[str, list[str]] = {}
    plan_side = arm_moves.plan_side

    def spy(ctx, side, target, path_constraints=()):
        seen[side] = [c.side for c in path_constraints]
        return plan_side(ctx, side, target, path_constraints)

    monkeypatch.setattr(arm_moves, "plan_side", spy)
    (fact,) = [f for f in api.facts() if 'hand_name="all"' in f["statement"]]
    scene, env = _scene_for(fact, 0)
    exec(fact["example"], step_namespace(HumanoidMotionPlanner(env, targets=scene.targets)))  # noqa: S102
    assert seen == {"left": ["left"], "right": ["right"]}
