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
from humanoidgen.planning.constraints import Constraint, Const
from humanoidgen.planning.kinematics import Kinematics
from humanoidgen.sim.layout import Side


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
    w_reg: float = 0.02
    n_random_seeds: int = 6
    seed: int = 0
    major_iterations: int = 200

    def solve(self, side: Side, constraints: list[Constraint], q_current: np.ndarray,
              q_nominal: np.ndarray, avoid_collisions: bool = True) -> GoalResult:
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

                prog.AddCost(_lift(cost_fn, 1), q)
            if with_collisions and movers:
                def dist_fn(x):
                    at(x)
                    return self.collisions.mover_distances(side, movers, obstacles)

                prog.AddConstraint(_lift(dist_fn, len(movers)), np.full(len(movers), self.clearance),
                                   np.full(len(movers), np.inf), q, description="collision")
            return prog, q

        prog, q = build(True)
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
        for s in seeds:
            tried += 1
            result = solver.Solve(prog, s, options)
            qs = np.clip(result.GetSolution(q), arm.lo, arm.hi)
            at(qs)
            viol = max([c.violation(self.kin) for c in hard], default=0.0)
            clear = min(self.collisions.mover_distances(side, movers, obstacles)[0], default=np.inf) if movers else None
            ok = viol < 2e-3 and (clear is None or clear >= self.clearance - 1e-3)
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
            if movers:
                # Would the constraints hold if collisions did not count? Then collisions are the reason.
                free_prog, free_q = build(False)
                for s in seeds[:2]:
                    res = solver.Solve(free_prog, s, options)
                    qf = np.clip(res.GetSolution(free_q), arm.lo, arm.hi)
                    at(qf)
                    if max([c.violation(self.kin) for c in hard], default=0.0) < 2e-3:
                        d, pair = self.collisions.min_distance((side,))
                        if pair is not None and d < self.clearance:
                            violations.append(
                                f"collision: the constraints are reachable only with {self.collisions.describe_pair(pair)} "
                                f"{max(-d, 0) * 1000:.1f} mm into each other (need {self.clearance * 1000:.0f} mm clearance); "
                                "ignore that object if the contact is intended"
                            )
                        break
            if not violations:
                at(closest[1])
                violations = [c.describe(self.kin) for c in hard if c.violation(self.kin) >= 2e-3]
            best = GoalResult(False, None, violations=violations or ["solver did not converge"], seeds_tried=tried)
        at(best.q if best.q is not None else q_current)
        self.kin.data.qpos[:] = base_qpos
        self.kin.forward()
        best.solve_time = time.perf_counter() - t0
        return best
