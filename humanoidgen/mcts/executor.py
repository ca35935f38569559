"""What the search runs branches on: a protocol, the sandbox-backed implementation (one SandboxWorker per
executor) and a tiny in-memory fake for fast tests of the search logic."""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from typing import Protocol

from humanoidgen.generation.worker import JUDGE, RESET, RESTORE, SNAPSHOT, setup
from humanoidgen.sandbox import SandboxWorker

RESET_TIMEOUT_S = 120.0


@dataclass
class Outcome:
    ok: bool
    error_type: str | None = None
    message: str = ""
    line: int | None = None


class Executor(Protocol):
    def reset(self, spec_data: dict, seed: int | None) -> dict: ...  # {"scene": ..., "hands": ...}
    def run_step(self, code: str) -> Outcome: ...
    def snapshot(self) -> dict: ...
    def restore(self, snap: dict) -> None: ...
    def judge(self) -> dict: ...  # {"checks": [...], "events": [...]}
    def close(self) -> None: ...


class SandboxExecutor:
    """Runs steps in a SandboxWorker. A killed worker (timeout, crash) or one whose namespace a step poisoned
    (`np = 1`) is rebuilt (reset) before the next restore, so every branch starts from a sound scene."""

    def __init__(self, worker: SandboxWorker | None = None, step_timeout_s: float = 120.0) -> None:
        self.own = worker is None
        self.worker = worker or SandboxWorker(setup)
        self.step_timeout_s = step_timeout_s
        self._spec: tuple[dict, int | None] | None = None
        self._stale = False  # the scene is gone or the namespace is poisoned
        self._provided: set[str] | None = None
        self._judge = None  # episodes.replay_judge.ReplayJudge for the scene of the last reset

    def reset(self, spec_data: dict, seed: int | None) -> dict:
        if self._judge is None or self._spec != (spec_data, seed):
            from humanoidgen.episodes.replay_judge import ReplayJudge
            from humanoidgen.tasks.registry import parse_task

            self._judge = ReplayJudge(parse_task(spec_data, "<search>"), seed)
        self._spec = (spec_data, seed)
        self._stale = False
        return self.worker.call(RESET, spec_data, seed, timeout_s=RESET_TIMEOUT_S)

    def run_step(self, code: str) -> Outcome:
        if self._rebinds(code):
            self._stale = True
        out = self.worker.run_step(code, timeout_s=self.step_timeout_s)
        if out.error_type in ("Timeout", "WorkerDied"):
            self._stale = True
        return Outcome(out.ok, out.error_type, out.message, out.line)

    def snapshot(self) -> dict:
        return self.worker.call(SNAPSHOT, timeout_s=RESET_TIMEOUT_S)

    def restore(self, snap: dict) -> None:
        if self._stale and self._spec is not None:
            self.worker.close()  # a fresh process: a poisoned namespace does not survive a reset
            self.reset(*self._spec)
        self.worker.call(RESTORE, snap, timeout_s=RESET_TIMEOUT_S)

    def judge(self) -> dict:
        """The verdict of the replay here on the worker's commands since the reset (never the worker's own)."""
        if self._judge is None:
            raise RuntimeError("judge() before reset()")
        return self._judge.report(self.worker.call(JUDGE, timeout_s=RESET_TIMEOUT_S))

    def close(self) -> None:
        if self.own:
            self.worker.close()

    def _rebinds(self, code: str) -> bool:
        if self._provided is None:
            from humanoidgen.generation.script_gen import step_names

            self._provided = set(step_names())
        try:
            tree = ast.parse(code)
        except (SyntaxError, ValueError, MemoryError, RecursionError):  # untrusted text may exhaust the parser
            return False
        return any(isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store) and n.id in self._provided
                   for n in ast.walk(tree))


_EVENT = re.compile(r"^\s*#\s*event:\s*(.+)$", re.M)


class FakeExecutor:
    """In-memory stand-in: a step fails if it contains `fail`; a `# event: ...` line emits a planner event;
    the task succeeds once every `goal` string occurs in the executed code, in order."""

    def __init__(self, goal: list[str]) -> None:
        self.goal = goal
        self.code: list[str] = []
        self.events: list[str] = []
        self.steps_run = 0

    def reset(self, spec_data: dict, seed: int | None) -> dict:
        self.code, self.events = [], []
        return {"scene": {"attributes": [], "status": []}, "hands": {}}

    def run_step(self, code: str) -> Outcome:
        self.steps_run += 1
        if "fail" in code:
            return Outcome(False, "PlanningError", "the fake planner failed", 1)
        self.code.append(code)
        self.events += _EVENT.findall(code)
        return Outcome(True)

    def snapshot(self) -> dict:
        return {"code": list(self.code), "events": list(self.events)}

    def restore(self, snap: dict) -> None:
        self.code, self.events = list(snap["code"]), list(snap["events"])

    def judge(self) -> dict:
        text, pos = "\n".join(self.code), 0
        for g in self.goal:
            pos = text.find(g, pos)
            if pos < 0:
                break
        return {"checks": [{"predicate": "goal", "ok": pos >= 0, "detail": ""}], "events": list(self.events)}

    def close(self) -> None:
        pass


def outcome_text(out: Outcome) -> str:
    where = f" (line {out.line} of the step)" if out.line else ""
    return f"{out.error_type}{where}: {out.message}"

