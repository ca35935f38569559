"""Exceptions of the LLM layer; messages say what to fix, never contain the API key."""

from __future__ import annotations

from typing import Any

from humanoidgen.llm.redact import redact_text


class LLMError(RuntimeError):
    """Base class of every error raised by `humanoidgen.llm`. The message is redacted on creation: it may quote
    an endpoint's error body, which can echo the key back."""

    def __init__(self, *args: Any) -> None:
        super().__init__(*(redact_text(a) if isinstance(a, str) else a for a in args))


class LLMNotConfigured(LLMError):
    """Live mode without a base URL or API key."""


class LLMUnreachable(LLMError):
    """Connection refused / DNS failure / timeout, after retries."""


class LLMAuthError(LLMError):
    """401/403: the endpoint rejected the key."""


class LLMRateLimited(LLMError):
    """429 on every attempt."""


class LLMServerError(LLMError):
    """5xx on every attempt."""


class LLMBadResponse(LLMError):
    """HTTP 200 whose body is not a chat completion (not JSON, no choices): retrying cannot help."""


class LLMRequestError(LLMError):
    """Other 4xx (bad request, unknown model, wrong path): retrying cannot help."""


class LLMImagesRejected(LLMRequestError):
    """A 4xx answer to a request with pictures (--images): most likely the model does not take images."""


class LLMReplayMissing(LLMError):
    """Replay mode and the recording has no (more) responses for this request."""
