"""A scripted, local OpenAI-compatible chat server for tests and demos (no network beyond loopback).

    with ScriptedServer([Response.error(429), Response("hello", reasoning="hm")]) as srv:
        LLMClient(LLMConfig(base_url=srv.base_url, ...)).chat([...])
        assert len(srv.requests) == 2

Each script entry serves one request, in order: a `Response` (reply, HTTP error, or with `raw` a body sent
verbatim), a plain string (a reply), or a callable(request_json) -> Response | str, for conversation-aware
scripts. `headers` add response headers (Retry-After, ...). `vision=False` makes a text-only endpoint: a request
with an image part gets HTTP 400 as DeepSeek's API words it, without using a script entry.
"""

from __future__ import annotations

import json
import threading
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any, Self

CHAT_PATHS = ("/v1/chat/completions", "/chat/completions")


@dataclass
class Response:
    """One scripted answer. `status != 200` makes it an HTTP error with `body` as JSON/text."""

    text: str = ""
    reasoning: str | None = (
        None  # sent as message.reasoning_content (DeepSeek-R1 style)
    )
    status: int = 200
    body: Any = None  # error body; default: OpenAI-style {"error": {...}}
    prompt_tokens: int | None = None  # None: rough word count of the request
    completion_tokens: int | None = None  # None: word count of text (+ reasoning)
    reasoning_tokens: int | None = None  # None: word count of reasoning, 0 without
    finish_reason: str = "stop"
    delay_s: float = 0.0  # sleep before answering (client timeout tests)
    headers: dict[str, str] = field(default_factory=dict)  # extra headers, e.g. {"Retry-After": "5"}
    # Sent verbatim as the body, whatever the status (malformed-answer tests); None: the usual JSON.
    raw: bytes | str | None = None
    content_type: str = "application/json"

    @classmethod
    def error(cls, status: int, body: Any = None, **kw: Any) -> Response:
        return cls(status=status, body=body, **kw)

    @classmethod
    def malformed(cls, raw: bytes | str, status: int = 200, **kw: Any) -> Response:
        """An answer whose body is exactly `raw` (truncated JSON, HTML, {"choices": []}, ...)."""
        return cls(status=status, raw=raw, **kw)


Entry = Response | str | Callable[[dict[str, Any]], Response | str]


def _words(s: str | None) -> int:
    return len((s or "").split())


def _text(content: Any) -> str:
    if isinstance(content, list):
        return " ".join(str(p.get("text", "")) for p in content if isinstance(p, dict))
    return content if isinstance(content, str) else ""


def _has_image(req: dict[str, Any]) -> bool:
    return any(isinstance(p, dict) and p.get("type") == "image_url"
               for m in req.get("messages", []) if isinstance(m.get("content"), list) for p in m["content"])


# What a text-only endpoint answers to an image part (DeepSeek's API, 2025).
NO_VISION_BODY = {"error": {"message": "Failed to deserialize the JSON body into the target type: messages[0]: "
                                       "unknown variant `image_url`, expected `text` at line 1 column 120",
                            "type": "invalid_request_error", "param": None, "code": "invalid_request_error"}}


def _openai_body(req: dict[str, Any], r: Response) -> dict[str, Any]:
    prompt = r.prompt_tokens
    if prompt is None:
        prompt = sum(_words(_text(m.get("content"))) for m in req.get("messages", []))
    reasoning = (
        r.reasoning_tokens if r.reasoning_tokens is not None else _words(r.reasoning)
    )
    completion = (
        r.completion_tokens
        if r.completion_tokens is not None
        else _words(r.text) + reasoning
    )
    message: dict[str, Any] = {"role": "assistant", "content": r.text}
    if r.reasoning is not None:
        message["reasoning_content"] = r.reasoning
    return {
        "id": f"chatcmpl-{uuid.uuid4().hex[:12]}",
        "object": "chat.completion",
        "created": int(time.time()),
        "model": req.get("model", "scripted"),
        "choices": [{"index": 0, "message": message, "finish_reason": r.finish_reason}],
        "usage": {
            "prompt_tokens": prompt,
            "completion_tokens": completion,
            "total_tokens": prompt + completion,
            "completion_tokens_details": {"reasoning_tokens": reasoning},
        },
    }


