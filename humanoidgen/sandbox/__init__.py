"""Checking and running untrusted (LLM-written) plan steps: `checker` (static allow-list) and `runner`
(separate worker process with restricted builtins, wall-time and memory limits).

The names below are imported when first used: `hgen run` starts the workers' fork server
(`sandbox.forkserver`) before it imports numpy and the runner, so the server's seconds of warm-up start
that much earlier."""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from humanoidgen.sandbox.checker import (SAFE_BUILTINS, CheckedCode, CodeRejected, Violation, check_code,
                                             split_steps, strip_api_imports)
    from humanoidgen.sandbox.runner import SandboxError, SandboxWorker, StepOutcome

_WHERE = {
    "SAFE_BUILTINS": "checker", "CheckedCode": "checker", "CodeRejected": "checker", "Violation": "checker",
    "check_code": "checker", "split_steps": "checker", "strip_api_imports": "checker",
    "SandboxError": "runner", "SandboxWorker": "runner", "StepOutcome": "runner",
}

__all__ = ["SAFE_BUILTINS", "CheckedCode", "CodeRejected", "SandboxError", "SandboxWorker", "StepOutcome",
           "Violation", "check_code", "split_steps", "strip_api_imports"]


def __getattr__(name: str) -> Any:
    module = _WHERE.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value
