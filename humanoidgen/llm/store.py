"""Response cache (one JSON file per request key) and JSONL record/replay.

Only the request (model, messages, params) and the result are written, never headers or keys; both are
redacted (`redact.redact`) on the way out, since a prompt or an answer may quote the key. Pictures (image parts)
are written as PNG files beside the record (`images.stored`), the record keeping their sha256.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
import tempfile
from collections import defaultdict
from pathlib import Path
from typing import Any

from humanoidgen.llm.errors import LLMReplayMissing
from humanoidgen.llm.images import images_dir_of, stored
from humanoidgen.llm.redact import redact
from humanoidgen.llm.results import ChatResult

log = logging.getLogger(__name__)


def request_key(request: dict[str, Any]) -> str:
    """sha256 of the canonical JSON of the full request (model, messages, params)."""
    blob = json.dumps(
        request, sort_keys=True, ensure_ascii=False, separators=(",", ":"), default=str
    )
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()


def first_user_words(request: dict[str, Any], n: int = 8) -> str:
    """A human handle on a request for error messages."""
    for m in request.get("messages", []):
        if m.get("role") == "user":
            content = m.get("content")
            if isinstance(content, list):  # multimodal parts
                content = " ".join(
                    str(p.get("text", "")) for p in content if isinstance(p, dict)
                )
            words = str(content or "").split()
            return " ".join(words[:n]) + (" ..." if len(words) > n else "")
    return "<no user message>"


def _atomic_write(path: Path, text: str) -> None:
    # Write-then-rename so a crash or a concurrent reader never sees half a file.
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".json")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def _ends_mid_line(path: Path) -> bool:
    if not path.is_file() or path.stat().st_size == 0:
        return False
    with path.open("rb") as f:
        f.seek(-1, os.SEEK_END)
        return f.read(1) != b"\n"


class ResponseCache:
    def __init__(self, cache_dir: Path) -> None:
        self.dir = Path(cache_dir)

    def path(self, key: str) -> Path:
        return self.dir / f"{key}.json"

    def get(self, key: str) -> ChatResult | None:
        p = self.path(key)
        if not p.is_file():
            return None
        try:
            data = json.loads(p.read_text(encoding="utf-8"))
            return ChatResult.from_dict(data["result"], cached=True)
        except (ValueError, KeyError, TypeError):
            return None  # a corrupt entry is a miss, not a crash

    def put(self, key: str, request: dict[str, Any], result: ChatResult) -> None:
        request = stored(request, self.dir / "images")
        entry = redact({"key": key, "request": request, "result": result.to_dict()})
        _atomic_write(
            self.path(key), json.dumps(entry, ensure_ascii=False, indent=1, default=str)
        )


class Recorder:
    """Appends one JSON line per response."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)

    def append(self, key: str, request: dict[str, Any], result: ChatResult) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        request = stored(request, images_dir_of(self.path))
        line = json.dumps(
            redact({"key": key, "request": request, "result": result.to_dict()}),
            ensure_ascii=False,
            default=str,
        )
        # A recording cut short mid-line (an interrupted run) must not swallow this entry too.
        torn = _ends_mid_line(self.path)
        with self.path.open("a", encoding="utf-8") as f:
            f.write(("\n" if torn else "") + line + "\n")


class Replayer:
    """Serves recorded responses by request key; repeated identical requests get them in recorded order."""

    def __init__(self, path: Path) -> None:
        self.path = Path(path)
        self._entries: dict[str, list[dict[str, Any]]] = defaultdict(list)
        self._next: dict[str, int] = defaultdict(int)
        if self.path.is_file():
            for n, line in enumerate(self.path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
                if not line.strip():
                    continue
                try:
                    rec = json.loads(line)
                    self._entries[rec["key"]].append(rec["result"])
                except (ValueError, KeyError, TypeError):
                    # e.g. the last line of a recording cut short; its request, if asked for, is reported missing
                    log.warning("%s line %d is not a recorded response; skipped", self.path, n)

    def next(self, key: str, request: dict[str, Any]) -> ChatResult:
        entries = self._entries.get(key, [])
        i = self._next[key]
        if i >= len(entries):
            seen = (
                f" (recorded {len(entries)} time(s), this is call {i + 1})"
                if entries
                else ""
            )
            raise LLMReplayMissing(
                f"no recorded response for the request starting {first_user_words(request)!r}{seen} "
                f"in {self.path}; re-run in 'record' mode to capture it"
            )
        self._next[key] = i + 1
        return ChatResult.from_dict(entries[i], cached=True)
