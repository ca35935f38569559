"""`hgen assets import`: a mesh made here becomes a model folder that a scene builds and simulates (resting on the
table), in every mesh format; the annotations are transferred with confidences; bad inputs get one line, exit 1
and leave nothing behind."""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml
from typer.testing import CliRunner

from humanoidgen.cli.main import app
from humanoidgen.objects.family_data import ENV_FAMILIES_PATH
from humanoidgen.objects.imported.collision import ENV_COLLISION_CACHE
from meshes_for_tests import bottle, mug

runner = CliRunner()


@pytest.fixture(autouse=True, scope="module")
def no_fetched_library():
    """These tests count the type_ids and draws of the models they import: a library fetched under the assets
    root (`hgen assets fetch --objects`) is kept out of sight."""
    mp = pytest.MonkeyPatch()
    mp.setattr("humanoidgen.objects.imported.model_file.library_dir", lambda: None)
    yield
    mp.undo()


@pytest.fixture(scope="module")
def collision_cache(tmp_path_factory) -> Path:
    """One CoACD cache for the module: the same mug is decomposed once (about 20 s on 2 cores)."""
    path = tmp_path_factory.mktemp("collision")
    old = os.environ.get(ENV_COLLISION_CACHE)
    os.environ[ENV_COLLISION_CACHE] = str(path)
    yield path
    if old is None:
        os.environ.pop(ENV_COLLISION_CACHE, None)
    else:
        os.environ[ENV_COLLISION_CACHE] = old


@pytest.fixture(scope="module")
def imported_mug(tmp_path_factory, collision_cache) -> Path:
    """`hgen assets import mug.obj --family cup --name my_mug --out MODELS` (its handle on +x in the file)."""
    work = tmp_path_factory.mktemp("mug")
    mug().export(work / "mug.obj")
    r = runner.invoke(app, ["assets", "import", str(work / "mug.obj"), "--family", "cup", "--name", "my_mug",
                            "--out", str(work / "models")])
    assert r.exit_code == 0, r.output
    assert "imported cup model 'my_mug' (type_id 100)" in r.output
    return work / "models"


def test_the_folder_holds_the_model_its_annotations_and_a_picture(imported_mug):
    folder = imported_mug / "cup" / "my_mug"
    assert sorted(p.name for p in folder.iterdir()) == ["annotations.yaml", "meshes.npz", "model.yaml",
                                                         "preview.png", "transfer.yaml"]
    info = yaml.safe_load((folder / "model.yaml").read_text())
    assert info["family"] == "cup" and info["type_id"] == 100 and info["links"][0]["collision_parts"] >= 2
    transfer = yaml.safe_load((folder / "transfer.yaml").read_text())
    conf = {p["name"]: p["confidence"] for p in transfer["points"]}
    assert set(conf) == {"side", "rim", "lip", "storage", "side_right", "handle_left", "center"}
    assert min(conf.values()) >= 0.5, conf
    ann = yaml.safe_load((folder / "annotations.yaml").read_text())
    pts = {p["name"]: np.array(p["position"]) for p in ann["points"]}
    # the handle was on +x in the file: the import turned it onto the family's +y (left)
    assert pts["handle_left"][1] > 0.02 and abs(pts["handle_left"][0]) < 0.01
    axis = pts["storage"][:2]  # the vertical axis (the frame is centred on the box, handle and all)
    assert abs(np.linalg.norm(pts["side"][:2] - axis) - 0.04) < 0.002  # on the body's outer surface
    assert pts["rim"][2] == pytest.approx(ann["bbox_max"][2], abs=0.003)
    # a wrap grasp's width is the body's diameter from either side, the handle's side too (not out to the handle)
    widths = {o["point"]: o["width"] for o in ann["operations"] if o["operation"] == "grasp"}
    assert widths == {"side": pytest.approx(0.08, abs=0.003), "side_right": pytest.approx(0.08, abs=0.003)}


