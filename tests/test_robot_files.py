"""Robot file handling: locate, verify, download (against a real loopback HTTP server)."""

from __future__ import annotations

import functools
import http.server
import shutil
import socket
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
from typer.testing import CliRunner

from humanoidgen.assets import robot_files as rf
from humanoidgen.cli import assets_cmd

SHARED_ASSETS = Path(__file__).resolve().parents[2] / "shared" / "assets"
N_FILES = 95
TAMPERED = "meshes/L_index_proximal.STL"


def test_shared_assets_are_present():
    # Everything below serves these files; say plainly when they are missing instead of failing obscurely.
    assert rf.is_assets_root(SHARED_ASSETS), f"robot files not at {SHARED_ASSETS}"


class _Server:
    """A static file server on 127.0.0.1 that records the paths it was asked for."""

    def __init__(self, directory: Path) -> None:
        self.requests: list[str] = []
        requests = self.requests

        class Handler(http.server.SimpleHTTPRequestHandler):
            def do_GET(self) -> None:  # noqa: N802 (http.server naming)
                requests.append(self.path)
                super().do_GET()

            def log_message(self, *args: object) -> None:  # keep test output quiet
                pass

        handler = functools.partial(Handler, directory=str(directory))
        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.httpd.server_address[1]}/{rf.ROBOT_DIR_NAME}"


@contextmanager
def serve(directory: Path) -> Iterator[_Server]:
    server = _Server(directory)
    server.thread.start()
    try:
        yield server
    finally:
        server.httpd.shutdown()
        server.httpd.server_close()


def part_files(root: Path) -> list[Path]:
    return list(root.rglob(f"*{rf.PART_SUFFIX}"))


def make_root(path: Path) -> Path:
    """A minimal folder that counts as an assets root."""
    (path / "h1_2").mkdir(parents=True)
    (path / "h1_2" / "h1_2.xml").write_text("<mujoco/>")
    return path


@pytest.fixture(autouse=True)
def clean_env(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    # Never read or write the real user cache from tests.
    for var in (rf.ENV_ASSETS, rf.ENV_CACHE, "XDG_CACHE_HOME"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))


@pytest.fixture(scope="module")
def server() -> Iterator[_Server]:
    with serve(SHARED_ASSETS) as s:
        yield s


