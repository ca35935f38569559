"""The physics holds a pinched cube: the right hand pinches a 3.5 cm, 50 g cube between thumb and index tips,
lifts it 10 cm and holds it still (2 ms step, elliptic cones, impratio 10, the stock hand gains).

The hand is turned palm-outward (palm normal to world -y), fingers forward, so that the thumb-index squeeze axis
(the palm normal: the thumb opposes the index from in front of the palm at thumb yaw 1.3) is horizontal and the
index finger is the lowest finger; with the palm facing down the squeeze axis would be vertical and the thumb
would have to get under the cube.
"""

import numpy as np
import pytest

from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.ik import AxisGoal, solve_arm_ik_restarts
from humanoidgen.sim.scene import SceneBuilder

SIZE = 0.035
CUBE_POS = np.array([-0.32, -0.15, SIZE / 2])
# Between thumb tip and index tip of the right hand at the pre-pinch posture, wrist-yaw frame (measured from the
# finger meshes: thumb tip near (0.18, 0.09, 0.027), index tip near (0.24, 0.0, 0.027) before closing).
PINCH_POINT_SIDE = np.array([0.205, 0.045, 0.027])
# Right hand (thumb yaw, thumb pitch, index, middle, ring, pinky): thumb turned to face the index, index open,
# the other fingers curled out of the way; then thumb pitch and index close (they stop at the cube).
PRE_PINCH = np.array([1.3, 0.0, 0.0, 1.4, 1.4, 1.4])
SQUEEZE = np.array([1.3, 0.5, 0.9, 1.4, 1.4, 1.4])
LIFT = 0.10
RIGHT_ARM, RIGHT_HAND = slice(7, 14), slice(20, 26)


def _smooth(n: int):
    for k in range(1, n + 1):
        s = k / n
        yield s * s * (3 - 2 * s)


def _cube_contacts(env: HumanoidEnv, body: str) -> set[str]:
    m, d = env.model, env.data
    cube = m.body(body).id
    out = set()
    for c in d.contact[: d.ncon]:
        b1, b2 = int(m.geom_bodyid[c.geom1]), int(m.geom_bodyid[c.geom2])
        if cube in (b1, b2):
            out.add(m.body(b2 if b1 == cube else b1).name)
    return out


def pinch_and_lift() -> dict:
    """Pinch, lift and hold; returns what the tests check."""
    builder = SceneBuilder()
    cube = builder.add_cube(size=SIZE, pos=tuple(CUBE_POS), mass=0.05)
    env = HumanoidEnv(builder.build())
    m, d = env.model, env.data
    axes = (AxisGoal(np.array([0.0, 1.0, 0.0]), np.array([0.0, -1.0, 0.0]), cone_deg=5.0),  # palm outward
            AxisGoal(np.array([1.0, 0.0, 0.0]), np.array([1.0, 0.0, 0.0]), cone_deg=10.0))  # fingers forward
    a = env.init_action()
    a[RIGHT_HAND] = PRE_PINCH
    env.reset(a)
    qs = []
    for target, seed in ((CUBE_POS + [0, 0, 0.08], env.arm_qpos("right")), (CUBE_POS, None),
                         (CUBE_POS + [0, 0, LIFT], None)):
        res = solve_arm_ik_restarts(m, d, "right", PINCH_POINT_SIDE, target, axes,
                                    seeds=[seed if seed is not None else qs[-1]], n_random=16, pos_tol=2e-3)
        assert res.converged, (target, res)
        qs.append(res.qpos)
    above, at, lifted = qs

    # Start with the hand 8 cm above the cube (teleported, then settled), descend over 1 s, close over 0.5 s.
    a[RIGHT_ARM] = above
    env.reset(a)
    for _ in range(25):
        env.step(a)
    for s in _smooth(50):
        a[RIGHT_ARM] = (1 - s) * above + s * at
        env.step(a)
    for s in _smooth(25):
        a[RIGHT_HAND] = (1 - s) * PRE_PINCH + s * SQUEEZE
        env.step(a)
    for _ in range(25):
        env.step(a)
    z0 = env.object_pose(cube.body)[0][2]
    # Lift 10 cm over 1 s; let the arm finish tracking (0.3 s: it lags its target by a few cm/s at the end of the
    # lift, hand and cube together), then hold 1 s.
    for s in _smooth(50):
        a[RIGHT_ARM] = (1 - s) * at + s * lifted
        env.step(a)
    for _ in range(15):
        env.step(a)
    free = m.jnt_dofadr[m.joint(f"{cube.body}_free").id]
    rel, speed = [], []
    for _ in range(50):
        env.step(a)
        hp, hR = env.hand_pose("right")
        rel.append(hR.T @ (env.object_pose(cube.body)[0] - hp))
        speed.append(np.linalg.norm(d.qvel[free:free + 3]))
    return dict(rise=env.object_pose(cube.body)[0][2] - z0, rel=np.array(rel), speed=np.array(speed),
                contacts=_cube_contacts(env, cube.body), hand=env.hand_qpos("right"))


@pytest.fixture(scope="module")
def pinch_run() -> dict:
    return pinch_and_lift()


def test_pinched_cube_rises_with_the_hand(pinch_run):
    assert pinch_run["rise"] >= 0.08


def test_pinched_cube_does_not_slip_or_jitter_while_held(pinch_run):
    rel = pinch_run["rel"]
    assert np.linalg.norm(rel - rel[0], axis=1).max() < 2e-3
    assert pinch_run["speed"].max() < 0.01


def test_cube_is_held_between_thumb_and_index(pinch_run):
    names = pinch_run["contacts"]
    assert any(n.startswith("R_thumb") for n in names), names
    assert any(n.startswith("R_index") for n in names), names
    assert "table" not in names
    # Thumb pitch and index stopped at the cube, short of their targets: the actuators keep squeezing.
    assert pinch_run["hand"][1] < SQUEEZE[1] - 0.05 and pinch_run["hand"][2] < SQUEEZE[2] - 0.05
