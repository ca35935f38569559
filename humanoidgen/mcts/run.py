"""Entry points: search a plan for one task (`search_plan`) and evaluate MCTS over tasks and trials
(`evaluate_mcts`: success rate, tokens per run and per success, distinct successful plans)."""

from __future__ import annotations

import contextlib
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from humanoidgen.llm import LLMClient
from humanoidgen.mcts.executor import Executor, SandboxExecutor
from humanoidgen.mcts.search import MCTS, MCTSConfig, MCTSResult, write_outputs
from humanoidgen.mcts.stcr import normalize_code
from humanoidgen.mcts.tree import Tree
from humanoidgen.tasks.spec import TaskSpec


def _spec_data(task: TaskSpec | str | Path) -> dict:
    from humanoidgen.tasks.registry import load_task

    spec = task if isinstance(task, TaskSpec) else load_task(task)
    return spec.model_dump(mode="json")


@contextlib.contextmanager
def sandbox_executors(workers: int, step_timeout_s: float = 120.0):
    """K sandbox-backed executors (one worker process each), closed on exit."""
    exs = [SandboxExecutor(step_timeout_s=step_timeout_s) for _ in range(max(1, workers))]
    try:
        yield exs
    finally:
        for ex in exs:
            ex.close()


def search_plan(task: TaskSpec | str | Path, client: LLMClient, expansions: int = 8, workers: int = 1,
                seed: int | None = None, executors: list[Executor] | None = None, tree: Tree | Path | None = None,
                out: Path | None = None, log_path: Path | None = None, picture: Path | None = None,
                step_timeout_s: float = 120.0, **config: Any) -> MCTSResult:
    """Search a plan for `task` with at most `expansions` LLM expansions (`workers` at once).

    `executors`: reuse these (e.g. SandboxExecutor(worker)); by default `workers` sandbox executors are started
    and closed here. `tree`: a tree (or a saved tree log) to continue; its task and seed are used.
    `out` receives the plan; the tree log and picture go next to it (or to `log_path` / `picture`).
    `config`: further MCTSConfig fields (gamma, minimal_guidance, short_description, verify)."""
    if isinstance(tree, (str, Path)):
        tree = Tree.load(Path(tree))
    if tree is not None:
        spec_data, seed = tree.meta["spec"], tree.meta["seed"]
    else:
        spec_data = _spec_data(task)
    cfg = MCTSConfig(expansions=expansions, **config)
    with (contextlib.nullcontext(executors) if executors is not None
          else sandbox_executors(workers, step_timeout_s)) as exs:
        result = MCTS(spec_data, client, exs, seed, cfg, tree).run()
    write_outputs(result, out, log_path, picture)
    return result


@dataclass
class MCTSEvalRow:
    task: str
    trials: int
    successes: int
    success_rate: float
    tokens_per_run: float
    tokens_per_success: float | None  # all tokens spent on the task / successes (None: no success)
    distinct_plans: int  # distinct successful plans (by normalized code)
    verified: int  # successful plans that re-ran to success from a fresh reset

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def plan_key(plan: list[tuple[str, str]]) -> str:
    return "\n".join(normalize_code(c) for _, c in plan)


def evaluate_mcts(tasks: list[str], trials: int, client: LLMClient, expansions: int = 8, workers: int = 1,
                  executors: list[Executor] | None = None, results: list[MCTSResult] | None = None,
                  step_timeout_s: float = 120.0, **config: Any) -> list[MCTSEvalRow]:
    """Trial i of a task searches on the scene of seed i; the executors serve every trial."""
    rows = []
    with (contextlib.nullcontext(executors) if executors is not None
          else sandbox_executors(workers, step_timeout_s)) as exs:
        for task in tasks:
            runs = [search_plan(task, client, expansions, seed=i, executors=exs, **config) for i in range(trials)]
            if results is not None:
                results.extend(runs)
            wins = [r for r in runs if r.success]
            spent = sum(r.tokens for r in runs)
            rows.append(MCTSEvalRow(runs[0].task if runs else str(task), trials, len(wins),
                                    len(wins) / trials if trials else 0.0, spent / trials if trials else 0.0,
                                    spent / len(wins) if wins else None, len({plan_key(r.plan) for r in wins}),
                                    sum(bool(r.verified) for r in wins)))
    return rows