@pytest.fixture(scope="module")
def fetched(server: _Server, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The one full download of the session (49 MB over loopback)."""
    dest = tmp_path_factory.mktemp("fetched")
    assert rf.fetch(dest, base_url=server.base_url, progress=False) == dest
    return dest


def copy_of(fetched: Path, tmp_path: Path, without: str | None = None) -> Path:
    dest = tmp_path / "dest"
    shutil.copytree(fetched, dest)
    if without:
        (dest / "h1_2" / without).unlink()
    return dest


# --------------------------------------------------------------------------- sums


def test_expected_sums_match_the_packaged_list() -> None:
    sums = rf.expected_sums()
    assert len(sums) == N_FILES
    assert "h1_2.xml" in sums and TAMPERED in sums
    assert all(not name.startswith("./") for name in sums)
    assert all(len(d) == 64 for d in sums.values())


@pytest.mark.parametrize("name", ["../evil", "./../evil", "meshes/../../x", "/etc/passwd", "a\\..\\b"])
def test_parse_sums_rejects_path_traversal(name: str) -> None:
    with pytest.raises(ValueError, match="unsafe"):
        rf.parse_sums(f"{'0' * 64}  {name}\n")


def test_parse_sums_rejects_garbage() -> None:
    with pytest.raises(ValueError, match="bad line 1"):
        rf.parse_sums("not-a-hash  ./x\n")


def test_verify_reports_missing_and_mismatched(tmp_path: Path) -> None:
    (tmp_path / "a").write_bytes(b"a")
    (tmp_path / "b").write_bytes(b"tampered")
    sums = rf.parse_sums(
        "ca978112ca1bbdcafac231b39a23dc4da786eff8147c4e72b9807785afee48bb  ./a\n"
        f"{'0' * 64}  ./b\n{'1' * 64}  ./c\n"
    )
    report = rf.verify(tmp_path, sums)
    assert (report.ok, report.missing, report.mismatched) == (["a"], ["c"], ["b"])
    assert not report.is_complete


def test_shared_assets_verify_complete() -> None:
    assert rf.verify(SHARED_ASSETS / "h1_2").is_complete


# --------------------------------------------------------------------------- fetch


def test_fetch_downloads_and_verifies_every_file(fetched: Path, server: _Server) -> None:
    report = rf.verify(fetched / "h1_2")
    assert report.is_complete
    assert len(report.ok) == N_FILES
    assert not part_files(fetched)
    assert (fetched / "h1_2" / "h1_2.xml").read_bytes() == (
        SHARED_ASSETS / "h1_2" / "h1_2.xml"
    ).read_bytes()


def test_second_fetch_downloads_nothing(fetched: Path, server: _Server) -> None:
    before = len(server.requests)
    mtimes = {p: p.stat().st_mtime_ns for p in fetched.rglob("*") if p.is_file()}
    rf.fetch(fetched, base_url=server.base_url, progress=False)
    assert len(server.requests) == before
    assert {p: p.stat().st_mtime_ns for p in fetched.rglob("*") if p.is_file()} == mtimes


def test_fetch_resumes_missing_and_repairs_corrupt(
    fetched: Path, server: _Server, tmp_path: Path
) -> None:
    dest = copy_of(fetched, tmp_path, without="h1_2.xml")
    (dest / "h1_2" / TAMPERED).write_bytes(b"truncated")
    (dest / "h1_2" / "meshes" / f".x{rf.PART_SUFFIX}").write_bytes(b"leftover of a kill")
    before = len(server.requests)
    rf.fetch(dest, base_url=server.base_url, progress=False)
    assert sorted(server.requests[before:]) == ["/h1_2/h1_2.xml", f"/h1_2/{TAMPERED}"]
    assert rf.verify(dest / "h1_2").is_complete
    assert not part_files(dest)


def test_tampered_file_is_rejected_and_nothing_is_left(fetched: Path, tmp_path: Path) -> None:
    # The mirror serves only the tampered mesh; the destination already has every other file.
    mirror = tmp_path / "mirror"
    (mirror / "h1_2" / "meshes").mkdir(parents=True)
    data = bytearray((SHARED_ASSETS / "h1_2" / TAMPERED).read_bytes())
    data[100] ^= 0xFF
    (mirror / "h1_2" / TAMPERED).write_bytes(bytes(data))
    dest = copy_of(fetched, tmp_path, without=TAMPERED)

    with serve(mirror) as bad, pytest.raises(rf.ChecksumError) as err:
        rf.fetch(dest, base_url=bad.base_url, progress=False)

    message = str(err.value)
    assert TAMPERED in message
    assert rf.expected_sums()[TAMPERED] in message
    assert rf.sha256_file(mirror / "h1_2" / TAMPERED) in message
    assert not (dest / "h1_2" / TAMPERED).exists()
    assert not part_files(dest)


def test_http_404_is_a_fetch_error(server: _Server, tmp_path: Path) -> None:
    with pytest.raises(rf.FetchError, match="404") as err:
        rf.fetch(tmp_path, base_url=server.base_url + "/nowhere", progress=False)
    assert "--base-url" in str(err.value)
    assert not part_files(tmp_path)


def test_unreachable_host_is_a_fetch_error(tmp_path: Path) -> None:
    with socket.socket() as s:  # a port that was free a moment ago: connection refused
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    url = f"http://127.0.0.1:{port}/h1_2"
    with pytest.raises(rf.FetchError) as err:
        rf.fetch(tmp_path, base_url=url, progress=False, timeout=5)
    assert url in str(err.value) and "--base-url" in str(err.value)
    assert not part_files(tmp_path)


def test_interrupt_mid_download_leaves_no_temp_file(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    class Response:
        def __init__(self) -> None:
            self.calls = 0

        def __enter__(self) -> Response:
            return self

        def __exit__(self, *exc: object) -> None:
            pass

        def read(self, n: int) -> bytes:
            self.calls += 1
            if self.calls > 1:
                raise KeyboardInterrupt
            return b"x" * n

    monkeypatch.setattr(rf.urllib.request, "urlopen", lambda url, timeout: Response())
    with pytest.raises(KeyboardInterrupt):
        rf.fetch(tmp_path, base_url="http://example.invalid/h1_2", progress=False)
    assert not [p for p in tmp_path.rglob("*") if p.is_file()]


# --------------------------------------------------------------------------- resolve


def test_hgen_assets_wins(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    explicit = make_root(tmp_path / "explicit")
    monkeypatch.setenv(rf.ENV_ASSETS, str(explicit))
    monkeypatch.setenv(rf.ENV_CACHE, str(make_root(tmp_path / "cache")))
    assert rf.resolve_assets_root() == explicit
    assert rf.robot_mjcf_path() == explicit / "h1_2" / "h1_2.xml"


def test_invalid_hgen_assets_is_an_error(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv(rf.ENV_ASSETS, str(tmp_path / "nothing-here"))
    with pytest.raises(rf.AssetsNotFoundError, match=rf.ENV_ASSETS):
        rf.resolve_assets_root()


def test_hgen_cache_used_when_valid(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    cache = make_root(tmp_path / "cache")
    monkeypatch.setenv(rf.ENV_CACHE, str(cache))
    assert rf.cache_dir() == cache
    assert rf.resolve_assets_root() == cache


def test_cache_dir_defaults(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    assert rf.cache_dir() == tmp_path / "home" / ".cache" / "humanoidgen" / "assets"
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert rf.cache_dir() == tmp_path / "xdg" / "humanoidgen" / "assets"


def test_falls_back_to_shared_beside_checkout(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv(rf.ENV_CACHE, str(tmp_path / "empty-cache"))
    assert rf.resolve_assets_root() == SHARED_ASSETS
    assert rf.robot_mjcf_path().is_file()


def test_nothing_found_says_how_to_fix(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv(rf.ENV_CACHE, str(tmp_path / "empty-cache"))
    monkeypatch.setattr(rf, "checkout_assets_dir", lambda: tmp_path / "no-shared")
    with pytest.raises(rf.AssetsNotFoundError) as err:
        rf.resolve_assets_root()
    message = str(err.value)
    assert "hgen assets fetch" in message
    assert str(tmp_path / "empty-cache") in message and str(tmp_path / "no-shared") in message
    assert isinstance(err.value, RuntimeError)


# --------------------------------------------------------------------------- CLI

runner = CliRunner()


def test_cli_where_complete(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(rf.ENV_ASSETS, str(SHARED_ASSETS))
    result = runner.invoke(assets_cmd.app, ["where"])
    assert result.exit_code == 0, result.output
    assert str(SHARED_ASSETS) in result.output
    assert f"all {N_FILES} files verified" in result.output


def test_cli_where_incomplete_lists_files(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv(rf.ENV_ASSETS, str(make_root(tmp_path / "partial")))
    result = runner.invoke(assets_cmd.app, ["where"])
    assert result.exit_code == 1
    assert "mismatched: h1_2.xml" in result.output
    assert f"missing:    {TAMPERED}" in result.output


def test_cli_where_not_found(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv(rf.ENV_CACHE, str(tmp_path / "empty-cache"))
    monkeypatch.setattr(rf, "checkout_assets_dir", lambda: tmp_path / "no-shared")
    result = runner.invoke(assets_cmd.app, ["where"])
    assert result.exit_code == 1
    assert "hgen assets fetch" in result.output
    assert "Traceback" not in result.output


def test_cli_fetch_with_base_url(fetched: Path, server: _Server, tmp_path: Path) -> None:
    dest = copy_of(fetched, tmp_path, without="scene.xml")
    before = len(server.requests)
    result = runner.invoke(
        assets_cmd.app, ["fetch", "--dest", str(dest), "--base-url", server.base_url, "--no-progress"]
    )
    assert result.exit_code == 0, result.output
    assert server.requests[before:] == ["/h1_2/scene.xml"]
    assert str(dest / "h1_2") in result.output
    assert f"all {N_FILES} verified" in result.output


def test_cli_fetch_error_is_red_message_and_exit_1(tmp_path: Path) -> None:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    result = runner.invoke(
        assets_cmd.app,
        ["fetch", "--dest", str(tmp_path / "d"), "--base-url", f"http://127.0.0.1:{port}/h1_2"],
    )
    assert result.exit_code == 1
    assert "could not download" in result.output
    assert "Traceback" not in result.output
    assert not isinstance(result.exception, rf.AssetsError)  # handled, not raised
