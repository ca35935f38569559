"""CollisionWorld.clear_of answers the path planners' validity question (is everything moving farther than the
clearance from its obstacles?) with fewer distance queries than min_distance; its answer must be the same, for
negative, zero and positive clearances, with an object held (its slack) and with touch slack."""

import numpy as np
import pytest

from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.planning.paths import JointSpace
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.layout import SIDES
from humanoidgen.sim.scene import SceneBuilder

CLEARANCES = (-0.004, 0.0, 0.002, 0.005, 0.02)


@pytest.fixture(scope="module")
def world():
    builder = SceneBuilder()
    builder.add_cube(pos=(-0.35, -0.2, 0.02))
    builder.add_cube(pos=(-0.30, 0.2, 0.02))
    env = HumanoidEnv(builder.build())
    kin = Kinematics(env.model)
    kin.sync(env.data.qpos)
    return env, kin, CollisionWorld(kin)


def _set(kin, space, q):
    kin.data.qpos[space.qadr] = q
    kin.forward()


def _agree(kin, cw, rng, n=40):
    """Random postures of both arms around the start pose, and postures bisected toward them until something
    moving comes within 0-2 cm of an obstacle (where the answer depends on the clearance): the two answers agree
    at each. Returns how many postures had their nearest pair within 0-2 cm."""
    space = JointSpace.of(kin, "all")
    base = space.current(kin)
    near = 0

    def check(q):
        _set(kin, space, q)
        for sides in (("left",), ("right",), SIDES):
            d = cw.min_distance(sides)[0]
            for c in CLEARANCES:
                assert cw.clear_of(sides, c) == (d > c), (sides, c, d)
        return cw.min_distance(SIDES)[0]

    for _ in range(n):
        far = np.clip(base + rng.normal(0, 0.6, base.shape), space.lo, space.hi)
        d_far = check(far)
        if check(base) <= 0.02 or d_far > 0.0:
            continue
        lo, hi = 0.0, 1.0  # base clear, far blocked: bisect for the posture between at 3-15 mm
        for _ in range(12):
            t = 0.5 * (lo + hi)
            d = check(base + t * (far - base))
            if 0.003 < d < 0.015:
                near += 1
                break
            lo, hi = (t, hi) if d > 0.015 else (lo, t)
    _set(kin, space, base)
    return near
def test_clear_of_answers_as_min_distance(world):
    env, kin, cw = world
    assert _agree(kin, cw, np.random.default_rng(0)) >= 10  # the clearance decides at these postures


def test_clear_of_with_a_held_object_and_touch_slack(world):
    env, kin, cw = world
    body = env.model.body(_cube_body(env))
    adr = int(env.model.jnt_qposadr[body.jntadr[0]])
    saved = kin.data.qpos.copy()
    kin.data.qpos[adr:adr + 3] = kin.ee_pose("right")[0] + np.array([0.0, 0.0, -0.06])  # in the right hand
    kin.forward()
    kin.attach("right", body.name)
    try:
        fingers = cw.finger_geoms("left")
        with cw.allow_touch(fingers, frozenset(cw.obstacles("left")), 0.01):
            assert _agree(kin, cw, np.random.default_rng(1)) >= 5
    finally:
        kin.detach("right")
        kin.data.qpos[:] = saved
        kin.forward()


def _cube_body(env) -> str:
    return next(env.model.body(b).name for b in range(env.model.nbody) if "cube" in env.model.body(b).name)


def test_clear_of_near_a_small_obstacle(world):
    """A cube moved about the right hand: with small geoms the pair's bounding spheres are apart while the geoms
    are within the clearance (the sphere bound must use the clearance, not zero)."""
    env, kin, cw = world
    body = env.model.body(_cube_body(env))
    adr = int(env.model.jnt_qposadr[body.jntadr[0]])
    saved = kin.data.qpos.copy()
    rng = np.random.default_rng(2)
    decided = 0
    try:
        tip = kin.ee_pose("right")[0]
        for _ in range(300):
            kin.data.qpos[adr:adr + 3] = tip + rng.uniform(-0.12, 0.12, 3)
            kin.forward()
            d = cw.min_distance(("right",))[0]
            for c in (0.01, 0.02, 0.03, 0.04):
                assert cw.clear_of(("right",), c) == (d > c), (c, d)
            decided += 0.01 < d <= 0.04
    finally:
        kin.data.qpos[:] = saved
        kin.forward()
    assert decided >= 10


def test_warm_up_compiles_the_kernel_the_planner_calls(tmp_path):
    """The fork server compiles the broadphase kernel before forking (broadphase.warm_up); a locked-down worker
    cannot write a new compilation to numba's cache (a fresh checkout failed every plan with a PermissionError).
    So warm_up must produce the one specialization the collision checks then use."""
    import os
    import subprocess
    import sys

    code = ("from humanoidgen.planning import broadphase as b; b.warm_up(); "
            "from humanoidgen.sim.env import HumanoidEnv; from humanoidgen.sim.scene import SceneBuilder; "
            "from humanoidgen.planning.kinematics import Kinematics; "
            "from humanoidgen.planning.collision import CollisionWorld; "
            "builder = SceneBuilder(); builder.add_cube(pos=(-0.35, -0.2, 0.02)); env = HumanoidEnv(builder.build()); "
            "kin = Kinematics(env.model); kin.sync(env.data.qpos); cw = CollisionWorld(kin); "
            "cw.clear_of(('left', 'right'), 0.005); print(len(b._pairs.signatures))")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))  # a cache of its own: compiled here, not loaded
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip().splitlines()[-1] == "1"


def test_the_kernel_loads_without_scipy_and_a_later_blas_call_still_compiles(tmp_path):
    """warm_up loads numba's registries without importing scipy.linalg (numba only probes it for BLAS; the
    kernel needs none: 0.25 s of the fork server's start); a compiled np.dot later in the same process still
    works (numba imports SciPy then), and the import system is left as it was."""
    import os
    import subprocess
    import sys

    code = ("import sys; from humanoidgen.planning import broadphase as b; b.warm_up(); "
            "print('scipy.linalg' in sys.modules); import numpy as np; from numba import njit; "
            "f = njit(lambda a, c: np.dot(a, c)); a = np.arange(4.0).reshape(2, 2); "
            "print(bool((f(a, a) == a @ a).all())); print('scipy.linalg' in sys.modules)")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split() == ["False", "True", "True"]


def test_without_blas_changes_nothing_where_scipy_linalg_is_imported():
    import sys

    import scipy.linalg

    from humanoidgen.planning.broadphase import without_blas

    with without_blas():
        import scipy.linalg as again
    assert again is scipy.linalg and sys.modules["scipy.linalg"] is scipy.linalg
