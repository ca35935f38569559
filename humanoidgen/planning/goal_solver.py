"""The goal-pose solver: arm joints that satisfy the relational constraints (paper eq. for theta_T).

    min   sum_i w_i c_i(q)  +  w_reg |q - q_nominal|^2
    s.t.  hard constraints within their bounds, joint limits, and every moving geom at least `clearance`
          from every obstacle that is not ignored.

Solved with SNOPT through pydrake's MathematicalProgram; kinematics, Jacobians and distances come from
the MuJoCo model (one world). Several seeds (the current posture, the nominal posture, random ones); the
best feasible solution wins. A failure is data: which constraints are violated and by how much.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from pydrake.autodiffutils import ExtractGradient, ExtractValue, InitializeAutoDiff
from pydrake.solvers import MathematicalProgram, SnoptSolver, SolverOptions

from humanoidgen.planning.collision import CollisionWorld
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.sim.layout import Side

# Bounds already include the constraints' tolerances (1 mm, 0.5 deg); this only absorbs round-off.
VIOLATION_SLACK = 1e-4


def _depth(d: float) -> str:
    """A contact's distance in words: how deep, or how close (a clearance not kept)."""
    return f"{-d * 1000:.1f} mm deep" if d < 0 else f"{d * 1000:.1f} mm apart"


@dataclass
class GoalResult:
    """Outcome of a goal solve. On failure `violations` says which constraint missed and by how much."""

    success: bool
    q: np.ndarray | None
    ee_pos: np.ndarray | None = None
    ee_mat: np.ndarray | None = None
    cost: float = np.inf
    violations: list[str] = field(default_factory=list)
    min_clearance: float | None = None
    seeds_tried: int = 0
    solve_time: float = 0.0
    # On a failure caused by collisions: (moving body, obstacle body, distance) of the contacts the goal needs.
    contacts: list[tuple[int, int, float]] = field(default_factory=list)
    miss: float | None = None  # on a failure: how far (m) the closest solution's hand points are from their targets
    # A held part followed only partway (the arm's reach ends): the arm configuration and the part's joint value
    # there, for a move that goes that far and grips the part again to go on (planning/recoveries/grip_again.py).
    partial: tuple[np.ndarray, float] | None = None

    def message(self) -> str:
        if self.success:
            return f"solved in {self.solve_time * 1000:.0f} ms ({self.seeds_tried} seed(s))"
        return "no joint configuration satisfies the constraints: " + "; ".join(self.violations)


def _lift(fn, dim_out: int):
    """Wrap `fn(q) -> (value, jacobian)` for Drake: plain floats in, or AutoDiff with the chain rule."""

    def wrapped(x):
        if x.dtype == float:
            return fn(x)[0]
        q = ExtractValue(x).reshape(-1)
        v, J = fn(q)
        return InitializeAutoDiff(np.asarray(v).reshape(dim_out, 1), np.asarray(J).reshape(dim_out, -1) @ ExtractGradient(x))

    return wrapped


