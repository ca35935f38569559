"""Collision queries against the MuJoCo model itself (one world for simulation and planning).

The geoms that move with an arm (its links, its hand, and an object it holds) are checked against every
other collidable geom (table, objects, the other arm, the torso), except objects on the ignore list.
Distances come from `mj_geomDistance` on the scratch kinematics; a bounding-sphere test skips far pairs.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

import mujoco
import numpy as np

from humanoidgen.planning.broadphase import candidate_pairs
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.sim.layout import HAND_PREFIX, ROOT_BODY, SIDES, Side, arm_bodies

FAR = 1.0  # reported distance for pairs too far apart to matter


def _collidable(m: mujoco.MjModel, g: int) -> bool:
    return m.geom_contype[g] != 0 or m.geom_conaffinity[g] != 0


def _arm_body_ids(m: mujoco.MjModel, side: Side) -> set[int]:
    ids = {m.body(b).id for b in arm_bodies(side)}
    prefix = HAND_PREFIX[side] + "_"
    ids |= {b for b in range(m.nbody) if m.body(b).name.startswith(prefix)}
    return ids


@dataclass
class CollisionWorld:
    kin: Kinematics
    ignored_bodies: set[int] = field(default_factory=set)
    influence: float = 0.05  # pairs farther apart than this are not measured
    held_slack: float = 0.006
    # The obstacles (root bodies) a held object may touch with `held_slack`: what it is lifted from and what it is
    # set down on; None: every obstacle. A move sets it (`held_touch_only`): slack against everything let a
    # pinched block's path graze an open drawer's wall on its way over it, which knocked it out of the fingers.
    held_touch: frozenset[int] | None = None
    # Hand parts meant to touch something: mover geom -> (obstacle geoms, slack). Their distances to those
    # obstacles count `slack` more, so they may come that much closer than everything else (fingertips that
    # must reach the table side of a low object). Set through `allow_touch`.
    touch: dict[int, tuple[frozenset[int], float]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        m = self.kin.model
        self._arm_bodies = {s: _arm_body_ids(m, s) for s in SIDES}
        prefix = {s: HAND_PREFIX[s] + "_" for s in SIDES}
        self._finger_geoms = {s: [g for g in range(m.ngeom) if m.body(int(m.geom_bodyid[g])).name.startswith(prefix[s])
                                  and _collidable(m, g)] for s in SIDES}
        self._floor = {g for g in range(m.ngeom) if m.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE}
        self._fromto = np.zeros(6)
        # Per-geom facts the geom lists are made of, and the lists themselves per (side, held body, ignored
        # bodies): planning asks for them thousands of times per move and they change only at a grasp, a
        # release or a change of the ignore list.
        self._collidable = (m.geom_contype != 0) | (m.geom_conaffinity != 0)
        self._geom_body = m.geom_bodyid.astype(np.int64)
        self._geom_root = m.body_rootid[self._geom_body].astype(np.int64)
        self._not_floor = np.ones(m.ngeom, bool)
        self._not_floor[list(self._floor)] = False
        self._lists: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}

    # -- which geoms ---------------------------------------------------------------------------------
    def _moving_bodies(self, side: Side) -> set[int]:
        bodies = set(self._arm_bodies[side])
        if side in self.kin.attached:
            bodies.add(self.kin.attached[side][0])
        return bodies

    def movers(self, side: Side) -> list[int]:
        return self._geom_lists(side)[0].tolist()

    def obstacles(self, side: Side) -> list[int]:
        return self._geom_lists(side)[1].tolist()

    def shared_body(self) -> int | None:
        """The body both hands carry (one object held by both), or None."""
        a = self.kin.attached
        left, right = (a[s][0] if s in a else None for s in SIDES)
        return left if left is not None and left == right else None

    def _geom_lists(self, side: Side) -> tuple[np.ndarray, np.ndarray]:
        """(movers, obstacles) of `side` as geom id arrays, cached; see `movers` and `obstacles`. While both
        hands carry one object, the other arm is no obstacle: it moves with the object (the arms are checked
        against each other on the joint move, `arm_arm_distance`)."""
        held = self.kin.attached[side][0] if side in self.kin.attached else None
        shared = held is not None and self.shared_body() == held
        key = (side, held, shared, frozenset(self.ignored_bodies))
        lists = self._lists.get(key)
        if lists is None:
            if len(self._lists) > 256:  # a planner that keeps changing its ignore list: start over
                self._lists.clear()
            moving = np.isin(self._geom_body, sorted(self._moving_bodies(side)))
            ignored = np.isin(self._geom_body, sorted(self.ignored_bodies)) | np.isin(self._geom_root,
                                                                                        sorted(self.ignored_bodies))
            if shared:
                other = next(s for s in SIDES if s != side)
                ignored |= np.isin(self._geom_body, sorted(self._arm_bodies[other]))
            movers = np.flatnonzero(moving & self._collidable)
            obstacles = np.flatnonzero(~moving & self._not_floor & self._collidable & ~ignored)
            movers.flags.writeable = obstacles.flags.writeable = False
            lists = self._lists[key] = (movers, obstacles)
        return lists

    def finger_geoms(self, side: Side) -> list[int]:
        """The collidable geoms of `side`'s fingers (thumb, index, ..., not the palm)."""
        return list(self._finger_geoms[side])

    def body_geoms(self, body: int) -> frozenset[int]:
        m = self.kin.model
        return frozenset(g for g in range(m.ngeom) if int(m.geom_bodyid[g]) == body and _collidable(m, g))

    @contextmanager
    def allow_touch(self, movers: list[int], obstacles: frozenset[int], slack: float) -> Iterator[None]:
        """Within the block, `movers` may come `slack` closer to `obstacles` than the clearances ask."""
        saved = dict(self.touch)
        try:
            for g in movers:
                self.touch[g] = (obstacles, slack)
            yield
        finally:
            self.touch = saved

    @contextmanager
    def touch_only(self, side: Side, owners: set[int], slack: float) -> Iterator[None]:
        """Within the block, what moves with `side` may come `slack` closer to the obstacles named by `owners`
        (`contact_pairs`' obstacle bodies) than the clearances ask, on top of any touch already allowed."""
        geoms = frozenset(int(g) for g in self._geom_lists(side)[1] if self._owner(int(g)) in owners)
        saved = dict(self.touch)
        try:
            for g in self.movers(side):
                obstacles, had = self.touch.get(g, (frozenset(), 0.0))
                self.touch[g] = (obstacles | geoms, max(had, slack))
            yield
        finally:
            self.touch = saved

    @contextmanager
    def held_touch_only(self, roots: frozenset[int] | None) -> Iterator[None]:
        """Within the block, a held object's slack applies only against the obstacles of these root bodies."""
        saved = self.held_touch
        try:
            self.held_touch = roots
            yield
        finally:
            self.held_touch = saved

    def held_near(self, side: Side, within: float) -> frozenset[int]:
        """The root bodies of the obstacles closer than `within` to the object `side` holds, at the scratch state."""
        if side not in self.kin.attached:
            return frozenset()
        held = self.kin.attached[side][0]
        movers, obstacles = self._geom_lists(side)
        mine = movers[self._geom_body[movers] == held]
        m, d = self.kin.model, self.kin.data
        near = set()
        for i, j in self._near_pairs(mine, obstacles):
            if mujoco.mj_geomDistance(m, d, int(mine[i]), int(obstacles[j]), self.influence, self._fromto) < within:
                near.add(int(self._geom_root[obstacles[j]]))
        return frozenset(near)

    def pair_distance(self, g1: int, g2: int) -> float:
        """Distance between two geoms at the scratch state (FAR beyond `influence`)."""
        return float(mujoco.mj_geomDistance(self.kin.model, self.kin.data, g1, g2, self.influence, self._fromto))

    def _slack(self, mover: int, obstacle: int) -> float:
        t = self.touch.get(mover)
        return t[1] if t is not None and obstacle in t[0] else 0.0

    # -- queries --------------------------------------------------------------------------------------
    def _near_pairs(self, movers: list[int] | np.ndarray, obstacles: list[int] | np.ndarray) -> np.ndarray:
        """Index pairs (i, j) of movers[i], obstacles[j] whose bounding spheres are within `influence`."""
        m, d = self.kin.model, self.kin.data
        mv, ob = np.asarray(movers), np.asarray(obstacles)
        centres = np.linalg.norm(d.geom_xpos[mv][:, None, :] - d.geom_xpos[ob][None, :, :], axis=2)
        gaps = centres - m.geom_rbound[mv][:, None] - m.geom_rbound[ob][None, :]
        return np.argwhere(gaps <= self.influence)

    def mover_distances(self, side: Side, movers: list[int], obstacles: list[int]) -> tuple[np.ndarray, np.ndarray]:
        """Per moving geom: distance to its nearest obstacle, and its gradient over the arm joints (n x 7)."""
        dist = np.full(len(movers), FAR)
        grad = np.zeros((len(movers), 7))
        if not movers or not obstacles:
            return dist, grad
        m, d = self.kin.model, self.kin.data
        nearest: dict[int, np.ndarray] = {}
        touch = self.touch
        for i, j in self._near_pairs(movers, obstacles):
            dd = mujoco.mj_geomDistance(m, d, movers[i], obstacles[j], self.influence, self._fromto)
            if touch:
                dd += self._slack(movers[i], obstacles[j])
            if dd < dist[i]:
                dist[i] = dd
                nearest[i] = self._fromto.copy()
        for i, ft in nearest.items():
            p1, p2 = ft[:3], ft[3:]
            v = p2 - p1
            n = np.linalg.norm(v)
            if n > 1e-9:
                normal = v / n * (1.0 if dist[i] >= 0 else -1.0)  # from the mover toward the obstacle
                J = self.kin.point_jacobian(side, p1, body=int(m.geom_bodyid[movers[i]]))
                grad[i] = -normal @ J
        return dist, grad

    def _slackened_distance(self, g1: int, g2: int, held: int) -> float:
        """Mover g1 to obstacle g2 at the scratch state, plus the slacks: `held_slack` when g1 belongs to the
        held body `held`, and any touch slack (`allow_touch`, `touch_only`)."""
        dd = mujoco.mj_geomDistance(self.kin.model, self.kin.data, g1, g2, self.influence, self._fromto)
        if self._geom_body[g1] == held and (self.held_touch is None or self._geom_root[g2] in self.held_touch):
            dd += self.held_slack
        if self.touch:
            dd += self._slack(g1, g2)
        return dd

    def min_distance(self, sides: tuple[Side, ...] = SIDES) -> tuple[float, tuple[int, int] | None]:
        """Smallest distance between any moving geom of `sides` and its obstacles, and that pair.

        A held object's distances count `held_slack` more: it may touch what it is set down on or lifted
        from, where the hand itself must keep clear."""
        best, pair = FAR, None
        for side in sides:
            movers, obstacles = self._geom_lists(side)
            if not len(movers) or not len(obstacles):
                continue
            held = self.kin.attached[side][0] if side in self.kin.attached else -1
            for i, j in self._near_pairs(movers, obstacles):
                g1, g2 = int(movers[i]), int(obstacles[j])
                dd = self._slackened_distance(g1, g2, held)
                if dd < best:
                    best, pair = dd, (g1, g2)
        return best, pair

    def clear_of(self, sides: tuple[Side, ...], clearance: float) -> bool:
        """`min_distance(sides)[0] > clearance`, answered with less work: the path planners ask it thousands of
        times per move and need only the yes or no. Only pairs that may come within the clearance are measured
        (broadphase: a pair's distance is at least its bounding spheres' gap, or a box obstacle's, and the
        slacks only add to it), and the first pair too close ends the search."""
        if self.held_slack < 0 or any(t[1] < 0 for t in self.touch.values()):
            return self.min_distance(sides)[0] > clearance  # a negative slack would void the sphere bound
        cut = max(clearance, 0.0)
        m, d = self.kin.model, self.kin.data
        for side in sides:
            movers, obstacles = self._geom_lists(side)
            if not len(movers) or not len(obstacles):
                continue
            held = self.kin.attached[side][0] if side in self.kin.attached else -1
            for i, j in candidate_pairs(m, d, movers, obstacles, cut):
                if self._slackened_distance(int(movers[i]), int(obstacles[j]), held) <= clearance:
                    return False
        return True

    def closest_pair(self, movers, obstacles) -> tuple[float, tuple[int, int] | None]:
        """Smallest distance between any geom of `movers` and any of `obstacles` at the scratch state (no slack),
        and that pair of geoms."""
        best, pair = FAR, None
        m, d = self.kin.model, self.kin.data
        mv, ob = np.asarray(movers, int), np.asarray(obstacles, int)
        if not len(mv) or not len(ob):
            return best, pair
        for i, j in self._near_pairs(mv, ob):
            dd = mujoco.mj_geomDistance(m, d, int(mv[i]), int(ob[j]), self.influence, self._fromto)
            if dd < best:
                best, pair = dd, (int(mv[i]), int(ob[j]))
        return best, pair

    def arm_arm_distance(self) -> float:
        """Smallest distance between anything moving with the left arm and anything moving with the right (an
        object both hands hold is in both hands, not between them)."""
        left, right = self._geom_lists("left")[0], self._geom_lists("right")[0]
        if (shared := self.shared_body()) is not None:
            left, right = (g[self._geom_body[g] != shared] for g in (left, right))
        return self.closest_pair(left, right)[0]

    def contact_pairs(self, sides: tuple[Side, ...], clearance: float = 0.0) -> list[tuple[int, int, float]]:
        """(moving body, obstacle body, distance) for each obstacle body closer than `clearance` to something
        moving: its deepest contact, deepest first. Obstacles are named by their object (root) body."""
        m, d = self.kin.model, self.kin.data
        worst: dict[tuple[int, int], float] = {}
        for side in sides:
            movers, obstacles = self._geom_lists(side)
            if not len(movers) or not len(obstacles):
                continue
            for i, j in self._near_pairs(movers, obstacles):
                g1, g2 = int(movers[i]), int(obstacles[j])
                dd = mujoco.mj_geomDistance(m, d, g1, g2, self.influence, self._fromto) + self._slack(g1, g2)
                if dd < clearance:
                    key = (self._owner(g1), self._owner(g2))
                    worst[key] = min(worst.get(key, FAR), dd)
        per_obstacle: dict[int, tuple[int, float]] = {}
        for (b1, b2), dd in worst.items():
            if b2 not in per_obstacle or dd < per_obstacle[b2][1]:
                per_obstacle[b2] = (b1, dd)
        return sorted(((b1, b2, dd) for b2, (b1, dd) in per_obstacle.items()), key=lambda x: x[2])

    def penetrations(self, sides: tuple[Side, ...], clearance: float = 0.0) -> list[tuple[str, float]]:
        """Every (moving body, obstacle body) closer than `clearance`, deepest first: "a and b", distance."""
        m = self.kin.model
        return [(f"{m.body(b1).name} and {m.body(b2).name}", dd) for b1, b2, dd in self.contact_pairs(sides, clearance)]

    def _owner(self, g: int) -> int:
        """The body to name for a geom: the object (root body), or the robot link itself."""
        m = self.kin.model
        b = int(m.geom_bodyid[g])
        root = int(m.body_rootid[b])
        return b if root == m.body(ROOT_BODY).id or root == 0 else root

    def describe_pair(self, pair: tuple[int, int]) -> str:
        m = self.kin.model
        return " and ".join(m.body(self._owner(g)).name for g in pair)
