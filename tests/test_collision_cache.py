"""CollisionWorld keeps its mover and obstacle lists between queries: they must still follow a grasp, a
release and every change of the ignore list (in place or by reassignment), and the queries must answer as
the lists built afresh would."""

import mujoco
import numpy as np

from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.layout import SIDES
from humanoidgen.sim.scene import SceneBuilder


def fresh_lists(cw: CollisionWorld, side: str) -> tuple[list[int], list[int]]:
    """The lists as the uncached code built them on every call."""
    m = cw.kin.model
    moving = set(cw._arm_bodies[side])
    if side in cw.kin.attached:
        moving.add(cw.kin.attached[side][0])
    collidable = [g for g in range(m.ngeom) if m.geom_contype[g] != 0 or m.geom_conaffinity[g] != 0]
    movers = [g for g in collidable if m.geom_bodyid[g] in moving]
    obstacles = []
    for g in collidable:
        b = int(m.geom_bodyid[g])
        if b in moving or g in cw._floor:
            continue
        if int(m.body_rootid[b]) in cw.ignored_bodies or b in cw.ignored_bodies:
            continue
        obstacles.append(g)
    return movers, obstacles


def test_cached_lists_follow_grasps_releases_and_the_ignore_list():
    builder = SceneBuilder()
    cube = builder.add_cube(pos=(-0.35, -0.2, 0.02))
    other = builder.add_cube(pos=(-0.30, 0.2, 0.02))
    env = HumanoidEnv(builder.build())
    kin = Kinematics(env.model)
    kin.sync(env.data.qpos)
    cw = CollisionWorld(kin)
    rng = np.random.default_rng(0)

    def check():
        for side in SIDES:
            assert (cw.movers(side), cw.obstacles(side)) == fresh_lists(cw, side)
        # Random arm postures: the distance query agrees with the same query over fresh lists.
        for _ in range(5):
            q = kin.data.qpos.copy()
            q[kin.model.jnt_qposadr[1]:] += rng.normal(0, 0.05, len(q) - kin.model.jnt_qposadr[1])
            kin.data.qpos[:] = q
            mujoco.mj_kinematics(kin.model, kin.data)
            best, pair = cw.min_distance()
            assert (best, pair) == min_distance_fresh(cw)

    check()
    cw.ignored_bodies.add(env.model.body(cube.body).id)  # in place
    check()
    kin.attach("right", other.body)
    check()
    cw.ignored_bodies = set()  # reassigned
    check()
    kin.detach("right")
    check()


def min_distance_fresh(cw: CollisionWorld):
    """The pre-cache min_distance, over lists built afresh."""
    m, d = cw.kin.model, cw.kin.data
    best, pair = 1.0, None
    for side in SIDES:
        movers, obstacles = fresh_lists(cw, side)
        held = cw.kin.attached[side][0] if side in cw.kin.attached else -1
        for i, j in cw._near_pairs(movers, obstacles):
            dd = mujoco.mj_geomDistance(m, d, movers[i], obstacles[j], cw.influence, np.zeros(6))
            if m.geom_bodyid[movers[i]] == held:
                dd += cw.held_slack
            if dd < best:
                best, pair = dd, (movers[i], obstacles[j])
    return best, pair

