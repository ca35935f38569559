"""Stepping the scene with 26-D actions at a fixed control rate."""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from humanoidgen.sim.action import ACTION_DIM, ACTION_JOINTS, ARM_SLICE, HAND_SLICE, validate_action
from humanoidgen.sim.geometry import mat_to_quat
from humanoidgen.sim.layout import ARM_JOINTS, HAND_BASE_FRAME, HAND_JOINTS, ROBOT, SIDES, Side
from humanoidgen.sim.scene import Scene

# Initial posture (radians, action order): the robot file's `home` (each arm's joints; the hands' posture, open).
INIT_ARM_QPOS: dict[Side, tuple[float, ...]] = {side: tuple(getattr(ROBOT.data.home, side)) for side in SIDES}
OPEN_HAND = ROBOT.hand.postures[ROBOT.data.home.hands]
DEFAULT_CONTROL_HZ = 50.0
MAX_CONTROL_HZ = 500.0


@dataclass
class HumanoidEnv:
    """The simulated robot at its table. `step(action)` holds the targets for one control period."""

    scene: Scene
    control_hz: float = DEFAULT_CONTROL_HZ
    data: mujoco.MjData = field(init=False, repr=False)

    def __post_init__(self) -> None:
        model = self.model
        if not 0 < self.control_hz <= MAX_CONTROL_HZ:
            raise ValueError(f"control_hz must be in (0, {MAX_CONTROL_HZ}], got {self.control_hz}")
        substeps = 1.0 / (self.control_hz * model.opt.timestep)
        if abs(substeps - round(substeps)) > 1e-6:
            raise ValueError(
                f"control period 1/{self.control_hz} s is not a whole number of physics steps of {model.opt.timestep} s"
            )
        self.n_substeps = int(round(substeps))
        self.data = mujoco.MjData(model)
        self._kinematics_qpos = np.zeros(model.nq)
        self._act_ids = np.array([model.actuator(name).id for name in ACTION_JOINTS])
        self._qpos_adr = np.array([model.jnt_qposadr[model.joint(name).id] for name in ACTION_JOINTS])
        self._ctrl_lo = model.actuator_ctrlrange[self._act_ids, 0]
        self._ctrl_hi = model.actuator_ctrlrange[self._act_ids, 1]
        self._site = {side: model.site(name).id for side, name in HAND_BASE_FRAME.items()}
        self.reset()

    @property
    def model(self) -> mujoco.MjModel:
        return self.scene.model

    @property
    def time(self) -> float:
        return float(self.data.time)

    def init_action(self) -> np.ndarray:
        a = np.zeros(ACTION_DIM)
        for side in ("left", "right"):
            a[ARM_SLICE[side]] = INIT_ARM_QPOS[side]
            a[HAND_SLICE[side]] = OPEN_HAND
        return a

    def reset(self, action: np.ndarray | None = None) -> None:
        """Put the robot at the initial posture (or the joint targets `action`) with zero velocity."""
        mujoco.mj_resetData(self.model, self.data)
        a = self.init_action() if action is None else self.clip(validate_action(action))
        self.set_joint_positions(a)
        self.data.ctrl[self._act_ids] = a
        mujoco.mj_forward(self.model, self.data)

    def set_joint_positions(self, action: np.ndarray) -> None:
        """Teleport the 26 driven joints (and their mimic followers) to `action` without simulating."""
        self.data.qpos[self._qpos_adr] = action
        for eq in range(self.model.neq):
            if self.model.eq_type[eq] != mujoco.mjtEq.mjEQ_JOINT:
                continue
            follower, driver = self.model.eq_obj1id[eq], self.model.eq_obj2id[eq]
            c = self.model.eq_data[eq]
            x = self.data.qpos[self.model.jnt_qposadr[driver]]
            self.data.qpos[self.model.jnt_qposadr[follower]] = c[0] + c[1] * x
        mujoco.mj_forward(self.model, self.data)
        self._kinematics_qpos[:] = self.data.qpos

    def clip(self, action: np.ndarray) -> np.ndarray:
        return np.clip(action, self._ctrl_lo, self._ctrl_hi)

    def step(self, action: np.ndarray) -> None:
        """Apply the 26-D joint-position target (clipped to joint limits) for one control period."""
        a = self.clip(validate_action(action))
        self.data.ctrl[self._act_ids] = a
        # The last substep runs on its own so that the configuration it started from, the one today's
        # kinematics (body and camera poses, so any picture rendered now) were computed from, is known:
        # recordings are rendered afterwards from it. nstep=k is a loop of single steps: the same physics.
        if self.n_substeps > 1:
            mujoco.mj_step(self.model, self.data, nstep=self.n_substeps - 1)
        self._kinematics_qpos[:] = self.data.qpos
        mujoco.mj_step(self.model, self.data)

    def kinematics_qpos(self) -> np.ndarray:
        """The configuration the current kinematics (`data.xpos`, `cam_xpos`, ...) were computed from: after
        `step` that is the state before its last physics substep, not `data.qpos`."""
        return self._kinematics_qpos.copy()

    # -- state queries -----------------------------------------------------------------------------------
    def joint_positions(self) -> np.ndarray:
        """Positions of the 26 driven joints, in action order."""
        return self.data.qpos[self._qpos_adr].copy()

    def arm_qpos(self, side: Side) -> np.ndarray:
        return self.joint_positions()[ARM_SLICE[side]]

    def hand_qpos(self, side: Side) -> np.ndarray:
        return self.joint_positions()[HAND_SLICE[side]]

    def hand_pose(self, side: Side) -> tuple[np.ndarray, np.ndarray]:
        """World position and rotation matrix of the hand's end-effector frame."""
        sid = self._site[side]
        return self.data.site_xpos[sid].copy(), self.data.site_xmat[sid].reshape(3, 3).copy()

    def ee_poses(self) -> np.ndarray:
        """Both hands' end-effector poses, left then right: position and quaternion (w, x, y, z), (14,)."""
        return np.concatenate([np.concatenate([p, mat_to_quat(R)]) for p, R in map(self.hand_pose, ("left", "right"))])

    def object_pose(self, body: str) -> tuple[np.ndarray, np.ndarray]:
        """World position and quaternion (w, x, y, z) of an object's body."""
        bid = self.model.body(body).id
        return self.data.xpos[bid].copy(), self.data.xquat[bid].copy()


def joint_names(side: Side) -> tuple[str, ...]:
    return ARM_JOINTS[side] + HAND_JOINTS[side]
