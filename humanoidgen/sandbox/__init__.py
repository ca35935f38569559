"""Checking and running untrusted (LLM-written) plan steps: `checker` (static allow-list) and `runner`
(separate worker process with restricted builtins, wall-time and memory limits)."""

from humanoidgen.sandbox.checker import (
    SAFE_BUILTINS,
    CheckedCode,
    CodeRejected,
    Violation,
    check_code,
    split_steps,
    strip_api_imports,
)
from humanoidgen.sandbox.runner import SandboxError, SandboxWorker, StepOutcome

__all__ = [
    "SAFE_BUILTINS",
    "CheckedCode",
    "CodeRejected",
    "SandboxError",
    "SandboxWorker",
    "StepOutcome",
    "Violation",
    "check_code",
    "split_steps",
    "strip_api_imports",
]