def test_an_imported_mug_rests_on_the_table_in_a_scene(imported_mug, monkeypatch):
    import mujoco

    from humanoidgen.objects import library
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.layout import TABLE_TOP_Z
    from humanoidgen.sim.scene import SceneBuilder

    monkeypatch.setenv(ENV_FAMILIES_PATH, str(imported_mug))
    assert library.model_named("cup", "my_mug").type_id == 100
    b = SceneBuilder()
    obj = library.add_object(b, "cup", type_id=100, pos=(-0.30, 0.05))
    env = HumanoidEnv(b.build())
    bid = env.model.body(obj.body).id
    z0 = float(env.data.xpos[bid][2])
    for _ in range(500):  # 1 s
        mujoco.mj_step(env.model, env.data)
    pos, R = env.data.xpos[bid], env.data.xmat[bid].reshape(3, 3)
    assert abs(pos[2] - z0) < 0.005, (pos, z0)  # neither sank into the table nor fell
    assert R[2, 2] > 0.999  # still upright
    assert abs(pos[0] + 0.30) < 0.005 and abs(pos[1] - 0.05) < 0.005
    ann = obj.annotations
    assert ann.bbox_min[2] + pos[2] == pytest.approx(TABLE_TOP_Z, abs=0.004)


@pytest.mark.parametrize("suffix,args", [(".stl", ["--scale", "0.001"]), (".ply", []), (".glb", ["--up", "z"]),
                                         (".msh", [])])
def test_every_mesh_format_imports(tmp_path, collision_cache, suffix, args):
    from humanoidgen.objects.imported.msh_file import write_msh

    mesh = bottle()
    if suffix == ".stl":
        mesh.apply_scale(1000.0)  # millimetres
    if suffix == ".msh":
        write_msh(mesh, tmp_path / "b.msh")  # MuJoCo's binary mesh: trimesh does not write it
    else:
        mesh.export(tmp_path / f"b{suffix}")
    r = runner.invoke(app, ["assets", "import", str(tmp_path / f"b{suffix}"), "--family", "bottle", "--out",
                            str(tmp_path / "models"), "--no-preview", *args])
    assert r.exit_code == 0, r.output
    ann = yaml.safe_load((tmp_path / "models" / "bottle" / "b" / "annotations.yaml").read_text())
    height = ann["bbox_max"][2] - ann["bbox_min"][2]
    assert height == pytest.approx(0.22, abs=1e-3)
    widths = [o["width"] for o in ann["operations"] if o.get("width")]
    assert widths and all(w == pytest.approx(0.07, abs=0.004) for w in widths)


def test_a_low_confidence_point_is_listed_for_a_manual_fix_and_the_fix_is_used(tmp_path, collision_cache,
                                                                              monkeypatch):
    mug(handle=False).export(tmp_path / "beaker.obj")  # a cup without a handle: its handle point is a guess
    r = runner.invoke(app, ["assets", "import", str(tmp_path / "beaker.obj"), "--family", "cup", "--out",
                            str(tmp_path / "models"), "--no-preview"])
    assert r.exit_code == 0, r.output
    assert "warning: handle_left: confidence" in r.output
    override = tmp_path / "models" / "cup" / "beaker" / "annotations.override.yaml"
    data = yaml.safe_load(override.read_text())
    assert list(data["points"]) == ["handle_left"]
    override.write_text("points:\n  handle_left: [0.0, 0.05, 0.0]\n")
    monkeypatch.setenv(ENV_FAMILIES_PATH, str(tmp_path / "models"))
    from humanoidgen.objects import library

    m = library.model_named("cup", "beaker")
    assert library.annotations("cup", m.type_id).point("handle_left").position == (0.0, 0.05, 0.0)


def _bad(tmp_path: Path, name: str, content) -> Path:
    p = tmp_path / name
    if isinstance(content, trimesh.Trimesh):
        content.export(p)
    else:
        p.write_bytes(content if isinstance(content, bytes) else content.encode())
    return p


