"""Collision-free joint-space paths for one arm or both, and their timing.

- `JointSpace`: which joints are planned ("left"/"right": 7-D, "all": 14-D, left then right) and their limits.
- `is_valid` / `segment_valid`: a configuration (or the straight segment between two) is clear of obstacles,
  measured by `CollisionWorld` on the scratch `Kinematics` (everything but the planned arms stays as synced).
- `plan_rrt_connect`: OMPL's RRT-Connect, then shortcutting; returns a `PathResult`.
- `straight_path`, `time_parametrize`: joint interpolation and a trapezoidal velocity profile sampled at the
  control period.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np

from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.sim.layout import SIDES, Side

Which = Literal["left", "right", "all"]
StateCheck = Callable[[Kinematics], bool]  # a further condition on a state, read from the kinematics set to it
ARM_DOF = 7

# H1-2 arm joint limits used for timing (rad/s, rad/s^2); conservative against the motors' ratings.
V_MAX = 1.5
A_MAX = 4.0
# Largest joint step between collision-checked states along a segment (rad): ~1 cm at the fingertips.
DEFAULT_RESOLUTION = 0.02
LIMIT_TOL = 5e-3  # joint values this far outside the limits still count as inside (a loaded arm settles a hair past them)


# -- joint space --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class JointSpace:
    """The planned joints: one arm (7-D) or both (14-D, left then right), with their qpos addresses and limits."""

    which: Which
    sides: tuple[Side, ...]
    qadr: np.ndarray
    lo: np.ndarray
    hi: np.ndarray

    @classmethod
    def of(cls, kin: Kinematics, which: Which) -> JointSpace:
        if which == "all":
            sides: tuple[Side, ...] = SIDES
        elif which in SIDES:
            sides = (which,)
        else:
            raise ValueError(f"which must be 'left', 'right' or 'all', got {which!r}")
        arms = [kin.arms[s] for s in sides]
        return cls(which=which, sides=sides, qadr=np.concatenate([a.qadr for a in arms]),
                   lo=np.concatenate([a.lo for a in arms]), hi=np.concatenate([a.hi for a in arms]))

    @property
    def dof(self) -> int:
        return len(self.qadr)

    def current(self, kin: Kinematics) -> np.ndarray:
        """The planned joints' values in the scratch kinematics."""
        return kin.data.qpos[self.qadr].copy()

    def within_limits(self, q: np.ndarray) -> bool:
        return bool(np.all(q >= self.lo - LIMIT_TOL) and np.all(q <= self.hi + LIMIT_TOL))

    def check(self, q: np.ndarray, name: str = "q") -> np.ndarray:
        q = np.asarray(q, float)
        if q.shape != (self.dof,):
            raise ValueError(f"{name} must have shape ({self.dof},) for {self.which!r}, got {q.shape}")
        return q


def _space(kin: Kinematics, sides: Which | JointSpace) -> JointSpace:
    return sides if isinstance(sides, JointSpace) else JointSpace.of(kin, sides)


# -- validity -----------------------------------------------------------------------------------------------
def _set(kin: Kinematics, space: JointSpace, q: np.ndarray) -> None:
    kin.data.qpos[space.qadr] = q
    kin.forward()  # also moves objects attached to a hand


def is_valid(kin: Kinematics, cw: CollisionWorld, sides: Which | JointSpace, q: np.ndarray,
             clearance: float = 0.0, state_ok: StateCheck | None = None) -> bool:
    """True when `q` is within the joint limits, every moving geom of the planned arm(s) keeps more than
    `clearance` from its obstacles and `state_ok` (if given) accepts the kinematics at `q`. Leaves the scratch
    kinematics at `q`.

    For "all" both sides are measured; each side's obstacles include the other arm, so arm-arm is covered."""
    space = _space(kin, sides)
    if not space.within_limits(q):
        return False
    _set(kin, space, q)
    if state_ok is not None and not state_ok(kin):
        return False
    return cw.clear_of(space.sides, clearance)


