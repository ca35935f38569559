"""The hostile plan battery: the scripts in this folder, their headers, and how placeholders are filled in.

Used by `tests/test_hostile.py` (through the real entry points, behind the plan worker) and by
`validate_unsandboxed.py` (each payload run bare, to show it really does something). Each script starts with

    # attempts: <what it tries, and by which route>
    # effect: file|exec|fork|socket|env|signal|hang|memory|output|parser|cheat|other
    # expect: failure (default) | contained   (contained: the episode may report success, e.g. a teleport)
    # needs: planner | worker                 (optional: what it needs to show its effect when run bare)

Placeholders (filled in by `render`):
    @@MARKER_DIR@@    a fresh, empty directory; every file a payload creates goes here
                      (`@@MARKER_DIR@@/../canary.txt` is the canary file payloads try to change or delete)
    @@PORT@@          a loopback TCP listener on 127.0.0.1 that counts connections
    @@HARNESS_PID@@   the process that must not be signalled, traced or read (the test process)
    @@HARNESS_PPID@@  the process that started it; payloads never touch it
    @@SHM_PATH@@      a /dev/shm path payloads try to create
    @@REPEAT:<n>:<text>@@   <text> (\\n = newline) repeated n times: parser bombs stay small on disk
    @@NUL@@, @@INVALID_UTF8@@   a NUL character, a byte that is not UTF-8 (0xff)
"""

from __future__ import annotations

import re
import secrets as _secrets
import socket
import threading
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
EFFECTS = ("file", "exec", "fork", "socket", "env", "signal", "hang", "memory", "output", "parser", "cheat", "other")
SECRET_VARS = ("OPENAI_API_KEY", "HGEN_TEST_SECRET")
_HEADER = re.compile(r"^#\s*(attempts|effect|expect|needs):\s*(.*?)\s*$")
_REPEAT = re.compile(r"@@REPEAT:(\d+):(.*?)@@")


@dataclass(frozen=True)
class Script:
    path: Path
    attempts: str
    effect: str
    expect: str = "failure"  # "contained": success is allowed (a physical cheat is not an escape)
    needs: str = ""

    @property
    def name(self) -> str:
        return self.path.stem

    @property
    def text(self) -> str:
        return self.path.read_text()


def scripts() -> list[Script]:
    out = []
    for path in sorted(HERE.glob("[0-9][0-9][0-9]_*.py")):
        head = {}
        for line in path.read_text().splitlines():
            m = _HEADER.match(line)
            if not m:
                break
            head[m.group(1)] = m.group(2)
        if head.get("effect") not in EFFECTS or not head.get("attempts"):
            raise ValueError(f"{path.name}: needs '# attempts:' and '# effect: <one of {EFFECTS}>' header lines")
        out.append(Script(path, head["attempts"], head["effect"], head.get("expect", "failure"), head.get("needs", "")))
    return out


def render(text: str, *, marker_dir: str, port: int, harness_pid: int, harness_ppid: int, shm_path: str) -> bytes:
    """The plan file's bytes for one run (surrogateescape turns @@INVALID_UTF8@@ into a raw 0xff byte)."""
    text = _REPEAT.sub(lambda m: m.group(2).replace("\\n", "\n") * int(m.group(1)), text)
    for key, value in (("@@MARKER_DIR@@", marker_dir), ("@@PORT@@", str(port)), ("@@HARNESS_PID@@", str(harness_pid)),
                       ("@@HARNESS_PPID@@", str(harness_ppid)), ("@@SHM_PATH@@", shm_path), ("@@NUL@@", "\0"),
                       ("@@INVALID_UTF8@@", "\udcff")):
        text = text.replace(key, value)
    return text.encode("utf-8", "surrogateescape")


def new_secret() -> str:
    """Shaped like an OpenAI key (so key-shaped scanners and redaction patterns see it as one)."""
    return "sk-hgencanary-" + _secrets.token_hex(16)


def secret_forms(secret: str) -> list[str]:
    """What a leak of `secret` may look like: itself, reversed, hex (payloads encode to get past redaction)."""
    return [secret, secret[::-1], secret.encode().hex()]


def shm_path() -> str:
    return f"/dev/shm/hgen-hostile-{_secrets.token_hex(6)}"


class Listener:
    """A TCP listener on 127.0.0.1:<free port> in a daemon thread: counts connections, keeps what they send.
    Bounded (1000 connections, 64 KiB each) and stopped by `close()`."""

    def __init__(self) -> None:
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(16)
        self.sock.settimeout(0.2)
        self.port: int = self.sock.getsockname()[1]
        self.count, self.data = 0, b""
        self._stop = threading.Event()
        self.thread = threading.Thread(target=self._serve, name="hostile-listener", daemon=True)
        self.thread.start()

    def _serve(self) -> None:
        while not self._stop.is_set() and self.count < 1000:
            try:
                conn, _ = self.sock.accept()
            except OSError:  # timeout, or closed
                continue
            self.count += 1
            conn.settimeout(0.5)
            try:
                self.data += conn.recv(65536)
            except OSError:
                pass
            conn.close()

    def close(self) -> None:
        self._stop.set()
        self.thread.join(2)
        self.sock.close()


def processes_mentioning(text: str) -> list[int]:
    """Pids of live processes whose command line contains `text` (e.g. the marker dir)."""
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                if text.encode() in (d / "cmdline").read_bytes():
                    out.append(int(d.name))
            except OSError:
                pass
    return out
