"""OpenAI-compatible chat client (DeepSeek-R1/V3, GPT-4o, vLLM, Ollama) with our own retries,
a response cache and record/replay."""

from __future__ import annotations

import datetime
import email.utils
import json
import logging
import math
import threading
import time
from dataclasses import replace
from typing import TYPE_CHECKING, Any
from urllib.parse import urlparse

if TYPE_CHECKING:  # imported where a request is made: the SDK takes ~0.9 s to import, and the plan workers'
    import openai  # fork server imports this module's package without ever calling an endpoint

from humanoidgen.llm.config import ENV_BASE_URL, LLMConfig
from humanoidgen.llm.errors import (
    LLMAuthError,
    LLMBadResponse,
    LLMError,
    LLMImagesRejected,
    LLMNotConfigured,
    LLMRateLimited,
    LLMRequestError,
    LLMServerError,
    LLMUnreachable,
)
from humanoidgen.llm.images import has_images
from humanoidgen.llm.redact import redact_text, watch_env
from humanoidgen.llm.results import ChatResult, TokenUsage
from humanoidgen.llm.store import Recorder, Replayer, ResponseCache, request_key

log = logging.getLogger(__name__)

_LOOPBACK = {"localhost", "127.0.0.1", "::1", "0.0.0.0"}
# Local servers (vLLM, Ollama) accept any key; the SDK still wants a non-empty one.
_PLACEHOLDER_KEY = "EMPTY"
_sleep = time.sleep  # module-level so tests can watch the retry delays without sleeping


class _Retryable(Exception):
    """Internal: one failed attempt that may succeed if repeated (after `retry_after` s, if the server said)."""

    def __init__(self, final: LLMError, retry_after: float | None = None) -> None:
        super().__init__(str(final))
        self.final = final
        self.retry_after = retry_after