class ScriptedServer:
    """Threaded HTTP server on 127.0.0.1:<free port>; a context manager (start on enter, stop on exit)."""

    def __init__(
        self,
        responses: list[Entry] | None = None,
        default: Entry | None = None,
        api_key: str | None = None,
        vision: bool = True,
    ) -> None:
        self.script: list[Entry] = list(responses or [])
        self.default = default  # served once the script is used up; None -> HTTP 500 "script exhausted"
        self.api_key = api_key  # if set, requests without "Bearer <api_key>" get 401
        self.vision = vision  # False: requests with an image part get HTTP 400 (NO_VISION_BODY)
        # Every chat request in arrival order: JSON body, path, Authorization header.
        self.requests: list[dict[str, Any]] = []
        self.paths: list[str] = []
        self.auth_headers: list[str | None] = []
        self.errors: list[Exception] = []  # exceptions raised by script callables
        self._lock = threading.Lock()
        self._httpd: ThreadingHTTPServer | None = None
        self._thread: threading.Thread | None = None

    # ---- lifecycle --------------------------------------------------------------------------

    @property
    def port(self) -> int:
        assert self._httpd is not None, "server not started"
        return self._httpd.server_address[1]

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.port}/v1"

    def start(self) -> Self:
        handler = type("_Handler", (_Handler,), {"scripted": self})
        self._httpd = ThreadingHTTPServer(("127.0.0.1", 0), handler)
        self._httpd.daemon_threads = True
        # Short poll interval: stop() waits at most one interval for serve_forever to notice.
        self._thread = threading.Thread(
            target=self._httpd.serve_forever,
            kwargs={"poll_interval": 0.05},
            name="ScriptedServer",
            daemon=True,
        )
        self._thread.start()
        return self

    def stop(self) -> None:
        if self._httpd is not None:
            self._httpd.shutdown()
            self._httpd.server_close()
            self._thread and self._thread.join(timeout=5)
            self._httpd = None

    def __enter__(self) -> Self:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def add(self, *entries: Entry) -> None:
        with self._lock:
            self.script.extend(entries)

    # ---- serving ------------------------------------------------------------------------------

    def _log(self, path: str, req: dict[str, Any], auth: str | None) -> None:
        with self._lock:
            self.requests.append(req)
            self.paths.append(path)
            self.auth_headers.append(auth)

    def _next(self, req: dict[str, Any]) -> Response:
        with self._lock:
            n = len(self.requests)
            entry = self.script.pop(0) if self.script else self.default
        if entry is None:
            return Response.error(
                500,
                {
                    "error": {
                        "message": f"ScriptedServer: script exhausted at request #{n}",
                        "type": "server_error",
                    }
                },
            )
        if callable(entry) and not isinstance(entry, Response):
            try:
                entry = entry(req)
            except Exception as e:  # noqa: BLE001 - a buggy script must fail loudly, not as a dropped connection
                self.errors.append(e)
                msg = f"ScriptedServer: script callable raised {type(e).__name__}: {e}"
                return Response.error(
                    500, {"error": {"message": msg, "type": "server_error"}}
                )
        return Response(text=entry) if isinstance(entry, str) else entry


class _Handler(BaseHTTPRequestHandler):
    scripted: ScriptedServer
    protocol_version = "HTTP/1.1"  # keep-alive, like real endpoints

    def log_message(self, format: str, *args: Any) -> None:  # quiet test output
        pass

    def _send(
        self,
        status: int,
        payload: Any,
        headers: dict[str, str] | None = None,
        content_type: str = "application/json",
    ) -> None:
        data = (
            payload
            if isinstance(payload, bytes)
            else (
                payload.encode()
                if isinstance(payload, str)
                else json.dumps(payload).encode()
            )
        )
        self.send_response(status)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(data)))
        for k, v in (headers or {}).items():
            self.send_header(k, v)
        self.end_headers()
        try:
            self.wfile.write(data)
        except (BrokenPipeError, ConnectionResetError):
            pass  # the client gave up (timeout tests); nothing to report

    def do_POST(self) -> None:
        length = int(self.headers.get("Content-Length") or 0)
        raw = self.rfile.read(length) if length else b""
        srv = self.scripted
        path = self.path.split("?")[0]
        if path not in CHAT_PATHS:
            self._send(
                404, {"error": {"message": f"unknown path {path}", "type": "not_found"}}
            )
            return
        try:
            req = json.loads(raw or b"{}")
        except ValueError:
            self._send(
                400,
                {
                    "error": {
                        "message": "body is not JSON",
                        "type": "invalid_request_error",
                    }
                },
            )
            return
        auth = self.headers.get("Authorization")
        srv._log(path, req, auth)
        if srv.api_key is not None and auth != f"Bearer {srv.api_key}":
            # Unscripted 401: the script entry is not consumed.
            self._send(
                401,
                {
                    "error": {
                        "message": "invalid api key",
                        "type": "invalid_request_error",
                    }
                },
            )
            return
        if not srv.vision and _has_image(req):
            self._send(400, NO_VISION_BODY)  # unscripted, like the 401: the script entry is not consumed
            return
        r = srv._next(req)
        if r.delay_s:
            time.sleep(r.delay_s)
        if r.raw is not None:
            self._send(r.status, r.raw, r.headers, r.content_type)
            return
        if r.status != 200:
            body = (
                r.body
                if r.body is not None
                else {
                    "error": {
                        "message": f"scripted HTTP {r.status}",
                        "type": "scripted_error",
                        "code": r.status,
                    }
                }
            )
            self._send(r.status, body, r.headers)
            return
        self._send(200, _openai_body(req, r), r.headers)
