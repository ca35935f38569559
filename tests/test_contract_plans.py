"""Issue 35's contract corpus (bench/contract_plans/): plans written from the plan author's contract only (the
prompt, the paper, the task YAMLs, the annotations). Every plan loads and says what it exercises; the corpus's
own task specs load and the bench runs a task folder on its own spec.

Success is not asserted (bench/foreign_plans.py --corpus bench/contract_plans measures it), nor that the
checker accepts every plan: some plans probe the prompt's rules (imports, while, try, with, lambda)."""

from __future__ import annotations

from pathlib import Path

from humanoidgen.episodes.plans import load_plan
from humanoidgen.tasks.registry import load_task, task_names
from bench_scripts import load_bench

ROOT = Path(__file__).resolve().parents[1]
CONTRACT = ROOT / "bench" / "contract_plans"


def _bench():
    return load_bench("foreign_plans", "foreign_plans_bench_contract")


bench = _bench()


def test_a_corpus_task_spec_is_run_instead_of_a_builtin_name(tmp_path):
    (tmp_path / "tasks").mkdir()
    (tmp_path / "tasks" / "my_task.yaml").write_text("name: my_task\n")
    for task in ("my_task", "open_drawer"):
        (tmp_path / task).mkdir()
        (tmp_path / task / "a.py").write_text("# step: x\nplanner.open_hand('left')\n")
    plans = {p.task: p for p in bench.discover(tmp_path)}
    assert set(plans) == {"my_task", "open_drawer"}  # the specs folder is no task
    assert plans["my_task"].episode_task == str(tmp_path / "tasks" / "my_task.yaml")
    assert plans["open_drawer"].episode_task == "open_drawer"


def test_contract_corpus_size_and_coverage():
    plans = bench.discover(CONTRACT)
    assert len(plans) >= 30
    own = sorted(p.stem for p in (CONTRACT / "tasks").glob("*.yaml"))
    assert len(own) >= 3
    tasks = {p.task for p in plans}
    assert set(task_names()) <= tasks, f"built-in tasks without a contract plan: {set(task_names()) - tasks}"
    assert tasks <= set(task_names()) | set(own), "a task folder with neither a built-in task nor its own spec"


def test_contract_task_specs_load_with_data_predicates():
    for path in sorted((CONTRACT / "tasks").glob("*.yaml")):
        spec = load_task(path)
        assert spec.name == path.stem
        assert spec.success, f"{path.name}: no success predicates"
        assert spec.plan is None  # plans live in the corpus, not beside the spec


def test_every_contract_plan_loads_and_says_what_it_exercises():
    for p in bench.discover(CONTRACT):
        assert load_plan(p.path).steps, p.key
        head = p.path.read_text().splitlines()[0]
        assert head.startswith("# ") and not head.lower().startswith("# step"), f"{p.key}: no header line"


def _entry(plan, seeds, ok, wall):
    return {"task": "t", "plan": plan, "seeds": seeds, "successes": len(ok), "succeeded_seeds": ok,
            "failures": [{"seed": s, "message": f"m{s}", "cause": "c"} for s in seeds if s not in ok],
            "mean_wall_s": wall}


def test_merge_adds_seeds_run_later_and_replaces_seeds_run_again():
    old = [_entry("a", [0, 1, 2], [0, 2], 10.0), _entry("b", [0], [], 1.0)]
    new = [_entry("a", [2, 3], [3], 20.0)]
    merged = {e["plan"]: e for e in bench.merge_entries(old, new, {"t/a": 0, "t/b": 1})}
    a = merged["a"]
    assert a["seeds"] == [0, 1, 2, 3] and a["succeeded_seeds"] == [0, 3] and a["successes"] == 2
    assert [f["seed"] for f in a["failures"]] == [1, 2]  # seed 2 failed in the newer run
    assert a["mean_wall_s"] == 15.0
    assert merged["b"] == old[1]  # a plan not run now is kept as it was