@dataclass
class GoalSolver:
    kin: Kinematics
    collisions: CollisionWorld
    clearance: float = 0.005
    held_clearance: float = 0.002
    w_reg: float = 0.02
    n_random_seeds: int = 6
    n_extra_seeds: int = 18  # solve(thorough=True): a second round of random seeds when the first found nothing
    seed: int = 0
    major_iterations: int = 200

    def solve(self, side: Side, constraints: list[Constraint], q_current: np.ndarray,
              q_nominal: np.ndarray, avoid_collisions: bool = True, thorough: bool = False,
              time_limit: float | None = None, max_seeds: int | None = None) -> GoalResult:
        """`thorough`: if the usual seeds find nothing, try `n_extra_seeds` more random ones (slow; for a last try).
        `time_limit` (s): no further seed is started after this long (the current posture's and the nominal
        one's always are); for the planner's wider, optional searches. `max_seeds`: at most this many seeds."""
        t0 = time.perf_counter()
        hard = [c for c in constraints if not c.soft]
        soft = [c for c in constraints if c.soft]
        for c in constraints:
            if c.side != side:
                raise ValueError(f"constraint {c.name!r} is on the {c.side} hand, not the {side} hand")
        arm = self.kin.arms[side]
        base_qpos = self.kin.data.qpos.copy()
        movers = self.collisions.movers(side) if avoid_collisions else []
        obstacles = self.collisions.obstacles(side) if avoid_collisions else []

        # A held object may come closer to things than the hand: it is meant to be set down on or next to them.
        held_body = self.kin.attached[side][0] if side in self.kin.attached else None
        lower = np.array([self.held_clearance if self.kin.model.geom_bodyid[g] == held_body else self.clearance
                          for g in movers])

        def at(q):
            self.kin.data.qpos[:] = base_qpos
            self.kin.set_arm(side, q)
            self.kin.forward()

        def build(with_collisions: bool) -> tuple[MathematicalProgram, np.ndarray]:
            prog = MathematicalProgram()
            q = prog.NewContinuousVariables(7, "q")
            prog.AddBoundingBoxConstraint(arm.lo, arm.hi, q)
            prog.AddQuadraticErrorCost(self.w_reg * np.eye(7), q_nominal, q)
            for c in hard:
                lo, hi = c.bounds()

                def fn(x, c=c):
                    at(x)
                    return c.evaluate(self.kin)

                prog.AddConstraint(_lift(fn, len(lo)), lo, hi, q, description=c.name)
            for c in soft:
                def cost_fn(x, c=c):
                    at(x)
                    v, g = c.cost(self.kin)
                    return np.array([v]), g[None]

                prog.AddCost(lambda x, f=_lift(cost_fn, 1): f(x).reshape(-1)[0], q)  # Drake wants a scalar cost
            if with_collisions and movers:
                def dist_fn(x):
                    at(x)
                    return self.collisions.mover_distances(side, movers, obstacles)

                prog.AddConstraint(_lift(dist_fn, len(movers)), lower, np.full(len(movers), np.inf), q,
                                   description="collision")
            return prog, q

        prog, q = build(True)
        free_prog, free_q = build(False) if movers else (prog, q)
        solver = SnoptSolver()
        options = SolverOptions()
        options.SetOption(solver.solver_id(), "Major iterations limit", self.major_iterations)
        options.SetOption(solver.solver_id(), "Major feasibility tolerance", 1e-5)
        options.SetOption(solver.solver_id(), "Major optimality tolerance", 1e-4)
        rng = np.random.default_rng(self.seed)
        seeds = [np.clip(q_current, arm.lo, arm.hi), np.clip(q_nominal, arm.lo, arm.hi)]
        seeds += [rng.uniform(arm.lo, arm.hi) for _ in range(self.n_random_seeds)]
        best: GoalResult | None = None
        closest: tuple[float, np.ndarray] | None = None
        tried = 0
        def check(qs: np.ndarray) -> tuple[float, float | None]:
            at(qs)
            viol = max([c.violation(self.kin) for c in hard], default=0.0)
            if not movers:
                return viol, None
            dists = self.collisions.mover_distances(side, movers, obstacles)[0]
            return viol, float(np.min(dists - lower)) + self.clearance  # the tightest margin, as a clearance

        def rounds():
            yield from seeds
            if thorough and best is None:  # near the edge of reach a solution may lie in a basin few seeds find
                yield from (rng.uniform(arm.lo, arm.hi) for _ in range(self.n_extra_seeds))

        for s in rounds():
            if time_limit is not None and tried >= 2 and time.perf_counter() - t0 > time_limit:
                break
            if max_seeds is not None and tried >= max_seeds:
                break
            tried += 1
            # Solve without collisions first (cheap and smooth); only if that lands in contact, solve again
            # with the distance constraints, starting from there.
            qs = np.clip(solver.Solve(free_prog, s, options).GetSolution(free_q), arm.lo, arm.hi)
            viol, clear = check(qs)
            late = time_limit is not None and time.perf_counter() - t0 > time_limit
            if movers and not late and (viol >= VIOLATION_SLACK or clear < self.clearance - 1e-3):
                # From the free solution (near, but in contact), else from the seed itself (SNOPT can stall
                # pushing a link out of a deep contact it starts in).
                for start in ([qs, s] if viol < VIOLATION_SLACK else [s]):
                    qc = np.clip(solver.Solve(prog, start, options).GetSolution(q), arm.lo, arm.hi)
                    viol_c, clear_c = check(qc)
                    if viol_c < VIOLATION_SLACK or viol_c <= viol:
                        qs, viol, clear = qc, viol_c, clear_c
                    if viol < VIOLATION_SLACK and clear >= self.clearance - 1e-3:
                        break
            at(qs)
            ok = viol < VIOLATION_SLACK and (clear is None or clear >= self.clearance - 1e-3)
            cost = float(self.w_reg * np.sum((qs - q_nominal) ** 2) + sum(c.cost(self.kin)[0] for c in soft))
            if ok and (best is None or cost < best.cost - 1e-6):
                p, R = self.kin.ee_pose(side)
                best = GoalResult(True, qs, p, R, cost, [], clear, tried)
                if tried <= 2:  # a good solution from the current or nominal posture is enough
                    break
            score = viol + max(0.0, self.clearance - (clear if clear is not None else np.inf))
            if closest is None or score < closest[0]:
                closest = (score, qs)
        if best is None:
            assert closest is not None
            violations: list[str] = []
            contacts: list[tuple[int, int, float]] = []
            if movers:
                # Would the constraints hold if collisions did not count? Then collisions are the reason.
                for s in seeds[:2]:
                    res = solver.Solve(free_prog, s, options)
                    qf = np.clip(res.GetSolution(free_q), arm.lo, arm.hi)
                    at(qf)
                    if max([c.violation(self.kin) for c in hard], default=0.0) < VIOLATION_SLACK:
                        contacts = self.collisions.contact_pairs((side,), self.clearance)
                        hits = [(f"{self.kin.model.body(b1).name} and {self.kin.model.body(b2).name}", d)
                                for b1, b2, d in contacts]
                        if hits:
                            listed = ", ".join(f"{what} ({_depth(d)})" for what, d in hits)
                            violations.append(
                                f"collision: the constraints are reachable only with these in contact: {listed} "
                                f"(need {self.clearance * 1000:.0f} mm clearance); ignore an object if the contact "
                                "is intended"
                            )
                        break
            if not violations:
                at(closest[1])
                violations = [c.describe(self.kin) for c in hard if c.violation(self.kin) >= VIOLATION_SLACK]
            if not violations and movers:
                # The closest solution meets the constraints but not the clearance: say what it touches.
                contacts = self.collisions.contact_pairs((side,), self.clearance)
                if contacts:
                    listed = ", ".join(f"{self.kin.model.body(b1).name} and {self.kin.model.body(b2).name} "
                                       f"({_depth(d)})" for b1, b2, d in contacts)
                    violations = [f"collision: the closest solution found has these in contact: {listed} "
                                  f"(need {self.clearance * 1000:.0f} mm clearance)"]
            at(closest[1])
            miss = max([c.violation(self.kin) for c in hard if getattr(c, "type", "") in ("point2point", "point2line")],
                       default=None)
            best = GoalResult(False, None, violations=violations or ["solver did not converge"], seeds_tried=tried,
                              contacts=contacts if violations else [], miss=miss)
        at(best.q if best.q is not None else q_current)
        self.kin.data.qpos[:] = base_qpos
        self.kin.forward()
        best.solve_time = time.perf_counter() - t0
        return best
