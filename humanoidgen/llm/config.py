"""Configuration of the LLM client.

The API key is deliberately *not* a field: the config only names the env var that holds it, so
dumping, logging or caching a config can never leak the secret.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

DEFAULT_MODEL = "deepseek-reasoner"
ENV_BASE_URL = "OPENAI_BASE_URL"
ENV_MODEL = "HGEN_LLM_MODEL"
ENV_API_KEY = "OPENAI_API_KEY"

Mode = Literal["live", "record", "replay"]


class LLMConfig(BaseModel):
    """Where and how to talk to an OpenAI-compatible chat endpoint."""

    model_config = ConfigDict(extra="forbid")

    base_url: str | None = None
    model: str = DEFAULT_MODEL
    api_key_env: str = ENV_API_KEY
    timeout_s: float = Field(60.0, gt=0)
    max_retries: int = Field(4, ge=0)  # retries after the first attempt
    backoff_s: float = Field(1.0, ge=0)  # first retry delay; doubles each retry
    backoff_max_s: float = Field(30.0, ge=0)  # cap on a single delay
    # A 429/503 Retry-After is honoured up to this many seconds: a server asking for an hour would otherwise
    # hang the command silently (the cap is logged when it applies).
    retry_after_max_s: float = Field(120.0, ge=0)
    temperature: float | None = None
    max_tokens: int | None = None
    cache_dir: Path | None = None
    mode: Mode = "live"
    recording_path: Path | None = None  # JSONL; needed for "record" and "replay"

    @classmethod
    def from_env(
        cls, base_url: str | None = None, model: str | None = None, **kw: Any
    ) -> LLMConfig:
        """Build a config: explicit arguments (CLI flags) win over env vars, which win over defaults."""
        return cls(
            base_url=base_url or os.environ.get(ENV_BASE_URL) or None,
            model=model or os.environ.get(ENV_MODEL) or DEFAULT_MODEL,
            **kw,
        )

    def api_key(self) -> str | None:
        """Read the key at call time (never stored on the object)."""
        return os.environ.get(self.api_key_env) or None

    def backoff_delay(self, retry: int) -> float:
        """Delay before retry number `retry` (0-based): exponential, capped."""
        return min(self.backoff_s * (2**retry), self.backoff_max_s)
