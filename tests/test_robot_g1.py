"""The second robot, the Unitree G1 with the H1-2's Inspire hands (`robots/g1_inspire`): its files come out of the
mjlab 1.6.0 wheel (checked archive, checked files), its hands are the H1-2's attached with MjSpec (their poses on
the mount the same to the float), and its scene builds, reaches the table and renders in a process of its own
(`--robot`).

The G1's files are made available from a local copy of the wheel ($HGEN_MJLAB_WHEEL, else pip's download folder
used by the project's machines), else one downloaded from PyPI; without either the G1 tests fail saying so. The
archive fetch itself is tested on a small wheel built here."""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import mujoco
import numpy as np
import pytest
from typer.testing import CliRunner

from humanoidgen.assets.robot_files import ChecksumError, FetchError, fetch, fetch_archive, resolve_assets_root
from humanoidgen.cli.main import app
from humanoidgen.robots import load_robot
from humanoidgen.robots.check import check
from humanoidgen.sim.robot import build_robot_spec

REPO = Path(__file__).resolve().parents[1]
WHEEL_SHA = "03d003854e2f44c48330c6dcf4c2253ff7641bb569747846825a21b9efa8540b"
WHEEL_CANDIDATES = [os.environ.get("HGEN_MJLAB_WHEEL", ""), "/tmp/pipdl/mjlab/mjlab-1.6.0-py3-none-any.whl",
                    "/tmp/pipdl2/mjlab-1.6.0-py3-none-any.whl"]


# --------------------------------------------------------------------------- the archive fetch, offline


def _wheel(path: Path, files: dict[str, bytes]) -> str:
    with zipfile.ZipFile(path, "w") as zf:
        for name, data in files.items():
            zf.writestr(name, data)
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_an_archive_source_takes_out_only_the_checked_files_of_its_folder(tmp_path: Path):
    files = {"pkg/model/robot.xml": b"<mujoco/>", "pkg/model/assets/a.STL": b"mesh", "pkg/other.py": b"x = 1"}
    digest = _wheel(tmp_path / "w.whl", files)
    sums = {n: hashlib.sha256(files[f"pkg/model/{n}"]).hexdigest() for n in ("robot.xml", "assets/a.STL")}
    dest = tmp_path / "root" / "model"
    assert fetch_archive(f"file://{tmp_path / 'w.whl'}", digest, "pkg/model", sums, dest) == 2
    assert sorted(p.relative_to(dest).as_posix() for p in dest.rglob("*") if p.is_file()) == ["assets/a.STL",
                                                                                              "robot.xml"]
    assert fetch_archive(str(tmp_path / "w.whl"), digest, "pkg/model", sums, dest) == 0  # intact: nothing to do


def test_an_archive_or_a_file_with_another_sha256_is_refused_and_nothing_is_written(tmp_path: Path):
    files = {"m/robot.xml": b"<mujoco/>"}
    digest = _wheel(tmp_path / "w.whl", files)
    with pytest.raises(ChecksumError, match="the archive"):
        fetch_archive(str(tmp_path / "w.whl"), "0" * 64, "m", {"robot.xml": hashlib.sha256(b"<mujoco/>").hexdigest()},
                      tmp_path / "a")
    with pytest.raises(ChecksumError, match="robot.xml"):
        fetch_archive(str(tmp_path / "w.whl"), digest, "m", {"robot.xml": "1" * 64}, tmp_path / "b")
    assert not (tmp_path / "b" / "robot.xml").exists()
    with pytest.raises(FetchError, match="no file m/missing.xml"):
        fetch_archive(str(tmp_path / "w.whl"), digest, "m", {"missing.xml": "1" * 64}, tmp_path / "c")


# --------------------------------------------------------------------------- the G1 itself


@pytest.fixture(scope="module")
def mjlab_wheel(tmp_path_factory) -> Path:
    """The mjlab 1.6.0 wheel the G1's files come from: a local copy, else downloaded from PyPI as `hgen assets
    fetch --robot g1_inspire` would (no skip: without either the G1 is untested, which is a failure here)."""
    wheel = next((Path(p) for p in WHEEL_CANDIDATES if p and Path(p).is_file()), None)
    if wheel is not None:
        return wheel
    dest = tmp_path_factory.mktemp("mjlab_wheel")
    out = subprocess.run([sys.executable, "-m", "pip", "download", "--no-deps", "-q", "mjlab==1.6.0", "-d", str(dest)],
                         capture_output=True, text=True, timeout=300)
    wheels = sorted(dest.glob("mjlab-1.6.0-*.whl"))
    if out.returncode != 0 or not wheels:
        pytest.fail("no mjlab 1.6.0 wheel for the G1's files: none local (HGEN_MJLAB_WHEEL) and `pip download "
                    f"--no-deps mjlab==1.6.0` failed: {out.stderr.strip()[-300:]}")
    return wheels[0]