def collision_reason(kin: Kinematics, cw: CollisionWorld, sides: Which | JointSpace, q: np.ndarray,
                     clearance: float = 0.0) -> str:
    """Why `q` is invalid, in words ('' when it is valid)."""
    space = _space(kin, sides)
    if not space.within_limits(q):
        bad = np.flatnonzero((q < space.lo - LIMIT_TOL) | (q > space.hi + LIMIT_TOL))
        return f"joints {bad.tolist()} outside their limits"
    _set(kin, space, q)
    d, pair = cw.min_distance(space.sides)
    if d > clearance:
        return ""
    return f"{cw.describe_pair(pair) if pair else 'geoms'} at distance {d:.4f} m (need > {clearance:.4f})"


def _coarse_to_fine(n: int) -> list[int]:
    """0..n ordered endpoints first, then midpoints of ever finer halvings: a collision in the middle of a
    segment (the usual case) is found after a few checks instead of n/2."""
    order = [0, n] if n > 0 else [0]
    seen = set(order)
    stride = 1 << max(n, 1).bit_length()
    while stride >= 1:
        for i in range(stride, n, stride):
            if i not in seen:
                seen.add(i)
                order.append(i)
        stride //= 2
    return order


def segment_valid(kin: Kinematics, cw: CollisionWorld, sides: Which | JointSpace, q0: np.ndarray,
                  q1: np.ndarray, resolution: float = DEFAULT_RESOLUTION, clearance: float = 0.0,
                  state_ok: StateCheck | None = None) -> bool:
    """True when every state on the straight joint-space segment q0 -> q1, sampled so that no joint moves
    more than `resolution` between checks (both ends included), is valid."""
    space = _space(kin, sides)
    q0, q1 = np.asarray(q0, float), np.asarray(q1, float)
    n = max(1, int(np.ceil(np.max(np.abs(q1 - q0)) / resolution - 1e-9)))
    for i in _coarse_to_fine(n):
        if not is_valid(kin, cw, space, q0 + (i / n) * (q1 - q0), clearance, state_ok):
            return False
    return True


# -- paths --------------------------------------------------------------------------------------------------
def straight_path(q0: np.ndarray, q1: np.ndarray, max_step: float = DEFAULT_RESOLUTION) -> np.ndarray:
    """Linear joint interpolation q0 -> q1 (both included), no joint moving more than `max_step` per step."""
    q0, q1 = np.asarray(q0, float), np.asarray(q1, float)
    if max_step <= 0:
        raise ValueError("max_step must be positive")
    n = max(1, int(np.ceil(np.max(np.abs(q1 - q0), initial=0.0) / max_step - 1e-9)))
    return q0 + np.linspace(0.0, 1.0, n + 1)[:, None] * (q1 - q0)


def path_length(path: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())


def shortcut(path: np.ndarray, valid_segment: Callable[[np.ndarray, np.ndarray], bool], iters: int,
             rng: np.random.Generator) -> np.ndarray:
    """Random shortcutting: join two random points of the path (anywhere on it, not only at waypoints) by a
    straight segment when that segment is valid; then drop every waypoint whose neighbours see each other.
    Deterministic for a given `rng` state, and bounded by `iters` (unlike time-limited simplifiers)."""
    path = np.asarray(path, float)
    for _ in range(iters):
        if len(path) < 3:
            break
        seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        if cum[-1] <= 0:
            break
        t0, t1 = np.sort(rng.uniform(0.0, cum[-1], 2))
        a = min(int(np.searchsorted(cum, t0, side="right")) - 1, len(seg) - 1)
        b = min(int(np.searchsorted(cum, t1, side="right")) - 1, len(seg) - 1)
        if a == b:  # same segment: already straight
            continue
        p0 = path[a] + (t0 - cum[a]) / max(seg[a], 1e-12) * (path[a + 1] - path[a])
        p1 = path[b] + (t1 - cum[b]) / max(seg[b], 1e-12) * (path[b + 1] - path[b])
        if valid_segment(p0, p1):
            path = np.vstack([path[:a + 1], p0, p1, path[b + 1:]])
            path = _dedupe(path)
    # Greedy vertex pruning: a cheap last pass that removes corners the random draws missed.
    out = [path[0]]
    i = 0
    while i < len(path) - 1:
        j = len(path) - 1
        while j > i + 1 and not valid_segment(path[i], path[j]):
            j -= 1
        out.append(path[j])
        i = j
    return np.array(out)


