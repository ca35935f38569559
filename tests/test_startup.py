"""Start-up (`hgen run` beyond its episode; bench/startup.py): the fork server builds the scene of the episode
it was started for while it imports (`episode_worker.prebuild`), and that episode's worker takes it instead
of building it; the robot's meshes that no geom uses are not compiled. Neither may change what is
simulated: the scene a worker takes is the one it would have built, to the bit."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import humanoidgen.sim.robot as robot  # noqa: E402
from humanoidgen.episodes import episode_worker  # noqa: E402
from humanoidgen.episodes.episode_worker import EpisodeSetup, prebuild, scene_key  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
TASK = "block_stack_single"
DATA_FIELDS = ("qpos", "qvel", "act", "ctrl", "qacc_warmstart", "time")


def _model_arrays(model: mujoco.MjModel, skip: tuple[str, ...] = ()) -> dict[str, np.ndarray]:
    return {n: getattr(model, n) for n in dir(model) if not n.startswith("_") and not n.startswith(skip)
            and isinstance(getattr(model, n, None), np.ndarray)}


def _assert_same_model(a: mujoco.MjModel, b: mujoco.MjModel, skip: tuple[str, ...] = ()) -> None:
    x, y = _model_arrays(a, skip), _model_arrays(b, skip)
    assert x.keys() == y.keys()
    differ = [n for n in x if x[n].shape != y[n].shape or not np.array_equal(x[n], y[n], equal_nan=True)]
    assert differ == []


@pytest.fixture
def no_prebuilt():
    episode_worker._PREBUILT.clear()
    yield
    episode_worker._PREBUILT.clear()


def test_the_worker_of_the_prebuilt_episode_takes_its_scene_which_is_the_one_it_would_build(no_prebuilt):
    spec = load_task(TASK)
    data = spec.model_dump(mode="json")
    prebuild({"task": TASK, "seed": 3, "dressing": None})  # in-process, as the fork server does before any fork
    prebuilt = episode_worker._PREBUILT[scene_key(data, 3, None)]
    state = {f: np.copy(getattr(prebuilt.data, f)) for f in DATA_FIELDS}
    _, fresh = build_scene(load_task(TASK), 3)
    _assert_same_model(prebuilt.model, fresh.model)
    for f in DATA_FIELDS:
        assert np.array_equal(state[f], getattr(fresh.data, f)), f
    ns = EpisodeSetup(data, "# step: nothing\npass\n", 3)()
    assert ns["planner"].env is prebuilt  # taken, not built again
    assert episode_worker._PREBUILT == {}  # by this worker only


def test_another_episode_builds_its_own_scene(no_prebuilt):
    data = load_task(TASK).model_dump(mode="json")
    prebuild({"task": TASK, "seed": 3, "dressing": None})
    prebuilt = episode_worker._PREBUILT[scene_key(data, 3, None)]
    for seed, dressing in ((4, None), (3, {"room_seed": 1})):  # another seed; the same seed in a room
        assert scene_key(data, seed, dressing) not in episode_worker._PREBUILT
    other = EpisodeSetup(data, "# step: nothing\npass\n", 4)()
    assert other["planner"].env is not prebuilt
    assert episode_worker._PREBUILT  # still there for its own episode


def test_a_hint_that_names_no_task_only_costs_the_server_its_build(no_prebuilt):
    with pytest.raises(KeyError):
        prebuild({"task": "no_such_task", "seed": 0, "dressing": None})
    assert episode_worker._PREBUILT == {}


def test_no_robot_mesh_is_compiled_that_no_geom_uses_and_the_physics_is_the_same(monkeypatch):
    model = SceneBuilder().build().model
    used = set(model.geom_dataid[model.geom_type == mujoco.mjtGeom.mjGEOM_MESH])
    assert used == set(range(model.nmesh))
    monkeypatch.setattr(robot, "_drop_unused_meshes", lambda spec: None)
    kept = SceneBuilder().build().model
    assert kept.nmesh == model.nmesh + 16  # the upstream meshes only visual geoms used
    _assert_same_model(model, kept, skip=("mesh_", "bvh_", "name_", "names", "paths", "geom_dataid"))
    a, b = mujoco.MjData(model), mujoco.MjData(kept)
    for k in range(300):  # the arms swing; contacts with the table and between the hands as they go
        ctrl = np.sin(k / 40 + np.arange(model.nu)) * 0.6
        a.ctrl[:], b.ctrl[:] = ctrl, ctrl
        mujoco.mj_step(model, a)
        mujoco.mj_step(kept, b)
    assert np.array_equal(a.qpos, b.qpos) and np.array_equal(a.qvel, b.qvel)


EPISODE = textwrap.dedent('''
    import hashlib, json, sys
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode
    from humanoidgen.sandbox.forkserver import prestart

    if sys.argv[1] == "hint":
        prestart(warm=("humanoidgen.episodes.episode_worker:prebuild",
                       {"task": "block_stack_single", "seed": 3, "dressing": None}))
    result, arrays = run_task_episode(EpisodeRequest("block_stack_single", 3, recorder=RecorderConfig(every=5)),
                                      render=False)
    h = hashlib.sha256()
    for key in sorted(arrays):
        h.update(key.encode() + arrays[key].tobytes())
    print(json.dumps({"success": result.success, "arrays": h.hexdigest(), "checks": result.checks}))
''')


def test_an_episode_run_on_the_prebuilt_scene_is_the_episode_run_without(tmp_path):
    """The real path, twice: a server told the episode (its worker takes the prebuilt scene) and one not told;
    the replay's recorded arrays are the same bytes."""
    script = tmp_path / "episode.py"
    script.write_text(EPISODE)
    out = []
    for mode in ("hint", "plain"):
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
        r = subprocess.run([sys.executable, str(script), mode], capture_output=True, text=True, timeout=600,
                           cwd=ROOT, env=env)
        assert r.returncode == 0, r.stderr[-3000:]
        out.append(json.loads(r.stdout.strip().splitlines()[-1]))
    assert out[0]["success"] and out[0] == out[1]