@pytest.mark.parametrize("name,content,family,extra,message", [
    ("corrupt.glb", b"glTF\x02\x00\x00\x00garbage", "cup", [], "not a readable glTF file"),
    ("empty.obj", "", "cup", [], "no mesh with faces"),
    ("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n", "cup", [], "no mesh with faces"),
    ("flat.obj", "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0.1 0.1 0\nf 1 2 3\nf 2 4 3\n", "plate", [], "flat or degenerate"),
    ("open.obj", None, "cup", [], "not watertight"),
    ("huge.obj", None, "cup", [], "would be 40 m across"),
    ("mug.obj", None, "teapot", [], "unknown family 'teapot'"),
    ("notes.txt", "a mug", "cup", [], "unknown file type '.txt'"),
    ("cut.msh", b"\x08\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x0c\x00\x00\x00" + b"\x00" * 40, "cube", [],
     "not a MuJoCo .msh file"),
    ("rigid.urdf", None, "drawer", [], "has no revolute or prismatic joint"),
    ("missing.urdf", None, "drawer", [], "mesh gone.obj is missing"),
    # radians written in an MJCF, whose angles are degrees: a lid that would open 1.7 deg
    ("radians.xml", None, "box", [], 'its lid turns 1.7 deg; a box\'s opens at least 45 deg (an MJCF\'s angles are '
                                     'degrees unless <compiler angle="radian"/>)'),
])
def test_a_bad_input_gets_one_line_and_leaves_nothing(tmp_path, collision_cache, name, content, family, extra,
                                                      message):
    if name == "open.obj":
        m = trimesh.creation.box(extents=(0.05, 0.05, 0.05))
        content = trimesh.Trimesh(m.vertices, m.faces[:-2])
    elif name == "huge.obj":
        content = trimesh.creation.box(extents=(40.0, 10.0, 10.0))
    elif name == "mug.obj":
        content = mug()
    elif name == "rigid.urdf":
        trimesh.creation.box(extents=(0.1, 0.1, 0.1)).export(tmp_path / "box.obj")
        content = ('<robot name="r"><link name="a"><visual><geometry><mesh filename="box.obj"/></geometry>'
                   '</visual></link></robot>')
    elif name == "missing.urdf":
        content = ('<robot name="r"><link name="a"><visual><geometry><mesh filename="gone.obj"/></geometry>'
                   '</visual></link><link name="b"/><joint name="j" type="prismatic"><parent link="a"/>'
                   '<child link="b"/><limit lower="0" upper="0.1"/></joint></robot>')
    elif name == "radians.xml":
        content = _BOX_WITH_HANDLE.replace('range="0 100"', 'range="0 1.7"')
    path = _bad(tmp_path, name, content)
    out = tmp_path / "models"
    r = runner.invoke(app, ["assets", "import", str(path), "--family", family, "--out", str(out), "--no-preview",
                            *extra])
    assert r.exit_code == 1, r.output
    lines = [line for line in r.output.splitlines() if line.strip()]
    assert len(lines) == 1 and message in lines[0], r.output
    assert not out.exists(), sorted(out.rglob("*"))


