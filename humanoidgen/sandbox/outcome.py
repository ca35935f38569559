"""What a plan step or call came to, as the parent reports it (`StepOutcome`, `SandboxError`), and how the
worker turns an exception into one without trusting the exception: its class, message and line in the
step are read defensively (a hostile exception's `__str__` may raise or lie)."""

from __future__ import annotations

import contextlib
import re
import traceback
from dataclasses import dataclass
from typing import Any

STDOUT_LIMIT = 64_000
MESSAGE_LIMIT = 4_000  # characters of an error message
STEP_FILENAME = "<step>"


@dataclass
class StepOutcome:
    ok: bool
    error_type: str | None  # exception class name, "CodeRejected", "Timeout", "WorkerDied", "ProtocolError"
    message: str
    line: int | None  # line within the step where it failed
    seconds: float  # wall time seen by the parent (check + execution + round trip)
    stdout: str = ""
    worker_restarted: bool = False  # a fresh worker ran this step: state from earlier steps is gone
    value: Any = None  # the result of `SandboxWorker.call`


class SandboxError(RuntimeError):
    """`SandboxWorker.call` failed; `outcome` says how."""

    def __init__(self, outcome: StepOutcome) -> None:
        self.outcome = outcome
        super().__init__(f"{outcome.error_type}: {outcome.message}")


def exit_text(code: int | None) -> str:
    if code is None:
        return "exit code unknown"
    if code < 0:
        import signal

        with contextlib.suppress(ValueError):
            return f"killed by {signal.Signals(-code).name}"
    return f"exit code {code}"


# C0/C1 control characters (escape sequences that move the cursor, erase lines or retitle a terminal; carriage
# returns and backspaces that overwrite what was printed) and the invisible format characters that reorder text
# (bidi overrides): text a plan wrote may reach a console, and must not be able to repaint it. Tabs and (where
# asked) newlines stay.
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u200b-\u200f\u202a-\u202e\u2060-\u2069\ufeff]")


def plain(x: Any, n: int, newlines: bool = True) -> str:
    """`x` if it is a string (else ""), at most `n` characters, each control character shown as U+FFFD and,
    without `newlines`, each newline as a space."""
    if not isinstance(x, str):
        return ""
    x = _CONTROL.sub("\ufffd", x[:n])
    return x if newlines else x.replace("\n", " ")


def outcome_of_reply(reply: Any) -> StepOutcome | None:
    """A StepOutcome from a decoded reply, trusting none of its types; None if it is not a reply."""
    if not isinstance(reply, dict) or reply.get("kind") != "reply" or not isinstance(reply.get("outcome"), dict):
        return None
    o = reply["outcome"]

    def text(x: Any, n: int) -> str:
        return plain(x, n)

    line = o.get("line")
    return StepOutcome(ok=o.get("ok") is True, error_type=text(o.get("error_type"), 100) or None,
                       message=text(o.get("message"), MESSAGE_LIMIT),
                       line=line if isinstance(line, int) and not isinstance(line, bool) else None,
                       seconds=0.0, stdout=text(o.get("stdout"), STDOUT_LIMIT), value=o.get("value"))


def type_name(e: BaseException) -> str:
    try:
        return str(type(e).__name__)[:100]
    except BaseException:  # noqa: BLE001 - a hostile exception class
        return "Exception"


def message_of(e: BaseException) -> str:
    """`call: reason` for planner failures (the LLM's feedback), else the exception's text; never raises."""
    try:
        call, reason = getattr(e, "call", None), getattr(e, "reason", None)
        if isinstance(call, str) and isinstance(reason, str):
            return f"{call}: {reason}"[:MESSAGE_LIMIT]
        return (str(e) or repr(e))[:MESSAGE_LIMIT]
    except BaseException:  # noqa: BLE001 - __str__ of a hostile exception
        return "(the exception could not be printed)"


def step_line(e: BaseException) -> int | None:
    """Line of the innermost traceback frame inside the step's code."""
    line = None
    try:
        for frame in traceback.extract_tb(e.__traceback__):
            if frame.filename == STEP_FILENAME:
                line = frame.lineno
    except BaseException:  # noqa: BLE001
        return None
    return line
