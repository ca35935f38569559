"""One redaction function for everything the LLM layer and `hgen generate` write (cache, recordings, logs,
error messages): API keys from the environment and Authorization / Bearer tokens become "[REDACTED]".

The secret values are read from the environment at call time, so a key exported after start-up is covered too.
An endpoint may echo the key back (in an error body, or a model repeating its prompt), so redaction is applied
to what we write, not only to what we send.
"""

from __future__ import annotations

import os
import re
from typing import Any, TypeVar

REDACTED = "[REDACTED]"
# Shorter values are placeholders ("EMPTY", "none"), not secrets; replacing them would mangle every log.
MIN_SECRET_LEN = 8
# Env vars whose values are secrets: the ones the client is told to read (see `watch_env`) and any whose name
# says it is one.
_SECRET_NAME = re.compile(r"(API_?KEY|TOKEN|SECRET|PASSWORD)$", re.IGNORECASE)
_watched: set[str] = {"OPENAI_API_KEY"}
# Header-shaped secrets even when the value is not in our environment (a proxy's own token, say).
_PATTERNS = (
    (re.compile(r"(?i)\b(authorization[\"']?\s*[:=]\s*[\"']?)(?:bearer\s+|basic\s+)?[^\s\"',;}]+"), r"\1" + REDACTED),
    (re.compile(r"(?i)\b(bearer\s+)[A-Za-z0-9._~+/=-]{8,}"), r"\1" + REDACTED),
    (re.compile(r"\bsk-[A-Za-z0-9_-]{16,}"), REDACTED),  # OpenAI / DeepSeek style keys
)

T = TypeVar("T")


def watch_env(name: str) -> None:
    """Treat the value of env var `name` as a secret from now on (LLMConfig.api_key_env may be any name)."""
    _watched.add(name)


def secrets() -> list[str]:
    """The secret values currently in the environment, longest first (so a key containing another is
    replaced whole)."""
    values = {v for k, v in os.environ.items() if (k in _watched or _SECRET_NAME.search(k)) and
              len(v) >= MIN_SECRET_LEN}
    return sorted(values, key=len, reverse=True)


def redact_text(text: str, values: list[str] | None = None) -> str:
    values = secrets() if values is None else values
    for v in values:
        text = text.replace(v, REDACTED)
    for pattern, repl in _PATTERNS:
        text = pattern.sub(repl, text)
    return text


def redact(obj: T) -> T:
    """`obj` with every string (dict keys and values, list and tuple items, recursively) redacted; other
    values unchanged. The input is not modified."""
    return _walk(obj, secrets())


def _walk(obj: Any, values: list[str]) -> Any:
    if isinstance(obj, str):
        return redact_text(obj, values)
    if isinstance(obj, dict):
        return {_walk(k, values): _walk(v, values) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return type(obj)(_walk(v, values) for v in obj) if not hasattr(obj, "_fields") else \
            type(obj)(*(_walk(v, values) for v in obj))
    return obj
