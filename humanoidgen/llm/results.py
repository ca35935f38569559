"""Result types of a chat call (plain dataclasses so they round-trip through JSON)."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any


@dataclass(frozen=True)
class TokenUsage:
    prompt: int = 0
    completion: int = 0
    reasoning: int | None = (
        None  # only when the endpoint reports it (e.g. DeepSeek-R1, o-series)
    )
    total: int = 0

    def __add__(self, other: TokenUsage) -> TokenUsage:
        # None + None stays None ("never reported"); otherwise missing counts as 0.
        if self.reasoning is None and other.reasoning is None:
            reasoning = None
        else:
            reasoning = (self.reasoning or 0) + (other.reasoning or 0)
        return TokenUsage(
            self.prompt + other.prompt,
            self.completion + other.completion,
            reasoning,
            self.total + other.total,
        )

    @classmethod
    def from_openai(cls, usage: dict[str, Any] | None) -> TokenUsage:
        if not usage:
            return cls()
        details = usage.get("completion_tokens_details") or {}
        prompt = int(usage.get("prompt_tokens") or 0)
        completion = int(usage.get("completion_tokens") or 0)
        reasoning = details.get("reasoning_tokens")
        return cls(
            prompt=prompt,
            completion=completion,
            reasoning=None if reasoning is None else int(reasoning),
            total=int(usage.get("total_tokens") or prompt + completion),
        )


@dataclass(frozen=True)
class ChatResult:
    text: str
    reasoning: str | None = None  # DeepSeek-R1 `reasoning_content`
    usage: TokenUsage = field(default_factory=TokenUsage)
    model: str = ""
    latency_s: float = 0.0
    cached: bool = (
        False  # True when served from the cache or a recording (no request made)
    )
    finish_reason: str | None = None

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict[str, Any], cached: bool | None = None) -> ChatResult:
        d = dict(d)
        d["usage"] = TokenUsage(**d.get("usage", {}))
        if cached is not None:
            d["cached"] = cached
        return cls(**d)