def test_a_urdf_drawer_imports_with_its_prismatic_joint_and_opens(tmp_path, collision_cache, monkeypatch):
    """A two-link URDF (case + drawer on a prismatic joint, as PartNet-Mobility ships them), sliding out along
    +y in the file: the import turns it to slide toward the robot (-x), and the drawer's points move with it."""
    from humanoidgen.objects import library
    from humanoidgen.objects.articulated import set_openness
    from humanoidgen.objects.queries import get_point_in_env
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder
    from meshes_for_tests import drawer_urdf

    urdf = drawer_urdf(tmp_path / "src", slide_axis="0 1 0")
    r = runner.invoke(app, ["assets", "import", str(urdf), "--family", "drawer", "--name", "made_drawer", "--out",
                            str(tmp_path / "models"), "--no-preview"])
    assert r.exit_code == 0, r.output
    monkeypatch.setenv(ENV_FAMILIES_PATH, str(tmp_path / "models"))
    m = library.model_named("drawer", "made_drawer")
    ann = library.annotations("drawer", m.type_id)
    assert ann.articulation is not None and ann.articulation.open == pytest.approx(0.2)
    assert ann.point("handle").part == "drawer"
    b = SceneBuilder()
    obj = library.add_object(b, "drawer", type_id=m.type_id, pos=(-0.05, 0.30))
    env = HumanoidEnv(b.build())
    closed = get_point_in_env(env, "handle", "drawer", 0)
    set_openness(env.model, env.data, obj.body, obj.annotations, 1.0)
    opened = get_point_in_env(env, "handle", "drawer", 0)
    assert opened[0] - closed[0] == pytest.approx(-0.2, abs=1e-3)  # out toward the robot
    assert abs(opened[1] - closed[1]) < 1e-3
    # the handle point is on the handle: the frontmost part of the drawer, 2 cm above its front's middle
    assert closed[0] == pytest.approx(env.data.xpos[env.model.body(obj.body).id][0] + ann.bbox_min[0] + 0.005,
                                      abs=0.006)


def test_a_task_runs_on_a_chosen_model_and_each_seed_draws_its_own(imported_mug, monkeypatch):
    """--model FAMILY=MODEL pins the task's objects of that family to a model; --randomize-models draws one per
    episode from the imported models, the same for the same seed."""
    from humanoidgen.tasks.models import ModelChoiceError, parse_models, with_models
    from humanoidgen.tasks.registry import load_task

    monkeypatch.setenv(ENV_FAMILIES_PATH, str(imported_mug))
    spec = load_task("empty_cup_place")
    pinned = with_models(spec, parse_models(["cup=my_mug"]), randomize=False)
    assert [o.type_id for o in pinned.objects if o.type == "cup"] == [100]
    assert [o.type_id for o in pinned.sample_layout(3) if o.type == "cup"] == [100]
    drawn = with_models(spec, {}, randomize=True)
    assert drawn.randomize_models == ["cup"]  # the plate family has no imported model here
    layouts = [drawn.sample_layout(s) for s in (1, 2, 1)]
    assert [o.type_id for o in layouts[0] if o.type == "cup"] == [100]
    assert layouts[0] == layouts[2]
    # the poses are those the task draws without the option
    assert [o.pos for o in layouts[1]] == [o.pos for o in spec.sample_layout(2)]
    with pytest.raises(ModelChoiceError, match="has no model 'nope'"):
        with_models(spec, {"cup": "nope"}, randomize=False)
    with pytest.raises(ModelChoiceError, match="has no family drawer"):
        with_models(spec, {"drawer": "x"}, randomize=False)
    r = runner.invoke(app, ["run", "empty_cup_place", "--model", "cup=nope"])
    assert r.exit_code == 1 and "cup has no model 'nope'" in r.output


def test_a_mesh_on_its_side_is_flagged_with_a_hint_about_up(tmp_path, collision_cache):
    """A glTF is y-up by its specification: a z-up file imported without --up lies on its side, and the import
    says so instead of passing quietly."""
    bottle().export(tmp_path / "b.glb")  # z up, as made
    r = runner.invoke(app, ["assets", "import", str(tmp_path / "b.glb"), "--family", "bottle", "--out",
                            str(tmp_path / "models"), "--no-preview"])
    assert r.exit_code == 0, r.output
    assert "most points are unsure: is the object upright? --up" in r.output


