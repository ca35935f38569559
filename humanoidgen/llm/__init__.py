"""LLM client layer: an OpenAI-compatible chat client with retries, cache and record/replay."""

from humanoidgen.llm.client import LLMClient
from humanoidgen.llm.config import LLMConfig
from humanoidgen.llm.errors import (
    LLMAuthError,
    LLMError,
    LLMImagesRejected,
    LLMNotConfigured,
    LLMRateLimited,
    LLMReplayMissing,
    LLMRequestError,
    LLMServerError,
    LLMUnreachable,
)
from humanoidgen.llm.results import ChatResult, TokenUsage

__all__ = [
    "ChatResult",
    "LLMAuthError",
    "LLMClient",
    "LLMConfig",
    "LLMError",
    "LLMImagesRejected",
    "LLMNotConfigured",
    "LLMRateLimited",
    "LLMReplayMissing",
    "LLMRequestError",
    "LLMServerError",
    "LLMUnreachable",
    "TokenUsage",
]
