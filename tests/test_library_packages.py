"""The object library's package kinds (objects/imported/package_kinds.py): the download commands (built without
network), and a fetch from a Debian package made here whose catalogue zip holds a mug: the files are checked
against the manifest's sha256 (a mismatch imports nothing) and imported."""

from __future__ import annotations

import hashlib
import io
import lzma
import sys
import tarfile
import zipfile
from pathlib import Path

import pydantic
import pytest
import yaml

from humanoidgen.objects.imported import fetch
from humanoidgen.objects.imported.package_kinds import KINDS
from meshes_for_tests import mug

CATALOGUE = "usr/share/hgen-test/furniture/Kitchen.sh3f"


def test_the_download_commands_are_pinned_and_need_no_network(tmp_path):
    assert KINDS["deb"].command("sweethome3d-furniture", "1.8-1") == ["apt-get", "download", "sweethome3d-furniture=1.8-1"]
    pip = KINDS["pip"].command("robosuite", "1.5.2")
    assert pip[:4] == [sys.executable, "-m", "pip", "download"] and "--no-deps" in pip and "robosuite==1.5.2" in pip
    # what each kind finds in the cache folder: apt writes an epoch's colon as %3a
    (tmp_path / "foo_2%3a1.0-3_all.deb").write_bytes(b"")
    (tmp_path / "foo_bar-1.0-py3-none-any.whl").write_bytes(b"")
    assert KINDS["deb"].cached("foo", "2:1.0-3", tmp_path) == tmp_path / "foo_2%3a1.0-3_all.deb"
    assert KINDS["deb"].cached("foo", "1.0-3", tmp_path) is None
    assert KINDS["pip"].cached("foo-bar", "1.0", tmp_path) == tmp_path / "foo_bar-1.0-py3-none-any.whl"
    assert KINDS["deb"].pin("foo", "1.0-3") == "foo=1.0-3 (deb)" and KINDS["pip"].pin("foo", "1.0") == "foo==1.0"


def _ar(members: dict[str, bytes]) -> bytes:
    out = [b"!<arch>\n"]
    for name, body in members.items():
        out.append(f"{name + '/':<16}{0:<12}{0:<6}{0:<6}{'100644':<8}{len(body):<10}`\n".encode())
        out.append(body + (b"\n" if len(body) % 2 else b""))
    return b"".join(out)


def _fake_deb(folder: Path, radius: float = 0.04) -> tuple[Path, bytes]:
    """A .deb (ar: debian-binary, control, data.tar.xz) with a SweetHome3D-like catalogue zip inside."""
    cat = io.BytesIO()
    with zipfile.ZipFile(cat, "w") as zf:
        zf.writestr("kitchen/mug/mug.obj", mug(radius=radius).export(file_type="obj"))
        zf.writestr("kitchen/mug/LICENSE.txt", "CC0, made by the test")
        zf.writestr("kitchen/other/skip.obj", "not taken: outside the prefix")
    data = io.BytesIO()
    with tarfile.open(fileobj=data, mode="w") as tf:
        for name, body in ((f"./{CATALOGUE}", cat.getvalue()), ("./usr/share/doc/hgen-test/copyright", b"CC0")):
            info = tarfile.TarInfo(name)
            info.size = len(body)
            tf.addfile(info, io.BytesIO(body))
    folder.mkdir(parents=True, exist_ok=True)
    deb = folder / "hgen-test-furniture_1.0-1_all.deb"
    deb.write_bytes(_ar({"debian-binary": b"2.0\n", "control.tar.xz": lzma.compress(b""),
                         "data.tar.xz": lzma.compress(data.getvalue())}))
    return deb, cat.getvalue()


def _manifest(tmp_path: Path, digest: str, kind: str = "deb") -> Path:
    path = tmp_path / "library.yaml"
    path.write_text(yaml.safe_dump({
        "packages": {"hgen-test-furniture": {"version": "1.0-1", "kind": kind}},
        "sources": {"test": {"licence": "CC0-1.0", "permissive": True, "attribution": "made by the test"}},
        "models": [{"name": "deb_mug", "family": "cup", "type_id": 200, "package": "hgen-test-furniture",
                    "file": f"{CATALOGUE}/kitchen/mug/mug.obj", "sha256": digest, "scale": 1.0, "up": "z",
                    "source": "test",
                    "extract": [{"package": "hgen-test-furniture", "archive": CATALOGUE, "prefix": "kitchen/mug/"}]}]}))
    return path


def test_fetch_takes_a_model_from_a_catalogue_inside_a_debian_package(tmp_path, monkeypatch):
    cache = tmp_path / "packages"
    _, cat = _fake_deb(cache)
    with zipfile.ZipFile(io.BytesIO(cat)) as zf:
        lines = sorted(f"{CATALOGUE}/{n} {hashlib.sha256(zf.read(n)).hexdigest()}"
                       for n in ("kitchen/mug/mug.obj", "kitchen/mug/LICENSE.txt"))
    digest = hashlib.sha256("\n".join(lines).encode()).hexdigest()
    monkeypatch.setattr(fetch, "MANIFEST", _manifest(tmp_path, digest))
    monkeypatch.setenv("HGEN_COLLISION_CACHE", str(tmp_path / "coacd"))
    report = fetch.fetch_library(tmp_path / "assets", cache, log=lambda s: None)
    assert report.imported == ["deb_mug"] and not report.failed
    info = yaml.safe_load((tmp_path / "assets" / "object_library" / "cup" / "deb_mug" / "model.yaml").read_text())
    assert info["source"]["package"] == "hgen-test-furniture=1.0-1 (deb)" and info["source"]["sha256"] == digest


def test_a_debian_packages_file_that_is_not_the_manifests_is_refused(tmp_path, monkeypatch):
    cache = tmp_path / "packages"
    _fake_deb(cache, radius=0.05)  # not the mug the digest below was taken of
    monkeypatch.setattr(fetch, "MANIFEST", _manifest(tmp_path, "0" * 64))
    monkeypatch.setenv("HGEN_COLLISION_CACHE", str(tmp_path / "coacd"))
    bad = fetch.fetch_library(tmp_path / "assets", cache, log=lambda s: None)
    assert bad.imported == [] and "sha256" in bad.failed[0]
    assert not (tmp_path / "assets" / "object_library" / "cup" / "deb_mug").exists()


def test_a_package_of_an_unknown_kind_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(fetch, "MANIFEST", _manifest(tmp_path, "0" * 64, kind="conda"))
    with pytest.raises(pydantic.ValidationError, match="unknown package kind"):
        fetch.manifest()


def test_a_missing_download_tool_is_a_fetch_error(tmp_path, monkeypatch):
    monkeypatch.setattr(fetch, "MANIFEST", _manifest(tmp_path, "0" * 64))
    monkeypatch.setattr(type(KINDS["deb"]), "command", lambda self, p, v: ["hgen-no-such-apt-get", "download"])
    report = fetch.fetch_library(tmp_path / "assets", tmp_path / "packages", log=lambda s: None)
    # the package's models fail with the reason; the fetch goes on with the other packages' models
    assert report.imported == [] and len(report.failed) == 1 and "not on this machine" in report.failed[0]
