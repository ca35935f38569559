"""Arm kinematics on a scratch copy of the MuJoCo model: set arm joints, read end-effector poses and
Jacobians. The planner never touches the simulation's own MjData."""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from humanoidgen.sim.layout import ARM_JOINTS, HAND_BASE_FRAME, HAND_JOINTS, SIDES, WRIST_BODY, Side

EE_FRAME_SIDE: dict[str, Side] = {HAND_BASE_FRAME[s]: s for s in SIDES}


def side_of_frame(end_effector_frame: str) -> Side:
    try:
        return EE_FRAME_SIDE[end_effector_frame]
    except KeyError:
        raise ValueError(
            f"unknown end_effector_frame {end_effector_frame!r}; use {' or '.join(map(repr, EE_FRAME_SIDE))}"
        ) from None


@dataclass
class ArmIndex:
    """Where one arm's joints live in qpos / qvel, and their limits."""

    qadr: np.ndarray
    dadr: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    wrist: int
    site: int


@dataclass
class Kinematics:
    model: mujoco.MjModel
    data: mujoco.MjData = field(init=False)
    arms: dict[Side, ArmIndex] = field(init=False)
    # side -> (object body id, free-joint qpos address, object position and rotation in the wrist frame)
    attached: dict[Side, tuple[int, int, np.ndarray, np.ndarray]] = field(default_factory=dict, init=False)

    def __post_init__(self) -> None:
        m = self.model
        self.data = mujoco.MjData(m)
        self.arms = {}
        for side in SIDES:
            jids = [m.joint(n).id for n in ARM_JOINTS[side]]
            self.arms[side] = ArmIndex(
                qadr=np.array([m.jnt_qposadr[j] for j in jids]),
                dadr=np.array([m.jnt_dofadr[j] for j in jids]),
                lo=m.jnt_range[jids, 0].copy(),
                hi=m.jnt_range[jids, 1].copy(),
                wrist=m.body(WRIST_BODY[side]).id,
                site=m.site(HAND_BASE_FRAME[side]).id,
            )
        # The six driven finger joints of each hand, and the mimic followers tied to them (equality constraints:
        # follower = c0 + c1 * driver), so that a posture can be set on the scratch model without simulating.
        self._hand_adr = {s: np.array([m.jnt_qposadr[m.joint(n).id] for n in HAND_JOINTS[s]]) for s in SIDES}
        self._followers: list[tuple[int, int, float, float]] = []
        for eq in range(m.neq):
            if m.eq_type[eq] == mujoco.mjtEq.mjEQ_JOINT:
                c = m.eq_data[eq]
                self._followers.append((int(m.jnt_qposadr[m.eq_obj1id[eq]]), int(m.jnt_qposadr[m.eq_obj2id[eq]]),
                                        float(c[0]), float(c[1])))
        self._jacp = np.zeros((3, m.nv))
        self._jacr = np.zeros((3, m.nv))

    def sync(self, qpos: np.ndarray) -> None:
        """Take the whole configuration (arms, hands, objects) from the simulation."""
        self.data.qpos[:] = qpos
        self.forward()

    def set_arm(self, side: Side, q: np.ndarray) -> None:
        self.data.qpos[self.arms[side].qadr] = q

    def set_hand(self, side: Side, posture: np.ndarray) -> None:
        """Put `side`'s fingers at a 6-D posture (driven joints, action order) and their followers with them
        (call `forward` after). Used to check a motion with the fingers the way they will be then."""
        adr = self._hand_adr[side]
        self.data.qpos[adr] = posture
        driven = set(adr.tolist())
        for follower, driver, c0, c1 in self._followers:
            if driver in driven:
                self.data.qpos[follower] = c0 + c1 * self.data.qpos[driver]

    def hand_q(self, side: Side) -> np.ndarray:
        return self.data.qpos[self._hand_adr[side]].copy()

    def arm_q(self, side: Side) -> np.ndarray:
        return self.data.qpos[self.arms[side].qadr].copy()

    def forward(self) -> None:
        mujoco.mj_kinematics(self.model, self.data)
        if self.attached:  # held objects ride on the wrist: place them, then recompute their geoms
            for side, (_, adr, rel_p, rel_R) in self.attached.items():
                wp, wR = self.data.xpos[self.arms[side].wrist], self.data.xmat[self.arms[side].wrist].reshape(3, 3)
                self.data.qpos[adr:adr + 3] = wp + wR @ rel_p
                quat = np.empty(4)
                mujoco.mju_mat2Quat(quat, (wR @ rel_R).ravel())
                self.data.qpos[adr + 3:adr + 7] = quat
            mujoco.mj_kinematics(self.model, self.data)
        mujoco.mj_comPos(self.model, self.data)

    def attach(self, side: Side, body_name: str) -> None:
        """Treat `body_name` (a free object) as part of `side`'s hand from its current relative pose on."""
        m = self.model
        bid = m.body(body_name).id
        jnt = m.body_jntadr[bid]
        if jnt < 0 or m.jnt_type[jnt] != mujoco.mjtJoint.mjJNT_FREE:
            raise ValueError(f"{body_name} is not a free object; it cannot be carried")
        wrist = self.arms[side].wrist
        wp, wR = self.data.xpos[wrist], self.data.xmat[wrist].reshape(3, 3)
        rel_p = wR.T @ (self.data.xpos[bid] - wp)
        rel_R = wR.T @ self.data.xmat[bid].reshape(3, 3)
        self.attached[side] = (bid, int(m.jnt_qposadr[jnt]), rel_p, rel_R)

    def detach(self, side: Side) -> None:
        self.attached.pop(side, None)

    def ee_pose(self, side: Side) -> tuple[np.ndarray, np.ndarray]:
        sid = self.arms[side].site
        return self.data.site_xpos[sid].copy(), self.data.site_xmat[sid].reshape(3, 3).copy()

    def point_jacobian(self, side: Side, world_point: np.ndarray, body: int | None = None) -> np.ndarray:
        """d(world point fixed to the wrist, or to `body`)/d(arm joints), 3x7."""
        mujoco.mj_jac(self.model, self.data, self._jacp, self._jacr, world_point,
                      self.arms[side].wrist if body is None else body)
        return self._jacp[:, self.arms[side].dadr].copy()

    def rotation_jacobian(self, side: Side) -> np.ndarray:
        """Angular velocity of the wrist per arm joint velocity, 3x7."""
        mujoco.mj_jacBody(self.model, self.data, None, self._jacr, self.arms[side].wrist)
        return self._jacr[:, self.arms[side].dadr].copy()