class LLMClient:
    def __init__(self, config: LLMConfig) -> None:
        self.config = config
        watch_env(config.api_key_env)  # whatever variable holds the key is redacted from everything written
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
            result = _redacted(self._replayer.next(key, request))
        else:
            result = self._cache.get(key) if self._cache else None
            if result is not None:
                result = _redacted(result)  # an entry written before redaction existed
            else:
                result = _redacted(self._live(model, messages, merged))
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
        import openai

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
                delay = self._delay(attempt, err.retry_after)
                log.warning(
                    "LLM attempt %d/%d failed: %s; retrying in %.2fs",
                    attempt + 1,
                    attempts,
                    err,
                    delay,
                )
                _sleep(delay)
        raise AssertionError("unreachable")  # pragma: no cover

    def _delay(self, attempt: int, retry_after: float | None) -> float:
        """The server's Retry-After when it sent one (capped, and said so), else exponential backoff."""
        cfg = self.config
        if retry_after is None:
            return cfg.backoff_delay(attempt)
        if retry_after > cfg.retry_after_max_s:
            log.warning(
                "%s asked to wait %.0fs (Retry-After); waiting %.0fs instead, the cap "
                "(LLMConfig.retry_after_max_s)",
                cfg.base_url,
                retry_after,
                cfg.retry_after_max_s,
            )
            return cfg.retry_after_max_s
        return retry_after

    def _attempt(
        self,
        sdk: openai.OpenAI,
        model: str,
        messages: list[dict[str, Any]],
        params: dict[str, Any],
    ) -> ChatResult:
        import openai

        cfg = self.config
        t0 = time.perf_counter()
        try:
            # The raw response: we parse the body ourselves so a malformed one becomes a clear error
            # instead of the SDK's JSONDecodeError (or a plain str for a non-JSON content type).
            raw = sdk.chat.completions.with_raw_response.create(model=model, messages=messages, **params)  # type: ignore[arg-type]
            body = raw.text
        except openai.APITimeoutError:
            raise _Retryable(
                LLMUnreachable(
                    f"cannot reach {cfg.base_url}: no answer within {cfg.timeout_s:g}s; "
                    f"check ${ENV_BASE_URL} / --base-url or raise the timeout (--timeout)"
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
            raise self._status_error(e, has_images(messages)) from None
        except openai.APIError as e:  # anything else the SDK rejects: still one clear line
            raise LLMBadResponse(f"unusable answer from {cfg.base_url}: {type(e).__name__}: {e}") from None
        latency = time.perf_counter() - t0
        data = _completion(body, cfg.base_url or "")
        choice = data["choices"][0]
        msg = choice.get("message") if isinstance(choice.get("message"), dict) else {}
        return ChatResult(
            text=_text(msg.get("content")),
            reasoning=_text(msg.get("reasoning_content") or msg.get("reasoning")) or None,
            usage=_usage(data.get("usage")),
            model=data.get("model") or model,
            latency_s=latency,
            cached=False,
            finish_reason=choice.get("finish_reason"),
        )

    def _status_error(self, e: openai.APIStatusError, images: bool = False) -> Exception:
        cfg = self.config
        status = e.status_code
        detail = _short(e)
        if status in (401, 403):
            return LLMAuthError(
                f"the endpoint {cfg.base_url} rejected the API key in ${cfg.api_key_env} (HTTP {status}: {detail})"
            )
        wait = retry_after_s(e.response.headers)
        if status == 429:
            return _Retryable(
                LLMRateLimited(f"rate limited by {cfg.base_url} (HTTP 429: {detail})"), wait
            )
        if status >= 500:
            return _Retryable(
                LLMServerError(
                    f"server error from {cfg.base_url} (HTTP {status}: {detail})"
                ),
                wait if status == 503 else None,
            )
        if images and status in (400, 415, 422):
            # Endpoints word this differently ("unknown variant `image_url`", "not a multimodal model"); the
            # picture is what this request adds, so name it and the way out.
            return LLMImagesRejected(
                f"{cfg.base_url} (model {cfg.model}) rejected a prompt with a picture (--images): HTTP {status}: "
                f"{' '.join(detail.split())}; if the model does not take images, run without --images or "
                f"choose a vision model"
            )
        hint = (
            " (wrong model name, or base URL missing '/v1'?)" if status == 404 else ""
        )
        return LLMRequestError(
            f"request rejected by {cfg.base_url} (HTTP {status}: {detail}){hint}"
        )


def _redacted(result: ChatResult) -> ChatResult:
    """The answer without secrets: a model (or proxy) echoing the key must not carry it into logs, plans,
    caches or recordings written downstream."""
    text = redact_text(result.text)
    reasoning = redact_text(result.reasoning) if result.reasoning else result.reasoning
    if text == result.text and reasoning == result.reasoning:
        return result
    return replace(result, text=text, reasoning=reasoning)


def _completion(body: str, base_url: str) -> dict[str, Any]:
    """The parsed chat completion of an HTTP 200 body, or LLMBadResponse saying what is wrong with it."""
    snippet = " ".join(body.split())[:120] or "<empty body>"
    hint = "; is the base URL an OpenAI-compatible API (usually ending in /v1)?"
    try:
        data = json.loads(body)
    except ValueError as exc:
        raise LLMBadResponse(
            f"{base_url} answered HTTP 200 with a body that is not valid JSON ({exc}): {snippet!r}{hint}"
        ) from None
    if not isinstance(data, dict):
        raise LLMBadResponse(
            f"{base_url} answered HTTP 200 with JSON that is not a chat completion object: {snippet!r}{hint}"
        )
    choices = data.get("choices")
    if not choices:
        finish = ""
        if "error" in data:
            finish = f" (error in the body: {str(data['error'])[:200]})"
        raise LLMBadResponse(f"the endpoint returned no choices{finish}: {base_url} answered {snippet!r}")
    if not isinstance(choices, list) or not isinstance(choices[0], dict):
        raise LLMBadResponse(f"{base_url} answered HTTP 200 with malformed choices: {snippet!r}")
    return data


def _text(content: Any) -> str:
    """A message's content as text: a string, or the text parts of a list of parts; anything else is none."""
    if isinstance(content, str):
        return content
    if isinstance(content, list):
        return "".join(str(p.get("text", "")) for p in content if isinstance(p, dict))
    return ""


def _usage(usage: Any) -> TokenUsage:
    try:
        return TokenUsage.from_openai(usage if isinstance(usage, dict) else None)
    except (TypeError, ValueError, AttributeError):
        return TokenUsage()  # odd token counts are no reason to drop a valid answer


def retry_after_s(headers: Any, now: float | None = None) -> float | None:
    """Seconds a 429/503 answer asks us to wait: `retry-after-ms` (OpenAI), `Retry-After` as seconds or as an
    HTTP date; None when absent or unreadable."""
    try:
        ms = headers.get("retry-after-ms")
        if ms is not None:
            value = float(ms) / 1000.0
            return max(0.0, value) if math.isfinite(value) else None
        ra = headers.get("retry-after")
    except (AttributeError, ValueError, TypeError):
        return None
    if ra is None:
        return None
    ra = str(ra).strip()
    try:
        value = float(ra)
        return max(0.0, value) if math.isfinite(value) else None
    except ValueError:
        pass
    try:
        when = email.utils.parsedate_to_datetime(ra)
    except (TypeError, ValueError, IndexError):
        return None
    if when.tzinfo is None:  # HTTP dates are GMT
        when = when.replace(tzinfo=datetime.timezone.utc)
    return max(0.0, when.timestamp() - (time.time() if now is None else now))


def _short(e: openai.APIStatusError, limit: int = 300) -> str:
    body = e.body
    if isinstance(body, dict):
        body = body.get("message") or body.get("error") or body
    text = str(body if body is not None else e.message)
    return text if len(text) <= limit else text[:limit] + "..."