def test_contents_ride_in_the_storage_of_the_cup_they_are_put_in(imported_mug, monkeypatch):
    """cup_pour_easy's two cubes stand in its cup's opening; on an imported mug (whose opening is elsewhere in
    its box, its bottom at another height) they move with its storage point and stay inside it."""
    from humanoidgen.objects.queries import get_point_in_env
    from humanoidgen.tasks.models import with_models
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    monkeypatch.setenv(ENV_FAMILIES_PATH, str(imported_mug))
    spec = load_task("cup_pour_easy")
    for derived in (with_models(spec, {"cup": "my_mug"}, randomize=False), with_models(spec, {}, randomize=True)):
        for seed in (0, 7):
            scene, env = build_scene(derived, seed)
            cup = scene.object("cup", 0)
            assert cup.type_id == 100
            storage = get_point_in_env(env, "storage", "cup", 0)
            for k in (0, 1):
                cube = env.data.xpos[env.model.body(scene.object("cube", k).body).id]
                assert np.linalg.norm(cube[:2] - storage[:2]) < 0.01, (seed, k)  # inside the opening
                assert storage[2] - 0.02 < cube[2] < storage[2] + 0.06


def test_fit_family_scales_a_model_into_the_size_range_of_the_familys_own(tmp_path):
    """--fit-family: an 8 cm tin imported as a bottle comes out as tall as the family's smallest bottle (the
    sizes its tasks were written for); one inside the range is left as it is."""
    from humanoidgen.objects.imported.sizing import family_size_range

    lo, hi = family_size_range("bottle")
    for name, height, want in (("stubby", 0.08, lo), ("fine", (lo + hi) / 2, (lo + hi) / 2)):
        trimesh.creation.cylinder(radius=0.02, height=height, sections=32).export(tmp_path / f"{name}.obj")
        r = runner.invoke(app, ["assets", "import", str(tmp_path / f"{name}.obj"), "--family", "bottle",
                                "--fit-family", "--out", str(tmp_path / "models"), "--no-preview"])
        assert r.exit_code == 0, r.output
        folder = tmp_path / "models" / "bottle" / name
        ann = yaml.safe_load((folder / "annotations.yaml").read_text())
        assert ann["bbox_max"][2] - ann["bbox_min"][2] == pytest.approx(want, abs=1e-4)
        info = yaml.safe_load((folder / "model.yaml").read_text())
        assert info["fitted"] == pytest.approx(want / height, rel=1e-6)
        assert ("scaled x" in r.output) == (name == "stubby")


def test_an_mjcf_whose_case_is_turned_keeps_its_drawer_inside(tmp_path, collision_cache):
    """A body welded between the root and the drawer may be turned (LIBERO's short cabinet turns its case and
    drawers by a quaternion): the drawer link is placed in its parent link's frame, inside the case, not left
    unturned beside it."""
    (tmp_path / "cab.xml").write_text("""<mujoco model="cab"><worldbody><body name="object">
  <body name="base" pos="0 0 0.1" quat="0.5 0.5 -0.5 -0.5">
    <geom type="box" size="0.15 0.2 0.01" pos="0 0 -0.09"/><geom type="box" size="0.15 0.2 0.01" pos="0 0 0.09"/>
    <geom type="box" size="0.15 0.01 0.1" pos="0 -0.19 0"/><geom type="box" size="0.15 0.01 0.1" pos="0 0.19 0"/>
    <geom type="box" size="0.01 0.2 0.1" pos="-0.14 0 0"/>
    <body name="drawer"><joint name="slide" type="slide" axis="1 0 0" range="0 0.2"/>
      <geom type="box" size="0.12 0.16 0.005" pos="0 0 -0.07"/><geom type="box" size="0.01 0.16 0.07" pos="0.13 0 0"/>
      <geom type="box" size="0.01 0.03 0.01" pos="0.15 0 0.03"/>
    </body></body></body></worldbody></mujoco>""")
    r = runner.invoke(app, ["assets", "import", str(tmp_path / "cab.xml"), "--family", "drawer", "--name", "cab",
                            "--out", str(tmp_path / "models"), "--no-preview"])
    assert r.exit_code == 0, r.output
    folder = tmp_path / "models" / "drawer" / "cab"
    info = yaml.safe_load((folder / "model.yaml").read_text())
    arrays = np.load(folder / "meshes.npz")
    links = {l["name"]: l for l in info["links"]}
    case = arrays[f"{next(n for n, l in links.items() if l['parent'] is None)}_v"]
    drawer = arrays["drawer_v"] + np.asarray(links["drawer"]["pos"])  # the drawer link's frame in the case's
    lo, hi = case.min(0), case.max(0)
    # inside the case but for its front and handle, which stand out toward the robot (-x)
    assert np.all(drawer[:, 1:].min(0) >= lo[1:] - 0.002) and np.all(drawer[:, 1:].max(0) <= hi[1:] + 0.002)
    assert drawer[:, 0].max() <= hi[0] + 0.002