@pytest.fixture(scope="module")
def g1_root(tmp_path_factory, mjlab_wheel: Path) -> Path:
    """An assets root with the H1-2's files (the hands' source) and the G1's, fetched from the wheel."""
    root = tmp_path_factory.mktemp("g1_assets")
    (root / "h1_2").symlink_to(resolve_assets_root() / "h1_2")
    fetch(root, base_url=str(mjlab_wheel), progress=False, robot=load_robot("g1_inspire"))
    return root


def test_the_g1_fits_its_model_files(g1_root: Path):
    assert check(REPO / "humanoidgen/robots/g1_inspire", g1_root) == []


def test_hgen_assets_fetch_robot_g1_from_a_local_wheel(g1_root: Path, mjlab_wheel: Path, tmp_path: Path):
    (tmp_path / "h1_2").symlink_to(g1_root / "h1_2")
    wheel = mjlab_wheel
    res = CliRunner().invoke(app, ["assets", "fetch", "--robot", "g1_inspire", "--dest", str(tmp_path),
                                   "--base-url", str(wheel), "--no-progress"])
    assert res.exit_code == 0, res.output
    assert "g1_inspire" in res.output and "all 36 verified" in res.output
    assert (tmp_path / "g1" / "g1.xml").is_file() and not (tmp_path / "g1" / "g1_constants.py").exists()


def _poses_on_mount(model: mujoco.MjModel, mount: str) -> dict[str, np.ndarray]:
    d = mujoco.MjData(model)
    mujoco.mj_kinematics(model, d)
    m = model.body(mount).id
    R, p = d.xmat[m].reshape(3, 3), d.xpos[m]
    out = {}
    for b in range(model.nbody):
        name = model.body(b).name
        if name[:2] in ("L_", "R_"):
            out[name] = np.concatenate([R.T @ (d.xpos[b] - p), (R.T @ d.xmat[b].reshape(3, 3)).ravel()])
    return out


def test_the_g1_carries_the_h1_2s_hands_exactly(g1_root: Path):
    h1, g1 = load_robot("h1_2_inspire"), load_robot("g1_inspire")
    m_h1 = build_robot_spec(g1_root, robot=h1).compile()
    m_g1 = build_robot_spec(g1_root, robot=g1).compile()
    assert m_g1.nu == m_h1.nu == 26 and m_g1.neq == m_h1.neq == 12  # 26 targets, 6 couplings a hand
    for side in ("left", "right"):
        a, b = _poses_on_mount(m_h1, h1.hand_mount(side)), _poses_on_mount(m_g1, g1.hand_mount(side))
        names = {n for n in a if g1.is_hand_name(n, side)}
        assert len(names) == 12 and names <= set(b)  # 12 finger links
        for n in names:
            np.testing.assert_allclose(b[n], a[n], atol=1e-9, err_msg=n)
    names = {m_g1.mesh(i).name for i in range(m_g1.nmesh)}
    assert not any("rubber_hand" in n for n in names)  # the G1's own hands are gone
    for side in ("left", "right"):  # the motors' torque limits come from the robot file (the MJCF has none)
        assert m_g1.actuator(g1.arm_joints[side][5]).forcerange[1] == 5.0
        assert m_g1.actuator(g1.arm_joints[side][3]).forcerange[1] == 25.0