def _dedupe(path: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    keep = np.concatenate([[True], np.max(np.abs(np.diff(path, axis=0)), axis=1) > tol])
    keep[-1] = True
    return path[keep]


@dataclass(frozen=True)
class PathResult:
    """Outcome of a planning query.

    path: waypoints (n, dof) from start to goal, each straight segment between them valid at the planning
        resolution; None when no path was found.
    reason: "direct" (the straight segment was free), "planned" (RRT-Connect + shortcutting), or why it failed
        ("start invalid: ...", "goal invalid: ...", "no path within ... s").
    planning_time: wall seconds spent (validity checks, search and shortcutting).
    """

    path: np.ndarray | None
    reason: str
    planning_time: float

    @property
    def ok(self) -> bool:
        return self.path is not None


def _seed_ompl(seed: int) -> None:
    from ompl import util as ou

    # OMPL hands every new RNG (planner, samplers) a seed drawn from one generator; re-seeding it before the
    # objects are built makes the run repeat. OMPL logs an error when seeded a second time in a process even
    # though the re-seed works for RNGs created afterwards, so hush the log meanwhile.
    level = ou.getLogLevel()
    ou.setLogLevel(ou.LOG_NONE)
    try:
        ou.RNG.setSeed(int(seed) if seed > 0 else 1)  # OMPL rejects seed 0
    finally:
        ou.setLogLevel(level)


def plan_rrt_connect(kin: Kinematics, cw: CollisionWorld, sides: Which | JointSpace, q_start: np.ndarray,
                     q_goal: np.ndarray, time_limit: float = 2.0, seed: int = 0, clearance: float = 0.0,
                     resolution: float = DEFAULT_RESOLUTION, shortcut_iters: int = 100,
                     try_direct: bool = True, state_ok: StateCheck | None = None) -> PathResult:
    """A collision-free joint path q_start -> q_goal for the arm(s) `sides`.

    The rest of the scene (the other arm when planning one, hands, objects, attached objects) stays as last
    synced into `kin`; the planned joints are restored to their values on entry before returning.
    `state_ok` is a further condition on every state (e.g. how far a carried object may turn on the way).
    Same inputs and seed give the same path as long as the search finishes within `time_limit`."""
    from ompl import base as ob
    from ompl import geometric as og
    from ompl import util as ou

    t_begin = time.perf_counter()
    space = _space(kin, sides)
    q_start, q_goal = space.check(q_start, "q_start"), space.check(q_goal, "q_goal")
    saved = space.current(kin)
    log_level = ou.getLogLevel()

    def result(path: np.ndarray | None, reason: str) -> PathResult:
        return PathResult(path, reason, time.perf_counter() - t_begin)

    def valid(q: np.ndarray) -> bool:
        return is_valid(kin, cw, space, q, clearance, state_ok)

    def valid_segment(a: np.ndarray, b: np.ndarray) -> bool:
        return segment_valid(kin, cw, space, a, b, resolution, clearance, state_ok)

    try:
        for name, q in (("start", q_start), ("goal", q_goal)):
            why = collision_reason(kin, cw, space, q, clearance)
            if why:
                return result(None, f"{name} invalid: {why}")
        if try_direct and valid_segment(q_start, q_goal):
            return result(np.stack([q_start, q_goal]), "direct")

        _seed_ompl(seed)
        ou.setLogLevel(ou.LOG_WARN)  # OMPL's info lines ("RRTConnect: created N states") are noise here
        dof = space.dof
        state_space = ob.RealVectorStateSpace(dof)
        bounds = ob.RealVectorBounds(dof)
        for i in range(dof):
            bounds.setLow(i, float(space.lo[i]))
            bounds.setHigh(i, float(space.hi[i]))
        state_space.setBounds(bounds)
        # OMPL checks motions every fraction x (bounds' diagonal) in the Euclidean norm; this keeps the largest
        # joint step at or below `resolution`, like segment_valid.
        state_space.setLongestValidSegmentFraction(resolution / state_space.getMaximumExtent())
        ss = og.SimpleSetup(state_space)
        ss.setStateValidityChecker(lambda s: valid(np.fromiter((s[i] for i in range(dof)), float, dof)))
        start, goal = state_space.allocState(), state_space.allocState()
        for i in range(dof):
            start[i], goal[i] = float(q_start[i]), float(q_goal[i])
        ss.setStartAndGoalStates(start, goal)
        ss.setPlanner(og.RRTConnect(ss.getSpaceInformation()))
        ss.solve(float(time_limit))
        if not ss.haveExactSolutionPath():
            return result(None, f"no path within {time_limit:.2f} s")
        raw = ss.getSolutionPath()
        path = np.array([[raw.getState(k)[i] for i in range(dof)] for k in range(raw.getStateCount())])
        # Pin the ends exactly (OMPL copies states, but keep the caller's floats bit-for-bit).
        path[0], path[-1] = q_start, q_goal
        path = shortcut(_dedupe(path), valid_segment, shortcut_iters, np.random.default_rng(seed))
        return result(path, "planned")
    finally:
        _set(kin, space, saved)
        ou.setLogLevel(log_level)


# -- timing -------------------------------------------------------------------------------------------------
def _drop_collinear(path: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Merge consecutive segments that point the same way: the trajectory then stops only at real corners."""
    path = _dedupe(np.asarray(path, float))
    if len(path) < 3:
        return path
    out = [path[0]]
    for k in range(1, len(path) - 1):
        u = path[k] - out[-1]
        w = path[k + 1] - path[k]
        cos = float(u @ w) / (np.linalg.norm(u) * np.linalg.norm(w))
        if cos < 1.0 - tol:
            out.append(path[k])
    out.append(path[-1])
    return np.array(out)


def _trapezoid(V: float, A: float) -> tuple[float, float, float]:
    """Rest-to-rest profile of s from 0 to 1 with |s'| <= V, |s''| <= A: (accel time, peak speed, duration)."""
    if V * V / A >= 1.0:  # never reaches V: triangle
        ta = np.sqrt(1.0 / A)
        return ta, A * ta, 2 * ta
    ta = V / A
    return ta, V, 1.0 / V + ta


def _trapezoid_s(t: np.ndarray, ta: float, vp: float, T: float) -> np.ndarray:
    a = vp / ta
    t = np.clip(t, 0.0, T)
    return np.where(t < ta, 0.5 * a * t ** 2,
                    np.where(t <= T - ta, 0.5 * a * ta ** 2 + vp * (t - ta), 1.0 - 0.5 * a * (T - t) ** 2))


def time_parametrize(path: np.ndarray, v_max: np.ndarray | float = V_MAX, a_max: np.ndarray | float = A_MAX,
                     dt: float = 0.02) -> tuple[np.ndarray, np.ndarray]:
    """Sample the piecewise-linear `path` (n, dof) every `dt` seconds: (times (m,), samples (m, dof)).

    Each straight stretch runs a rest-to-rest trapezoidal profile along its length, scaled by the joint that
    limits it most (per-joint `v_max`, `a_max`). A piecewise-linear path can only turn a corner at rest
    without an unbounded acceleration, so the arm stops at each corner (collinear waypoints are merged first;
    shortcut paths have few corners). Every stretch is stretched to a whole number of periods, so the
    samples hit every corner exactly, start at path[0] and end at path[-1] at rest."""
    path = np.atleast_2d(np.asarray(path, float))
    dof = path.shape[1]
    v = np.broadcast_to(np.asarray(v_max, float), (dof,))
    a = np.broadcast_to(np.asarray(a_max, float), (dof,))
    if dt <= 0 or np.any(v <= 0) or np.any(a <= 0):
        raise ValueError("dt, v_max and a_max must be positive")
    corners = _drop_collinear(path)
    times, samples, t0 = [0.0], [corners[0]], 0.0
    for q0, q1 in zip(corners[:-1], corners[1:]):
        d = np.abs(q1 - q0)
        moving = d > 0
        V, A = float(np.min(v[moving] / d[moving])), float(np.min(a[moving] / d[moving]))
        ta, vp, T = _trapezoid(V, A)
        n = max(1, int(np.ceil(T / dt - 1e-9)))
        c = T / (n * dt)  # <= 1: slowing time by c scales speed by c and acceleration by c^2
        tk = np.arange(1, n + 1) * dt
        s = _trapezoid_s(c * tk, ta, vp, T)
        s[-1] = 1.0
        samples.extend(q0 + s[:, None] * (q1 - q0))
        times.extend(t0 + tk)
        t0 += n * dt
    return np.array(times), np.array(samples)
