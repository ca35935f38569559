"""Hand targets (`PolicyConfig.hand_targets`): where each hand would be at the arm joint targets a policy
predicts, predicted beside those joint targets, and the executed arm targets pulled toward them.

Training: the recorded arm targets' forward kinematics on the task's model give each frame's hand target, 18
numbers in `policies.hands`' layout (per hand, left then right: position and the first two columns of the
rotation, in the world frame the point cloud is in). Execution (`HandFollower.follow`): each arm's predicted joint
targets are the seed and the anchor of a few damped least-squares steps that bring the hand's frame onto the
predicted hand target; the fingers' targets are executed as predicted.

Why: a policy's joint targets place the hand through seven joints' errors added along the arm, and close_drawer's
grips, made in postures up to 5.6 rad apart on a joint, missed the recorded targets by 0.02-0.04 rad a joint
(docs/results/policies.md), a few centimetres at the hand where its grip tolerates about one. The hand's own
target is a point in the cloud's frame, next to the handle the cloud shows; predicted directly, its error is not
multiplied along the arm. The joint targets keep choosing the posture (the arm's seventh joint and which of its
postures reaches the pose), which the hand's pose alone leaves open."""

from __future__ import annotations

import mujoco
import numpy as np

from humanoidgen.policies.hands import HAND_FEATURES
from humanoidgen.sim.action import ACTION_DIM, ARM_SLICE
from humanoidgen.sim.layout import ARM_JOINTS, HAND_BASE_FRAME, SIDES

PER_HAND = HAND_FEATURES // len(SIDES)
ROT_WEIGHT = 0.1  # metres per radian: one radian of the hand's turn weighs like 10 cm of its place
ANCHOR = 1e-3  # m^2 per rad^2: how strongly a joint stays at its predicted target (0.03 rad ~ 1 mm of the hand)
STEPS = 8  # Gauss-Newton steps: from a seed a few centimetres off, the hand lands within a millimetre in 3-5


def _unit_columns(t: np.ndarray) -> np.ndarray:
    """(9,) position + two predicted rotation columns -> the rotation matrix they stand for (Gram-Schmidt: a
    network's two columns are neither unit nor at right angles)."""
    a, b = t[3:6], t[6:9]
    x = a / max(np.linalg.norm(a), 1e-9)
    b = b - x * (x @ b)
    y = b / max(np.linalg.norm(b), 1e-9)
    return np.stack([x, y, np.cross(x, y)], axis=1)


class HandFollower:
    """Forward kinematics of the arm targets and the pull toward hand targets, on a scratch copy of `model` (any
    of the task's scenes: the arms and their base are the same in every one)."""

    def __init__(self, model: mujoco.MjModel) -> None:
        self.model = model
        self.data = mujoco.MjData(model)
        mujoco.mj_forward(model, self.data)
        self.arms = {}
        for side in SIDES:
            jids = [model.joint(n).id for n in ARM_JOINTS[side]]
            self.arms[side] = (np.array([model.jnt_qposadr[j] for j in jids]),
                               np.array([model.jnt_dofadr[j] for j in jids]),
                               model.jnt_range[jids, 0].copy(), model.jnt_range[jids, 1].copy(),
                               model.site(HAND_BASE_FRAME[side]).id)
        self._jacp, self._jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))

    def _place(self, side: str, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        qadr, _, _, _, site = self.arms[side]
        self.data.qpos[qadr] = q
        mujoco.mj_kinematics(self.model, self.data)
        return self.data.site_xpos[site].copy(), self.data.site_xmat[site].reshape(3, 3).copy()

    def targets(self, actions: np.ndarray) -> np.ndarray:
        """(T, 26) joint targets -> (T, 18) float32 hand targets (the hands' frames at those arm targets)."""
        a = np.asarray(actions, np.float64)
        if a.ndim != 2 or a.shape[1] != ACTION_DIM:
            raise ValueError(f"actions have shape {a.shape}, not (T, {ACTION_DIM})")
        out = np.empty((len(a), HAND_FEATURES), np.float32)
        for t, row in enumerate(a):
            for k, side in enumerate(SIDES):
                p, R = self._place(side, row[ARM_SLICE[side]])
                out[t, k * PER_HAND: (k + 1) * PER_HAND] = np.concatenate([p, R[:, 0], R[:, 1]])
        return out

    def follow(self, action: np.ndarray, target: np.ndarray) -> np.ndarray:
        """The 26 joint targets with each arm's moved so that its hand lands on `target` (18), each joint kept
        near its predicted value (`ANCHOR`) and within its range; a target that is not finite is refused."""
        a = np.array(action, np.float64)
        target = np.asarray(target, np.float64)
        if target.shape != (HAND_FEATURES,) or not np.all(np.isfinite(target)):
            raise ValueError(f"hand target must be {HAND_FEATURES} finite numbers, got shape {target.shape}")
        for k, side in enumerate(SIDES):
            qadr, dadr, lo, hi, site = self.arms[side]
            t = target[k * PER_HAND: (k + 1) * PER_HAND]
            p_goal, R_goal = t[:3], _unit_columns(t)
            seed = np.clip(a[ARM_SLICE[side]], lo, hi)
            q = seed.copy()
            for _ in range(STEPS):
                p, R = self._place(side, q)
                mujoco.mj_comPos(self.model, self.data)
                mujoco.mj_jacSite(self.model, self.data, self._jacp, self._jacr, site)
                # The small turn taking R onto R_goal, in the world frame (each column's cross product).
                turn = 0.5 * sum(np.cross(R[:, i], R_goal[:, i]) for i in range(3))
                e = np.concatenate([p_goal - p, ROT_WEIGHT * turn])
                J = np.vstack([self._jacp[:, dadr], ROT_WEIGHT * self._jacr[:, dadr]])
                H = J.T @ J + ANCHOR * np.eye(len(q))
                q = np.clip(q + np.linalg.solve(H, J.T @ e + ANCHOR * (seed - q)), lo, hi)
            a[ARM_SLICE[side]] = q
        return a


def follower_for_task(task: str) -> HandFollower:
    """A follower on `task`'s model (its scene for no seed: the robot is the same in all of them)."""
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    _, sim = build_scene(load_task(task), None, settle_s=0.0)
    return HandFollower(sim.model)