_BOX_WITH_HANDLE = """<mujoco model="handled_box"><worldbody><body name="box">
  <geom type="box" size="0.09 0.09 0.005" pos="0 0 0.005"/>
  <geom type="box" size="0.09 0.005 0.03" pos="0 -0.085 0.03"/><geom type="box" size="0.09 0.005 0.03" pos="0 0.085 0.03"/>
  <geom type="box" size="0.005 0.09 0.03" pos="-0.085 0 0.03"/><geom type="box" size="0.005 0.09 0.03" pos="0.085 0 0.03"/>
  <body name="lid" pos="0.09 0 0.06"><joint name="hinge" type="hinge" axis="0 1 0" range="0 100"/>
    <geom type="box" size="0.09 0.09 0.004" pos="-0.09 0 0.004"/>
    <geom type="box" size="0.01 0.05 0.035" pos="-0.09 0 0.043"/>
  </body></body></worldbody></mujoco>"""


def test_a_lid_with_a_handle_on_top_keeps_its_front_edge_on_the_lid(tmp_path, collision_cache):
    """A box lid with a 7 cm handle standing on it (Meta-World's box): the front edge is the middle of the lid's
    front rim and lid_top lies on its outer face, not halfway up the handle or at its top."""
    (tmp_path / "box.xml").write_text(_BOX_WITH_HANDLE)
    r = runner.invoke(app, ["assets", "import", str(tmp_path / "box.xml"), "--family", "box", "--name", "handled",
                            "--out", str(tmp_path / "models"), "--no-preview"])
    assert r.exit_code == 0, r.output
    folder = tmp_path / "models" / "box" / "handled"
    info = yaml.safe_load((folder / "model.yaml").read_text())
    assert [l["joint"]["kind"] for l in info["links"] if l["joint"]] == ["hinge"]
    v = np.load(folder / "meshes.npz")["lid_v"]  # the lid in its own frame (at the hinge), as its points are
    slab = v[v[:, 2] <= v[:, 2].min() + 0.0081]  # the 8 mm lid, under its handle
    ann = yaml.safe_load((folder / "annotations.yaml").read_text())
    pts = {p["name"]: np.asarray(p["position"]) for p in ann["points"] if p.get("part") == "lid"}
    bottom, top = slab[:, 2].min(), slab[:, 2].max()
    assert pts["lid_front"][2] == pytest.approx((bottom + top) / 2, abs=0.001)
    assert pts["lid_front"][0] == pytest.approx(v[:, 0].min(), abs=0.001)
    assert pts["lid_top"][2] == pytest.approx(top, abs=0.001)


