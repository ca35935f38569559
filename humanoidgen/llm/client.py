"""OpenAI-compatible chat client (DeepSeek-R1/V3, GPT-4o, vLLM, Ollama) with our own retries,
a response cache and record/replay."""

from __future__ import annotations

import logging
import threading
import time
from typing import Any
from urllib.parse import urlparse

import openai

from humanoidgen.llm.config import ENV_BASE_URL, LLMConfig
from humanoidgen.llm.errors import (
    LLMAuthError,
    LLMError,
    LLMNotConfigured,
    LLMRateLimited,
    LLMRequestError,
    LLMServerError,
    LLMUnreachable,
)
from humanoidgen.llm.results import ChatResult, TokenUsage
from humanoidgen.llm.store import Recorder, Replayer, ResponseCache, request_key

log = logging.getLogger(__name__)

_LOOPBACK = {"localhost", "127.0.0.1", "::1", "0.0.0.0"}
# Local servers (vLLM, Ollama) accept any key; the SDK still wants a non-empty one.
_PLACEHOLDER_KEY = "EMPTY"


class _Retryable(Exception):
    """Internal: one failed attempt that may succeed if repeated."""

    def __init__(self, final: LLMError) -> None:
        super().__init__(str(final))
        self.final = final


class LLMClient:
    def __init__(self, config: LLMConfig) -> None:
        self.config = config
        self.usage_total = (
            TokenUsage()
        )  # every returned result, cached/replayed included
        self.usage_live = (
            TokenUsage()
        )  # only requests actually sent (what the endpoint bills)
        self.calls = 0
        self._lock = threading.Lock()
        self._cache = ResponseCache(config.cache_dir) if config.cache_dir else None
        self._recorder: Recorder | None = None
        self._replayer: Replayer | None = None
        if config.mode in ("record", "replay") and config.recording_path is None:
            raise LLMNotConfigured(
                f"mode {config.mode!r} needs LLMConfig.recording_path (a JSONL file)"
            )
        if config.mode == "record":
            self._recorder = Recorder(config.recording_path)  # type: ignore[arg-type]
        elif config.mode == "replay":
            self._replayer = Replayer(config.recording_path)  # type: ignore[arg-type]
        self._sdk: openai.OpenAI | None = None

    # ---- public API -------------------------------------------------------------------------

    def chat(self, messages: list[dict[str, Any]], **params: Any) -> ChatResult:
        """One chat completion. `params` (temperature, max_tokens, ...) override the config's."""
        merged = {
            "temperature": self.config.temperature,
            "max_tokens": self.config.max_tokens,
        }
        merged = {k: v for k, v in {**merged, **params}.items() if v is not None}
        model = merged.pop("model", self.config.model)
        request = {"model": model, "messages": messages, "params": merged}
        key = request_key(request)

        if self._replayer is not None:
            result = self._replayer.next(key, request)
        else:
            result = self._cache.get(key) if self._cache else None
            if result is None:
                result = self._live(model, messages, merged)
                with self._lock:
                    self.usage_live = self.usage_live + result.usage
                if self._cache:
                    self._cache.put(key, request, result)
            if (
                self._recorder is not None
            ):  # record cache hits too, so replay is complete
                self._recorder.append(key, request, result)
        with self._lock:
            self.usage_total = self.usage_total + result.usage
            self.calls += 1
        return result

    # ---- live requests ------------------------------------------------------------------------

    def _client(self) -> openai.OpenAI:
        cfg = self.config
        if not cfg.base_url:
            raise LLMNotConfigured(
                f"no LLM endpoint configured: set ${ENV_BASE_URL} or pass --base-url "
                f"(e.g. https://api.deepseek.com/v1, http://localhost:8000/v1), "
                f"or use mode='replay' with a recording"
            )
        key = cfg.api_key()
        if key is None:
            if (urlparse(cfg.base_url).hostname or "") not in _LOOPBACK:
                raise LLMNotConfigured(
                    f"no API key: set ${cfg.api_key_env} for {cfg.base_url} "
                    f"(or LLMConfig.api_key_env to the variable that holds it)"
                )
            key = _PLACEHOLDER_KEY
        # Re-created per call so a key exported after construction is picked up; cheap.
        return openai.OpenAI(
            base_url=cfg.base_url, api_key=key, timeout=cfg.timeout_s, max_retries=0
        )

    def _live(
        self, model: str, messages: list[dict[str, Any]], params: dict[str, Any]
    ) -> ChatResult:
        cfg = self.config
        sdk = self._client()
        attempts = cfg.max_retries + 1
        for attempt in range(attempts):
            try:
                return self._attempt(sdk, model, messages, params)
            except _Retryable as err:
                if attempt + 1 >= attempts:
                    final = err.final
                    raise type(final)(
                        f"{final} (gave up after {attempts} attempts)"
                    ) from None
                delay = cfg.backoff_delay(attempt)
                log.warning(
                    "LLM attempt %d/%d failed: %s; retrying in %.2fs",
                    attempt + 1,
                    attempts,
                    err,
                    delay,
                )
                time.sleep(delay)
        raise AssertionError("unreachable")  # pragma: no cover

    def _attempt(
        self,
        sdk: openai.OpenAI,
        model: str,
        messages: list[dict[str, Any]],
        params: dict[str, Any],
    ) -> ChatResult:
        cfg = self.config
        t0 = time.perf_counter()
        try:
            resp = sdk.chat.completions.create(model=model, messages=messages, **params)  # type: ignore[arg-type]
        except openai.APITimeoutError:
            raise _Retryable(
                LLMUnreachable(
                    f"cannot reach {cfg.base_url}: no answer within {cfg.timeout_s:g}s; "
                    f"check ${ENV_BASE_URL} / --base-url or raise timeout_s"
                )
            ) from None
        except openai.APIConnectionError as e:
            cause = e.__cause__ or e
            raise _Retryable(
                LLMUnreachable(
                    f"cannot reach {cfg.base_url}: {type(cause).__name__}: {cause}; check ${ENV_BASE_URL} / --base-url"
                )
            ) from None
        except openai.APIStatusError as e:
            raise self._status_error(e) from None
        latency = time.perf_counter() - t0
        data = (
            resp.model_dump()
        )  # extra fields (reasoning_content) survive: SDK models allow extras
        choice = (data.get("choices") or [{}])[0]
        msg = choice.get("message") or {}
        return ChatResult(
            text=msg.get("content") or "",
            reasoning=msg.get("reasoning_content") or msg.get("reasoning") or None,
            usage=TokenUsage.from_openai(data.get("usage")),
            model=data.get("model") or model,
            latency_s=latency,
            cached=False,
            finish_reason=choice.get("finish_reason"),
        )

    def _status_error(self, e: openai.APIStatusError) -> Exception:
        cfg = self.config
        status = e.status_code
        detail = _short(e)
        if status in (401, 403):
            return LLMAuthError(
                f"the endpoint {cfg.base_url} rejected the API key in ${cfg.api_key_env} (HTTP {status}: {detail})"
            )
        if status == 429:
            return _Retryable(
                LLMRateLimited(f"rate limited by {cfg.base_url} (HTTP 429: {detail})")
            )
        if status >= 500:
            return _Retryable(
                LLMServerError(
                    f"server error from {cfg.base_url} (HTTP {status}: {detail})"
                )
            )
        hint = (
            " (wrong model name, or base URL missing '/v1'?)" if status == 404 else ""
        )
        return LLMRequestError(
            f"request rejected by {cfg.base_url} (HTTP {status}: {detail}){hint}"
        )


def _short(e: openai.APIStatusError, limit: int = 300) -> str:
    body = e.body
    if isinstance(body, dict):
        body = body.get("message") or body.get("error") or body
    text = str(body if body is not None else e.message)
    return text if len(text) <= limit else text[:limit] + "..."
