"""The hands' poses as a policy reads them (`PolicyConfig.observe_hands`): per hand, left then right, its
position and the first two columns of its rotation matrix (the continuous 6D rotation of Zhou et al., CVPR 2019),
18 numbers from the 14 of `ee_pose` (position and quaternion w, x, y, z per hand) that the recorder and the env give.

The quaternion is not fed as it is: q and -q are one orientation, so a sign the recording happens to flip would be
a jump across the whole input range for no motion at all; two columns of the matrix change as smoothly as the hand."""

from __future__ import annotations

import numpy as np

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
    parts = []
    for first in (0, 7):
        q = x[..., first + 3: first + 7]
        norm = np.linalg.norm(q, axis=-1, keepdims=True)
        if np.any(norm < 1e-9):
            raise ValueError("ee_pose holds a quaternion that is zero")
        w, qx, qy, qz = np.moveaxis(q / norm, -1, 0)
        parts += [x[..., first: first + 3],
                  np.stack([1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy + w * qz), 2 * (qx * qz - w * qy),
                            2 * (qx * qy - w * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz + w * qx)], axis=-1)]
    return np.concatenate(parts, axis=-1).astype(np.float32)
