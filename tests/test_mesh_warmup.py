"""The robot's collision meshes processed into MuJoCo's mesh cache ahead of the scene's compile, in threads of
their own (`sim.mesh_warmup`, started by the workers' fork server right after it imports MuJoCo): the scene
compiled after it is the same model to the bit, its compile finds the files in the cache, and the files warmed
up are the ones the robot's spec compiles."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402

from humanoidgen.assets.robot_files import resolve_assets_root  # noqa: E402
from humanoidgen.sim import mesh_warmup  # noqa: E402
from humanoidgen.sim.meshes import DEFAULT_MAX_FACES  # noqa: E402
from humanoidgen.sim.robot import build_robot_spec, robot_collision_meshes  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

# One fresh process per way of compiling (MuJoCo's cache lives as long as its process): the task's scene, with
# or without the warm-up first; the model's arrays as a digest, and the compile's CPU seconds.
COMPILE = textwrap.dedent('''
    import hashlib, json, os, sys, time
    os.environ.setdefault("MUJOCO_GL", "egl")
    import numpy as np
    from humanoidgen.assets.robot_files import resolve_assets_root
    from humanoidgen.sim import mesh_warmup, robot
    from humanoidgen.sim.scene import SceneBuilder
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    if sys.argv[1] == "warm":
        mesh_warmup.start(*robot.robot_collision_meshes(resolve_assets_root()), threads=2)
        mesh_warmup.wait()
    build = SceneBuilder.build
    cpu = []

    def timed(self):
        t = time.process_time()
        try:
            return build(self)
        finally:
            cpu.append(time.process_time() - t)

    SceneBuilder.build = timed
    _, env = build_scene(load_task("block_stack_single"), 3)
    h = hashlib.sha256()
    for name in sorted(dir(env.model)):
        value = getattr(env.model, name, None)
        if not name.startswith("_") and isinstance(value, np.ndarray):
            h.update(name.encode())
            h.update(np.ascontiguousarray(value).tobytes())
    for name in ("qpos", "qvel", "qacc_warmstart"):
        h.update(getattr(env.data, name).tobytes())
    print(json.dumps({"digest": h.hexdigest(), "compile_cpu_s": cpu[0]}))
''')


def _compile(tmp_path: Path, mode: str) -> dict:
    script = tmp_path / "compile.py"
    script.write_text(COMPILE)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, str(script), mode], capture_output=True, text=True, timeout=600, cwd=ROOT,
                       env=env)
    assert r.returncode == 0, r.stderr[-3000:]
    return json.loads(r.stdout.strip().splitlines()[-1])


def test_the_scene_compiled_after_the_warm_up_is_the_same_to_the_bit_and_finds_its_meshes_cached(tmp_path):
    cold, warm = _compile(tmp_path, "cold"), _compile(tmp_path, "warm")
    assert warm["digest"] == cold["digest"]  # the model's arrays and the settled state
    # The robot's files come from the cache: about 0.3 s of CPU instead of about 1.1 s.
    assert warm["compile_cpu_s"] < 0.6 * cold["compile_cpu_s"], (warm, cold)


def test_the_files_warmed_up_are_the_files_the_robot_spec_compiles():
    root = resolve_assets_root()
    _, meshes = robot_collision_meshes(root)
    compiled = build_robot_spec(root, DEFAULT_MAX_FACES)
    assert sorted((m.name, m.file) for m in meshes) == sorted((m.name, m.file) for m in compiled.meshes if m.file)
    assert len(meshes) > 10


def test_shares_hold_every_file_once_in_about_even_parts():
    spec, meshes = robot_collision_meshes(resolve_assets_root())
    shares = mesh_warmup._shares(spec, meshes, 2)
    assert sorted(m.name for share in shares for m in share) == sorted(m.name for m in meshes)
    sizes = [sum(os.path.getsize(os.path.join(spec.modelfiledir, spec.meshdir, m.file)) for m in s) for s in shares]
    assert min(sizes) > 0.8 * max(sizes)


def test_a_warm_up_that_fails_only_costs_its_time():
    spec = mujoco.MjSpec()
    spec.modelfiledir = "/nonexistent/"
    mesh = spec.add_mesh(name="missing", file="missing.stl")
    mesh_warmup.start(spec, [mesh], threads=1)
    mesh_warmup.wait()  # no exception: the scene's own compile reports a missing file
    mesh_warmup.wait()  # nothing pending
