"""LLM client layer, exercised over real HTTP against the local ScriptedServer."""

from __future__ import annotations

import json
import logging
import socket
import time
from pathlib import Path

import pytest

from humanoidgen.llm import (
    LLMAuthError,
    LLMClient,
    LLMConfig,
    LLMNotConfigured,
    LLMRateLimited,
    LLMReplayMissing,
    LLMServerError,
    LLMUnreachable,
    TokenUsage,
)
from humanoidgen.llm.fake_server import Response, ScriptedServer

SECRET = "sk-test-SECRET-do-not-leak-7f3a9c"
MSGS = [
    {"role": "system", "content": "You plan robot tasks."},
    {"role": "user", "content": "Place the cube on the plate please"},
]


@pytest.fixture(autouse=True)
def _env(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", SECRET)
    monkeypatch.delenv("OPENAI_BASE_URL", raising=False)
    monkeypatch.delenv("HGEN_LLM_MODEL", raising=False)


def cfg(base_url: str | None, **kw) -> LLMConfig:
    # Tiny timeouts/backoff keep the whole file well under a few seconds.
    kw = {
        "timeout_s": 2.0,
        "max_retries": 3,
        "backoff_s": 0.01,
        "backoff_max_s": 0.05,
        **kw,
    }
    return LLMConfig(base_url=base_url, model="deepseek-reasoner", **kw)


def test_plain_reply_with_usage_and_reasoning() -> None:
    reply = Response(
        "cube -> plate",
        reasoning="The cube is left of the plate.",
        prompt_tokens=20,
        completion_tokens=15,
        reasoning_tokens=9,
    )
    with ScriptedServer([reply]) as srv:
        client = LLMClient(cfg(srv.base_url, temperature=0.2))
        res = client.chat(MSGS, max_tokens=64)
    assert res.text == "cube -> plate"
    assert res.reasoning == "The cube is left of the plate."
    assert res.usage == TokenUsage(prompt=20, completion=15, reasoning=9, total=35)
    assert res.model == "deepseek-reasoner" and not res.cached and res.latency_s > 0
    assert res.finish_reason == "stop"
    assert client.usage_total == res.usage and client.calls == 1
    (req,) = srv.requests
    assert (
        req["messages"] == MSGS
        and req["temperature"] == 0.2
        and req["max_tokens"] == 64
    )
    assert srv.paths == ["/v1/chat/completions"]


def test_usage_accumulates_and_callable_script() -> None:
    def needs_plate(req: dict) -> Response:  # conversation-aware entry
        ok = "plate" in req["messages"][-1]["content"]
        return Response("yes" if ok else "no", prompt_tokens=3, completion_tokens=1)

    with ScriptedServer([needs_plate, "plain string reply"]) as srv:
        client = LLMClient(cfg(srv.base_url))
        assert client.chat(MSGS).text == "yes"
        second = client.chat([{"role": "user", "content": "hi"}])
    assert second.text == "plain string reply" and second.reasoning is None
    assert (
        client.usage_total.prompt == 3 + 1
        and client.usage_total.total == 4 + second.usage.total
    )


def test_429_then_success_is_retried() -> None:
    with ScriptedServer([Response.error(429), Response("ok")]) as srv:
        res = LLMClient(cfg(srv.base_url)).chat(MSGS)
    assert res.text == "ok" and len(srv.requests) == 2


def test_429_exhausted() -> None:
    with (
        ScriptedServer(default=Response.error(429)) as srv,
        pytest.raises(LLMRateLimited, match="after 2 attempts"),
    ):
        LLMClient(cfg(srv.base_url, max_retries=1)).chat(MSGS)
    assert len(srv.requests) == 2


def test_500_exhausts_retries() -> None:
    with (
        ScriptedServer([Response.error(500)] * 3 + [Response("too late")]) as srv,
        pytest.raises(LLMServerError, match="after 3 attempts") as ei,
    ):
        LLMClient(cfg(srv.base_url, max_retries=2)).chat(MSGS)
    assert "HTTP 500" in str(ei.value)
    assert len(srv.requests) == 3


def test_401_is_auth_error_without_retry() -> None:
    with (
        ScriptedServer(api_key="the-right-key", default=Response("never")) as srv,
        pytest.raises(
            LLMAuthError, match=r"rejected the API key in \$OPENAI_API_KEY"
        ) as ei,
    ):
        LLMClient(cfg(srv.base_url)).chat(MSGS)
    assert len(srv.requests) == 1 and srv.auth_headers == [
        f"Bearer {SECRET}"
    ]  # key sent, no retry
    assert SECRET not in str(ei.value)
    with (
        ScriptedServer([Response.error(401), Response("x")]) as srv,
        pytest.raises(LLMAuthError),
    ):
        LLMClient(cfg(srv.base_url)).chat(MSGS)
    assert len(srv.requests) == 1


def test_unreachable_port_fails_fast() -> None:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    url = f"http://127.0.0.1:{port}/v1"
    t0 = time.perf_counter()
    with pytest.raises(LLMUnreachable, match="cannot reach") as ei:
        LLMClient(cfg(url, max_retries=1, timeout_s=0.5)).chat(MSGS)
    assert time.perf_counter() - t0 < 5
    assert (
        url in str(ei.value)
        and "OPENAI_BASE_URL" in str(ei.value)
        and "2 attempts" in str(ei.value)
    )


def test_timeout_is_unreachable() -> None:
    with (
        ScriptedServer(default=Response("slow", delay_s=1.0)) as srv,
        pytest.raises(LLMUnreachable, match="no answer within"),
    ):
        LLMClient(cfg(srv.base_url, max_retries=0, timeout_s=0.2)).chat(MSGS)


def test_not_configured(monkeypatch: pytest.MonkeyPatch) -> None:
    with pytest.raises(LLMNotConfigured, match="OPENAI_BASE_URL"):
        LLMClient(cfg(None)).chat(MSGS)
    monkeypatch.delenv("OPENAI_API_KEY")
    with pytest.raises(LLMNotConfigured, match=r"\$OPENAI_API_KEY"):
        LLMClient(cfg("https://api.deepseek.com/v1")).chat(MSGS)
    with pytest.raises(LLMNotConfigured, match="recording_path"):
        LLMClient(cfg(None, mode="replay"))
    # Local endpoints (vLLM/Ollama) work without a key.
    with ScriptedServer(["local"]) as srv:
        assert LLMClient(cfg(srv.base_url)).chat(MSGS).text == "local"


def test_cache_hit_makes_no_request(tmp_path: Path) -> None:
    with ScriptedServer([Response("first", reasoning="r", reasoning_tokens=2)]) as srv:
        client = LLMClient(cfg(srv.base_url, cache_dir=tmp_path / "cache"))
        a = client.chat(MSGS)
        b = client.chat(MSGS)
        assert len(srv.requests) == 1
        assert (
            LLMClient(cfg(srv.base_url, cache_dir=tmp_path / "cache")).chat(MSGS).cached
        )  # on disk
    assert not a.cached and b.cached
    assert (b.text, b.reasoning, b.usage) == (a.text, a.reasoning, a.usage)
    assert client.usage_live == a.usage and client.usage_total == a.usage + a.usage
    assert len(list((tmp_path / "cache").glob("*.json"))) == 1


def test_cache_key_covers_params(tmp_path: Path) -> None:
    with ScriptedServer(["a", "b"]) as srv:
        client = LLMClient(cfg(srv.base_url, cache_dir=tmp_path))
        assert client.chat(MSGS, temperature=0.0).text == "a"
        assert client.chat(MSGS, temperature=1.0).text == "b"
    assert len(srv.requests) == 2


def test_record_then_replay(tmp_path: Path) -> None:
    rec = tmp_path / "run.jsonl"
    script = [
        Response("one", reasoning="think 1"),
        Response("two"),
        Response("one again"),
    ]
    with ScriptedServer(script) as srv:
        client = LLMClient(cfg(srv.base_url, mode="record", recording_path=rec))
        recorded = [
            client.chat(MSGS),
            client.chat(MSGS, temperature=0.5),
            client.chat(MSGS),
        ]
    assert len(rec.read_text().splitlines()) == 3
    # Server gone, no base URL: everything comes from the recording, repeated requests in order.
    replay = LLMClient(cfg(None, mode="replay", recording_path=rec))
    replayed = [
        replay.chat(MSGS),
        replay.chat(MSGS, temperature=0.5),
        replay.chat(MSGS),
    ]
    for r, p in zip(recorded, replayed):
        assert (p.text, p.reasoning, p.usage, p.model, p.finish_reason) == (
            r.text,
            r.reasoning,
            r.usage,
            r.model,
            r.finish_reason,
        )
        assert p.cached
    assert replay.usage_total == client.usage_total
    with pytest.raises(LLMReplayMissing, match=r"recorded 2 time\(s\), this is call 3"):
        replay.chat(MSGS)


def test_replay_unknown_request(tmp_path: Path) -> None:
    rec = tmp_path / "empty.jsonl"
    rec.write_text("")
    client = LLMClient(cfg(None, mode="replay", recording_path=rec))
    msgs = [{"role": "user", "content": "Stack the three red blocks into a tower now"}]
    with pytest.raises(LLMReplayMissing, match="Stack the three red blocks"):
        client.chat(msgs)


def test_api_key_never_persisted(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    caplog.set_level(logging.DEBUG)
    config = cfg(
        None,
        cache_dir=tmp_path / "cache",
        mode="record",
        recording_path=tmp_path / "rec.jsonl",
    )
    with ScriptedServer(
        [Response.error(503), Response("fine", reasoning="ok")], api_key=SECRET
    ) as srv:
        config = config.model_copy(update={"base_url": srv.base_url})
        client = LLMClient(config)
        client.chat(MSGS)
        client.chat(MSGS)  # cache hit, recorded too
    files = list(tmp_path.rglob("*"))
    assert (
        any(f.suffix == ".json" for f in files) and (tmp_path / "rec.jsonl").is_file()
    )
    for f in files:
        if f.is_file():
            assert SECRET not in f.read_text()
    assert SECRET not in repr(config) and SECRET not in str(config)
    assert SECRET not in config.model_dump_json() and SECRET not in json.dumps(
        config.model_dump(), default=str
    )
    assert SECRET not in caplog.text and "retrying" in caplog.text
    assert config.api_key() == SECRET  # read from the env at call time


def test_from_env_precedence(monkeypatch: pytest.MonkeyPatch) -> None:
    c = LLMConfig.from_env()
    assert c.base_url is None and c.model == "deepseek-reasoner"
    monkeypatch.setenv("OPENAI_BASE_URL", "http://env-host:8000/v1")
    monkeypatch.setenv("HGEN_LLM_MODEL", "deepseek-chat")
    c = LLMConfig.from_env()
    assert (c.base_url, c.model) == ("http://env-host:8000/v1", "deepseek-chat")
    c = LLMConfig.from_env(
        base_url="http://flag:1/v1", model="gpt-4o", timeout_s=5, mode="replay"
    )
    assert (c.base_url, c.model, c.timeout_s, c.mode) == (
        "http://flag:1/v1",
        "gpt-4o",
        5,
        "replay",
    )
    assert (
        LLMConfig().backoff_delay(10) == LLMConfig().backoff_max_s
    )  # exponential, capped
    assert LLMConfig(backoff_s=1.0).backoff_delay(2) == 4.0


def test_server_serves_short_path_and_unknown_paths() -> None:
    import urllib.error
    import urllib.request

    with ScriptedServer(["short path ok"]) as srv:
        root = srv.base_url.removesuffix("/v1")
        res = LLMClient(cfg(root)).chat(MSGS)  # SDK posts to <base>/chat/completions
        assert res.text == "short path ok" and srv.paths == ["/chat/completions"]
        req = urllib.request.Request(root + "/nope", data=b"{}", method="POST")
        with pytest.raises(urllib.error.HTTPError) as ei:
            urllib.request.urlopen(req, timeout=2)
        assert ei.value.code == 404


def test_script_callable_error_is_reported() -> None:
    def broken(req: dict) -> str:
        raise KeyError("oops")

    with (
        ScriptedServer([broken]) as srv,
        pytest.raises(LLMServerError, match="KeyError"),
    ):
        LLMClient(cfg(srv.base_url, max_retries=0)).chat(MSGS)
    assert isinstance(srv.errors[0], KeyError)


def test_plan_workers_do_not_import_the_sdk():
    """The fork server imports the generation worker; the SDK (about 0.9 s to import) is for requests only."""
    import subprocess
    import sys

    code = "import sys, humanoidgen.generation.worker; print('openai' in sys.modules)"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "False"