_SCENE = """
import json, mujoco, numpy as np
from humanoidgen.sim.scene import SceneBuilder
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.layout import ROBOT, WRIST_BODY, TABLE_X, palm_center_on_wrist
b = SceneBuilder(); b.add_cube(); scene = b.build(); env = HumanoidEnv(scene)
for _ in range(20):
    env.step(env.init_action())
m, d = scene.model, env.data
palms = {}
for s in ("left", "right"):
    w = m.body(WRIST_BODY[s]).id
    palms[s] = (d.xpos[w] + d.xmat[w].reshape(3, 3) @ palm_center_on_wrist(s)).tolist()
feet = min(d.xpos[m.body(n).id][2] for n in ROBOT.data.stand.feet)
root = m.body(ROBOT.data.stand.root_body).id
robot_geoms = {g for g in range(m.ngeom) if m.body_rootid[m.geom_bodyid[g]] == root}
table = m.geom("table_top").id
on_table = [{c.geom1, c.geom2} - {table} for c in d.contact[: d.ncon] if table in (c.geom1, c.geom2)]
print(json.dumps({"robot": ROBOT.name, "palms": palms, "table_x": list(TABLE_X), "feet": float(feet),
                  "floor": float(m.geom("floor").pos[2]), "n_on_table": len(on_table),
                  "robot_on_table": sum(1 for g in on_table if g & robot_geoms)}))
"""


def test_the_g1_scene_builds_in_a_process_of_its_own_with_its_home_over_the_table(g1_root: Path):
    env = {**os.environ, "HGEN_ASSETS": str(g1_root), "HGEN_ROBOT": "g1_inspire", "PYTHONPATH": str(REPO)}
    out = subprocess.run([sys.executable, "-c", _SCENE], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    r = json.loads(out.stdout.strip().splitlines()[-1])
    assert r["robot"] == "g1_inspire" and r["table_x"] == [-0.56, 0.2]
    for side, sign in (("left", 1), ("right", -1)):  # the home posture: palms 25 cm over the table, mirrored
        np.testing.assert_allclose(r["palms"][side], [-0.45, sign * 0.22, 0.25], atol=0.01)
    assert 0.0 < r["feet"] - r["floor"] < 0.06  # the feet stand on the floor
    assert r["n_on_table"] >= 1 and r["robot_on_table"] == 0  # the cube rests on the table, the robot clear of it


def test_hgen_render_robot_g1_draws_six_cameras(g1_root: Path, tmp_path: Path):
    env = {**os.environ, "HGEN_ASSETS": str(g1_root), "PYTHONPATH": str(REPO), "MUJOCO_GL": "egl"}
    env.pop("HGEN_ROBOT", None)
    out = subprocess.run([sys.executable, "-m", "humanoidgen.cli.main", "render", "--robot", "g1_inspire",
                          "--width", "64", "--height", "48", "--settle", "0", "--out", str(tmp_path / "g1.png")],
                         env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "6 cameras" in out.stdout and (tmp_path / "g1.png").stat().st_size > 0


def test_an_unknown_robot_is_one_line_and_exit_1():
    res = CliRunner().invoke(app, ["render", "--robot", "no_such_robot"])
    assert res.exit_code == 1
    assert "no_such_robot" in res.output and "robot.yaml" in res.output


def test_the_plan_worker_keeps_the_process_robot():
    """Scenes of a plan's episode are built in the sandbox's processes: they must build the same robot."""
    from humanoidgen.sandbox.lockdown import scrubbed_environ

    assert scrubbed_environ({"HGEN_ROBOT": "g1_inspire", "SECRET_TOKEN": "x"}).get("HGEN_ROBOT") == "g1_inspire"


def test_the_gym_env_takes_the_process_robot_and_refuses_another():
    from humanoidgen.envs import HumanoidTaskEnv

    with pytest.raises(ValueError, match="HGEN_ROBOT=g1_inspire"):
        HumanoidTaskEnv("close_drawer", robot="g1_inspire")


def test_the_gym_env_runs_the_g1_in_a_process_of_its_own(g1_root: Path):
    code = ("from humanoidgen.envs import HumanoidTaskEnv\n"
            "env = HumanoidTaskEnv('close_drawer', robot='g1_inspire')\n"
            "obs, info = env.reset(seed=100000)\n"
            "obs, r, term, trunc, info = env.step(obs['joint_pos'])\n"
            "from humanoidgen.sim.layout import ROBOT\n"
            "print(ROBOT.name, env.action_space.shape[0], obs['joint_pos'].shape[0])\n")
    env = {**os.environ, "HGEN_ASSETS": str(g1_root), "HGEN_ROBOT": "g1_inspire", "PYTHONPATH": str(REPO)}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split()[-3:] == ["g1_inspire", "26", "26"]
