"""Evaluation: success rate and token cost of script generation per task, over several trials."""

from __future__ import annotations

import contextlib
from dataclasses import asdict, dataclass
from typing import Any

from humanoidgen.generation.script_gen import ScriptResult, generate_script
from humanoidgen.generation.worker import setup
from humanoidgen.llm import LLMClient
from humanoidgen.sandbox import SandboxWorker


@dataclass
class EvalRow:
    task: str
    trials: int
    successes: int
    success_rate: float
    mean_tokens: float  # total tokens per trial (all its attempts)
    tokens_per_success: float | None  # all tokens spent on the task / successes (None: no success)
    mean_attempts: float

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def evaluate(tasks: list[str], trials: int, client: LLMClient, attempts: int = 1,
             step_timeout_s: float = 120.0, results: list[ScriptResult] | None = None,
             worker: SandboxWorker | None = None, images: bool = False) -> list[EvalRow]:
    """Trial i of a task generates a plan for the scene of seed i (so trials differ even with a cache).
    One sandbox worker (`worker`, else a new one) serves every trial. `results`, if given, collects each
    trial's ScriptResult. `images`: prompts carry the scene's annotated picture (generate_script)."""
    rows = []
    with contextlib.nullcontext(worker) if worker is not None else SandboxWorker(setup) as worker:
        for task in tasks:
            runs = [generate_script(task, client, attempts=attempts, seed=i, worker=worker,
                                    step_timeout_s=step_timeout_s, images=images) for i in range(trials)]
            if results is not None:
                results.extend(runs)
            wins = sum(r.success for r in runs)
            spent = sum(r.tokens for r in runs)
            rows.append(EvalRow(runs[0].task if runs else task, trials, wins, wins / trials if trials else 0.0,
                                spent / trials if trials else 0.0, spent / wins if wins else None,
                                sum(len(r.attempts) for r in runs) / trials if trials else 0.0))
    return rows