def test_a_drawer_whose_handle_no_hand_can_hook_is_kept_but_never_drawn(tmp_path, collision_cache, monkeypatch):
    """The drawer family's `usable` rules: the test drawer (handle 12 cm up, 2.5 cm out) passes; the same drawer at
    half size (its handle 6 cm over the table) fails the height rule, with the measured value in the reason. It is
    still a model of the family (--model takes it); --randomize-models does not draw it."""
    from humanoidgen.objects import library
    from humanoidgen.objects.imported.usable import unusable_reason
    from humanoidgen.objects.stand_ins import drawable_models
    from humanoidgen.tasks.models import with_models
    from humanoidgen.tasks.registry import load_task
    from meshes_for_tests import drawer_urdf

    urdf = drawer_urdf(tmp_path / "src")
    for name, scale in (("full", "1"), ("half", "0.5")):
        r = runner.invoke(app, ["assets", "import", str(urdf), "--family", "drawer", "--name", name, "--scale", scale,
                                "--out", str(tmp_path / "models"), "--no-preview"])
        assert r.exit_code == 0, r.output
    monkeypatch.setenv(ENV_FAMILIES_PATH, str(tmp_path / "models"))
    by = {m.info.name: m for m in library.family("drawer").imported()}
    assert unusable_reason(by["full"]) is None
    reason = unusable_reason(by["half"])
    got = re.match(r"its handle is ([0-9.]+) cm over its base \(at least 10.5 cm wanted\): the hand hooks", reason)
    assert got is not None and 5.5 <= float(got.group(1)) <= 6.5, reason
    assert [m.params["name"] for m in drawable_models("drawer")] == ["full"]
    spec = load_task("open_drawer")
    assert with_models(spec, {"drawer": "half"}, randomize=False).objects[0].type_id == by["half"].info.type_id
    assert {o.type_id for s in range(8) for o in with_models(spec, {}, True).sample_layout(s)} == \
        {by["full"].info.type_id}


def test_the_familys_own_drawers_pass_its_usable_rules():
    """The rules describe what the family's own models offer (their handles 21 cm up, standing 6 cm out)."""
    from humanoidgen.objects import library
    from humanoidgen.objects.imported.usable import family_rules
    from humanoidgen.objects.queries import get_point_in_env
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.layout import TABLE_TOP_Z
    from humanoidgen.sim.scene import SceneBuilder

    rules = family_rules("drawer")
    assert {("min_height" if r.min_height else "min_out") for r in rules} == {"min_height", "min_out"}
    for m in library.family("drawer").base.models():
        b = SceneBuilder()
        library.add_object(b, "drawer", type_id=m.type_id, pos=(-0.1, 0.3))
        env = HumanoidEnv(b.build())
        for r in rules:
            p = get_point_in_env(env, r.point, "drawer", 0)
            if r.min_height:
                assert p[2] - TABLE_TOP_Z >= r.min_height, (m.type_id, r)
            else:
                assert get_point_in_env(env, r.from_point, "drawer", 0)[0] - p[0] >= r.min_out, (m.type_id, r)


@pytest.mark.parametrize("extents,turn", [((0.06, 0.06, 0.04), 11.0), ((0.06, 0.06, 0.04), 37.0),
                                          ((0.04, 0.07, 0.03), 25.0), ((0.07, 0.04, 0.03), -60.0)])
def test_a_box_is_squared_to_the_axes_with_its_long_side_on_y(extents, turn):
    """A box-like model's faces come out along x and y whatever its yaw in the file, a square one too (its
    footprint's principal axes are any two directions: Meta-World's square bin came out turned 11 deg by them),
    and a long one has its long side on y."""
    from humanoidgen.objects.imported.transfer import transfer

    mesh = trimesh.creation.box(extents=extents)
    mesh.apply_translation((0.0, 0.0, extents[2] / 2))
    mesh.apply_transform(trimesh.transformations.rotation_matrix(np.radians(turn), (0, 0, 1)))
    res = transfer(mesh, "cube", 100, "a turned box")
    out = mesh.copy()
    out.apply_transform(res.transform)
    ext = out.extents
    assert ext[0] == pytest.approx(min(extents[:2]), abs=1e-4) and ext[1] == pytest.approx(max(extents[:2]), abs=1e-4)


