"""The hands' poses as a policy reads them (`PolicyConfig.observe_hands`): per hand, left then right, its
position and the first two columns of its rotation matrix (the continuous 6D rotation of Zhou et al., CVPR 2019),
18 numbers from the 14 of `ee_pose` (position and quaternion w, x, y, z per hand) that the recorder and the env give.

The quaternion is not fed as it is: q and -q are one orientation, so a sign the recording happens to flip would be
a jump across the whole input range for no motion at all; two columns of the matrix change as smoothly as the hand."""

from __future__ import annotations

import numpy as np

from humanoidgen.sim.geometry import quat_to_mat

EE_POSE_DIM = 14  # per hand: x, y, z, qw, qx, qy, qz
HAND_FEATURES = 18  # per hand: x, y, z and two rotation columns


def hand_features(ee_pose: np.ndarray) -> np.ndarray:
    """(..., 14) `ee_pose` -> (..., 18) float32: per hand, position then the rotation's first two columns."""
    x = np.asarray(ee_pose, np.float64)
    if x.shape[-1] != EE_POSE_DIM:
        raise ValueError(f"ee_pose has {x.shape[-1]} numbers per frame, not {EE_POSE_DIM} (two hands' position "
                         "and quaternion)")
    if not np.all(np.isfinite(x)):
        raise ValueError("ee_pose holds numbers that are not finite")
    frames = x.reshape(-1, EE_POSE_DIM)
    parts = []
    for first in (0, 7):
        quats = frames[:, first + 3: first + 7]
        if np.any(np.linalg.norm(quats, axis=-1) < 1e-9):
            raise ValueError("ee_pose holds a quaternion that is zero")
        R = np.stack([quat_to_mat(q) for q in quats]).reshape(-1, 3, 3)
        parts += [frames[:, first: first + 3], R[:, :, 0], R[:, :, 1]]
    return np.concatenate(parts, axis=-1).reshape(*x.shape[:-1], HAND_FEATURES).astype(np.float32)