PROBE = textwrap.dedent('''
    from humanoidgen.episodes import episode_worker


    def setup():
        return {"prebuilt": lambda: len(episode_worker._PREBUILT)}
''')

SERVER = textwrap.dedent('''
    import sys
    sys.path.insert(0, sys.argv[1])  # (the worker's path: the server's is its own)
    import warm_probe
    from humanoidgen.sandbox import SandboxWorker
    from humanoidgen.sandbox.forkserver import prestart

    prestart(warm=("humanoidgen.episodes.episode_worker:prebuild",
                   {"task": sys.argv[2], "seed": 3, "dressing": None}))
    with SandboxWorker(warm_probe.setup) as w:
        print(w.call("prebuilt"))
''')


@pytest.mark.parametrize("task, prebuilt", [(TASK, 1), ("no_such_task", 0)])
def test_the_server_builds_the_scene_it_is_told_before_it_forks_and_comes_up_if_it_cannot(tmp_path, task,
                                                                                          prebuilt):
    (tmp_path / "warm_probe.py").write_text(PROBE)
    (tmp_path / "server.py").write_text(SERVER)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, str(tmp_path / "server.py"), str(tmp_path), task], capture_output=True,
                       text=True, timeout=600, cwd=ROOT, env=env)
    assert r.returncode == 0, r.stderr[-3000:]
    assert int(r.stdout.strip().splitlines()[-1]) == prebuilt  # what a worker inherited from the server


def test_the_parent_of_an_episode_imports_no_planner():
    """`hgen run`'s own process imports what it needs to run and judge an episode, not the planner (numba,
    Drake: half a second of CPU beside the fork server's start on two cores); the worker and its twin get the
    planner from the server."""
    code = ("import sys; import humanoidgen.cli.main; "
            "from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode, load_spec; "
            "from humanoidgen.episodes.video import VideoWriter; load_spec('block_stack_single'); "
            "print(sorted(m for m in ('numba', 'pydrake', 'ompl', 'scipy', 'humanoidgen.planning.planner', "
            "'humanoidgen.planning.collision') if m in sys.modules))")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, cwd=ROOT, env=env)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip().splitlines()[-1] == "[]"


ORDER = textwrap.dedent('''
    import json, os, sys
    os.environ["HGEN_SANDBOX_WARM"] = json.dumps({"call": "humanoidgen.episodes.episode_worker:prebuild",
                                                 "data": {"task": sys.argv[1], "seed": 3, "dressing": None}})
    import humanoidgen.sandbox.forkserver  # (as the server: it names the environment variable)
    from humanoidgen.sim import scene

    later = ("pyseccomp", "pydrake.solvers", "ompl", "humanoidgen.planning.planner", "numba")
    seen = []
    build = scene.SceneBuilder.build

    def recorded(self):
        seen.extend(m for m in later if m in sys.modules)  # what the other thread had imported by then
        return build(self)

    scene.SceneBuilder.build = recorded
    import humanoidgen.sandbox.preload  # noqa: F401  (the server's warm-up)
    print(json.dumps({"at_compile": seen, "after": [m for m in later if m in sys.modules]}))
''')


def test_the_server_builds_the_scene_spec_before_its_other_imports(tmp_path):
    """The server's other thread holds back its imports (Drake, OMPL, the planner, the kernel) until the scene's
    spec is built and its compile started (`scene.before_compile`): sharing Python's lock with them, the spec
    took twice as long and the compile, the longest part, started that much later."""
    script = tmp_path / "order.py"
    script.write_text(ORDER)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, str(script), TASK], capture_output=True, text=True, timeout=600, cwd=ROOT,
                       env=env)
    assert r.returncode == 0, r.stderr[-3000:]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["at_compile"] == [] and len(out["after"]) == 5, out


def test_before_compile_is_called_before_each_compile(monkeypatch):
    calls = []
    monkeypatch.setattr("humanoidgen.sim.scene.before_compile", lambda: calls.append("before"))
    SceneBuilder().build()
    assert calls == ["before"]