def test_a_msh_with_texture_coordinates_takes_the_image_given_with_texture(tmp_path, collision_cache):
    """MuJoCo's .msh keeps texture coordinates but names no image (its MJCF does): --texture gives it; a mesh
    without coordinates refuses one in one line."""
    from PIL import Image

    from humanoidgen.objects.imported.msh_file import read_msh, write_msh

    box = trimesh.creation.box(extents=(0.05, 0.06, 0.04))
    box.apply_translation((0, 0, 0.02))
    uv = (box.vertices[:, :2] - box.vertices[:, :2].min(0)) / np.ptp(box.vertices[:, :2], axis=0)
    write_msh(box, tmp_path / "box.msh", uv=uv)
    assert np.allclose(read_msh(tmp_path / "box.msh").visual.uv, uv, atol=1e-6)  # trimesh's convention back
    Image.new("RGB", (8, 8), (200, 30, 30)).save(tmp_path / "label.png")
    r = runner.invoke(app, ["assets", "import", str(tmp_path / "box.msh"), "--family", "cube", "--out",
                            str(tmp_path / "models"), "--no-preview", "--texture", str(tmp_path / "label.png")])
    assert r.exit_code == 0, r.output
    folder = tmp_path / "models" / "cube" / "box"
    info = yaml.safe_load((folder / "model.yaml").read_text())
    assert info["links"][0]["textured"] and (folder / "texture.png").is_file()
    write_msh(box, tmp_path / "plain.msh")
    r = runner.invoke(app, ["assets", "import", str(tmp_path / "plain.msh"), "--family", "cube", "--out",
                            str(tmp_path / "models"), "--no-preview", "--texture", str(tmp_path / "label.png")])
    assert r.exit_code == 1 and "--texture needs a rigid mesh with a texture coordinate per vertex" in r.output
    assert not (tmp_path / "models" / "cube" / "plain").exists()


def test_coacd_past_its_time_limit_is_killed_and_hulls_of_clusters_stand_in(tmp_path, monkeypatch):
    """A decomposition that does not finish in COACD_SECONDS (pybullet's lego brick took more than 300 s) is
    killed; the parts are hulls of the surface's clusters, which cover the mesh."""
    import time

    from humanoidgen.objects.imported import collision

    def slow(*args, **kwargs):
        time.sleep(30)

    monkeypatch.setattr(collision, "_coacd", slow)
    monkeypatch.setattr(collision, "COACD_SECONDS", 1.0)
    cup = mug()
    t0 = time.perf_counter()
    parts = collision.convex_parts(cup, cache=tmp_path)
    assert time.perf_counter() - t0 < 10
    assert 1 <= len(parts) <= 8 and all(p.is_convex for p in parts)
    lo = np.min([p.bounds[0] for p in parts], axis=0)
    hi = np.max([p.bounds[1] for p in parts], axis=0)
    assert np.allclose(lo, cup.bounds[0], atol=0.005) and np.allclose(hi, cup.bounds[1], atol=0.005)


def test_a_library_model_written_under_other_import_rules_is_imported_again(imported_mug, tmp_path):
    """The library fetch keeps a model already there only if the same import rules wrote it: a model imported
    before a rule changed (e.g. box-like models squared to the axes) is imported again, not kept as it was."""
    import shutil

    from humanoidgen.objects.imported import fetch
    from humanoidgen.objects.imported.model_file import IMPORT_RULES

    root = tmp_path / "lib"
    shutil.copytree(imported_mug / "cup" / "my_mug", root / "cup" / "my_mug")
    path = root / "cup" / "my_mug" / "model.yaml"
    info = yaml.safe_load(path.read_text())
    assert info["import_rules"] == IMPORT_RULES
    m = fetch.LibraryModel(name="my_mug", family="cup", type_id=200, package="pkg", file="mug.obj",
                           sha256=info["source"]["sha256"] if len(info["source"]["sha256"]) == 64 else "0" * 64,
                           scale=info["scale"] / (info["fitted"] or 1.0), up=info["up"], source="test",
                           fit=info["fitted"] is not None)
    info["type_id"] = 200
    path.write_text(yaml.safe_dump(info, sort_keys=False))
    assert fetch._present(root, m)
    info["import_rules"] = IMPORT_RULES - 1  # the same files, imported under the rules before
    path.write_text(yaml.safe_dump(info, sort_keys=False))
    assert not fetch._present(root, m)
    del info["import_rules"]  # written before the rules were numbered
    path.write_text(yaml.safe_dump(info, sort_keys=False))
    assert not fetch._present(root, m)
