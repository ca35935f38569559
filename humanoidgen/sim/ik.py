"""A small damped-least-squares IK on the MuJoCo model: a point of the hand to a position, and hand axes to
directions. Enough for reachability checks and initial postures; the planner's goal solver (pydrake, with
collisions and relational constraints) is separate."""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from humanoidgen.sim.layout import ARM_JOINTS, WRIST_BODY, Side

RAD_WEIGHT = 0.1  # one radian of axis error counts like 10 cm of position error


@dataclass(frozen=True)
class AxisGoal:
    """Turn `local` (a wrist-yaw-frame direction) to within `cone_deg` of the world direction `target`."""

    local: np.ndarray
    target: np.ndarray
    cone_deg: float = 0.0


@dataclass(frozen=True)
class IKResult:
    qpos: np.ndarray  # the 7 arm joint angles
    position_error: float  # metres
    axis_error_deg: float  # the largest angle outside its cone
    converged: bool


def solve_arm_ik(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    side: Side,
    point_local: np.ndarray,
    target_pos: np.ndarray,
    axes: tuple[AxisGoal, ...] = (),
    q0: np.ndarray | None = None,
    iters: int = 300,
    damping: float = 1e-3,
    pos_tol: float = 1e-3,
    axis_tol_deg: float = 1.0,
) -> IKResult:
    """Move `point_local` (wrist-yaw frame) to `target_pos` and each axis goal onto its target.

    Works on a scratch copy of `data`; joint limits are enforced by clipping after every step.
    """
    d = mujoco.MjData(model)
    d.qpos[:] = data.qpos
    body = model.body(WRIST_BODY[side]).id
    jids = [model.joint(n).id for n in ARM_JOINTS[side]]
    qadr = np.array([model.jnt_qposadr[j] for j in jids])
    dadr = np.array([model.jnt_dofadr[j] for j in jids])
    lo, hi = model.jnt_range[jids, 0], model.jnt_range[jids, 1]
    if q0 is not None:
        d.qpos[qadr] = q0
    goals = [(np.asarray(g.local, float), np.asarray(g.target, float) / np.linalg.norm(g.target), g.cone_deg)
             for g in axes]
    jacp, jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))
    pos_err, worst = np.inf, 0.0
    for _ in range(iters):
        mujoco.mj_kinematics(model, d)
        mujoco.mj_comPos(model, d)
        R = d.xmat[body].reshape(3, 3)
        p = d.xpos[body] + R @ point_local
        e_pos = np.asarray(target_pos, float) - p
        mujoco.mj_jac(model, d, jacp, jacr, p, body)
        errs, jacs = [e_pos], [jacp[:, dadr]]
        worst = 0.0
        for local, target, cone in goals:
            a = R @ local
            cross = np.cross(a, target)
            ang = np.degrees(np.arctan2(np.linalg.norm(cross), np.dot(a, target)))
            excess = max(ang - cone, 0.0)
            worst = max(worst, excess)
            # Rotating about a x t turns the axis toward its target; spin about the axis itself stays free.
            scale = RAD_WEIGHT * excess / max(ang, 1e-9)
            errs.append(scale * cross)
            jacs.append(RAD_WEIGHT * (np.eye(3) - np.outer(a, a)) @ jacr[:, dadr])
        pos_err = float(np.linalg.norm(e_pos))
        if pos_err < pos_tol and worst < axis_tol_deg:
            break
        J, e = np.vstack(jacs), np.concatenate(errs)
        dq = J.T @ np.linalg.solve(J @ J.T + damping * np.eye(J.shape[0]), e)
        d.qpos[qadr] = np.clip(d.qpos[qadr] + np.clip(dq, -0.2, 0.2), lo, hi)
    return IKResult(qpos=d.qpos[qadr].copy(), position_error=pos_err, axis_error_deg=float(worst),
                    converged=pos_err < pos_tol and worst < axis_tol_deg)


def solve_arm_ik_restarts(
    model: mujoco.MjModel, data: mujoco.MjData, side: Side, point_local: np.ndarray, target_pos: np.ndarray,
    axes: tuple[AxisGoal, ...] = (), seeds: list[np.ndarray] | None = None, n_random: int = 8, seed: int = 0,
    **kw: float,
) -> IKResult:
    """`solve_arm_ik` from the given seeds, then random ones, until one converges; else the best attempt."""
    jids = [model.joint(n).id for n in ARM_JOINTS[side]]
    lo, hi = model.jnt_range[jids, 0], model.jnt_range[jids, 1]
    rng = np.random.default_rng(seed)
    starts = list(seeds or []) + [rng.uniform(lo, hi) for _ in range(n_random)]
    best: IKResult | None = None
    for q0 in starts:
        r = solve_arm_ik(model, data, side, point_local, target_pos, axes, q0=q0, **kw)
        if r.converged:
            return r
        if best is None or r.position_error + 0.01 * r.axis_error_deg < best.position_error + 0.01 * best.axis_error_deg:
            best = r
    assert best is not None
    return best
