"""Hand targets (policies/hand_targets.py): the arm targets' forward kinematics are the hands' frames a simulation
reaches at those joints, and following a predicted hand target brings a hand a few centimetres off back onto it
while the joints stay near their predicted values and within their ranges."""

import numpy as np
import pytest

from humanoidgen.policies.hand_targets import HandFollower, follower_for_task
from humanoidgen.policies.hands import hand_features
from humanoidgen.sim.action import ARM_SLICE

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def scene():
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    _, sim = build_scene(load_task("close_drawer"), 0, settle_s=0.0)
    return sim


def _reachable_targets(sim, n=6, seed=0):
    """Joint targets around the start posture, within the arms' ranges."""
    rng = np.random.default_rng(seed)
    start = sim.joint_positions()
    out = np.repeat(start[None], n, axis=0)
    f = HandFollower(sim.model)
    for side in ("left", "right"):
        _, _, lo, hi, _ = f.arms[side]
        out[:, ARM_SLICE[side]] = np.clip(start[ARM_SLICE[side]] + rng.uniform(-0.4, 0.4, (n, 7)), lo, hi)
    return out


def test_targets_are_the_hands_frames_at_the_arm_joints(scene):
    import mujoco

    actions = _reachable_targets(scene)
    got = HandFollower(scene.model).targets(actions)
    assert got.shape == (len(actions), 18) and got.dtype == np.float32
    for a, t in zip(actions, got):  # the simulation's own hand frames at those joints
        scene.set_joint_positions(a)
        mujoco.mj_kinematics(scene.model, scene.data)
        np.testing.assert_allclose(t, hand_features(scene.ee_poses()), atol=1e-5)
    with pytest.raises(ValueError, match="not \\(T, 26\\)"):
        HandFollower(scene.model).targets(actions[:, :14])


def test_following_a_hand_target_brings_a_hand_centimetres_off_back_onto_it(scene):
    f = HandFollower(scene.model)
    truth = _reachable_targets(scene, n=8, seed=1)
    targets = f.targets(truth)
    rng = np.random.default_rng(2)
    missed, left = [], []
    for a, t in zip(truth, targets):
        off = a.copy()
        off[:14] += rng.normal(0.0, 0.04, 14)  # 0.04 rad a joint: the size of a CPU-trained policy's miss
        before = f.targets(off[None])[0]
        fixed = f.follow(off, t)
        after = f.targets(fixed[None])[0]
        for k in (0, 9):  # each hand's position
            missed.append(np.linalg.norm(before[k:k + 3] - t[k:k + 3]))
            left.append(np.linalg.norm(after[k:k + 3] - t[k:k + 3]))
        np.testing.assert_array_equal(fixed[14:], off[14:])  # the fingers as predicted
        for side in ("left", "right"):
            _, _, lo, hi, _ = f.arms[side]
            q = fixed[ARM_SLICE[side]]
            assert np.all(q >= lo - 1e-9) and np.all(q <= hi + 1e-9)
            # Near the seed: the correction is of the size of the error, not another posture.
            assert np.abs(q - off[ARM_SLICE[side]]).max() < 0.5
    # Centimetres off before, about a millimetre after (a joint at its stop may leave a few).
    assert np.median(missed) > 0.015 and np.median(left) < 0.001 and max(left) < 0.005, (missed, left)
    # A target the joints already reach leaves them where they are.
    np.testing.assert_allclose(f.follow(truth[0], targets[0]), truth[0], atol=1e-6)
    with pytest.raises(ValueError, match="18 finite numbers"):
        f.follow(truth[0], np.full(18, np.nan))


def test_a_follower_for_a_task_is_on_its_robot():
    f = follower_for_task("close_drawer")
    assert set(f.arms) == {"left", "right"} and all(len(v[0]) == 7 for v in f.arms.values())
