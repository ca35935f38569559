"""The simulated H1-2: structure, actuation, hands, action validation."""

import mujoco
import numpy as np
import pytest

from humanoidgen.sim.action import ACTION_DIM, ACTION_JOINTS, HAND_SLICE, ActionError, validate_action
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.layout import ARM_JOINTS, HAND_JOINTS, HAND_PREFIX, SIDES
from humanoidgen.sim.robot import read_mimics


def test_model_structure(empty_scene):
    m = empty_scene.model
    assert m.nu == ACTION_DIM == 26
    hinge = [m.joint(j).name for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE]
    arm = [j for j in hinge if any(j in ARM_JOINTS[s] for s in SIDES)]
    hand = [j for j in hinge if j[:2] in ("L_", "R_")]
    assert len(arm) == 14
    assert len(hand) == 24  # 12 per hand: 6 actuated, 6 mimic followers
    actuated = {m.actuator(i).name for i in range(m.nu)}
    assert actuated == set(ACTION_JOINTS)
    assert sum(1 for j in hand if j in actuated) == 12
    assert m.neq == 12  # one mimic coupling per follower
    # No floating base, no legs or torso joints: only the arms and hands move.
    assert m.nq == m.nv == 14 + 24
    for name in ("l_hand_base_link", "r_hand_base_link"):
        assert m.site(name).id >= 0


def test_mimic_couplings_come_from_urdf(empty_scene):
    from humanoidgen.assets.robot_files import resolve_assets_root

    mimics = read_mimics(resolve_assets_root() / "h1_2" / "h1_2.urdf")
    assert len(mimics) == 12
    thumb = {m.follower: m.multiplier for m in mimics if m.driver == "L_thumb_proximal_pitch_joint"}
    assert thumb == {"L_thumb_intermediate_joint": 1.6, "L_thumb_distal_joint": 2.4}


@pytest.mark.parametrize("index", range(ACTION_DIM), ids=list(ACTION_JOINTS))
def test_each_action_entry_drives_its_joint(empty_scene, index):
    env = HumanoidEnv(empty_scene)
    start = env.joint_positions()
    lo, hi = env.model.actuator_ctrlrange[env._act_ids[index]]
    target_value = start[index] + (0.3 if start[index] + 0.3 <= hi else -0.3)
    action = env.init_action()
    action[index] = target_value
    for _ in range(50):  # one second at 50 Hz
        env.step(action)
    q = env.joint_positions()
    moved = abs(q[index] - start[index])
    assert moved > 0.8 * 0.3, f"{ACTION_JOINTS[index]} moved only {moved:.3f} rad of 0.3"
    assert abs(q[index] - target_value) < 0.06
    others = np.delete(np.abs(q - start), index)
    assert others.max() < 0.03, "other joints must hold their targets"


def _close(env, side, thumb_yaw, thumb_pitch, fingers):
    a = env.init_action()
    a[HAND_SLICE[side]] = [thumb_yaw, thumb_pitch, fingers, fingers, fingers, fingers]
    for _ in range(75):
        env.step(a)
    return a


def _hand_self_contacts(env, side):
    m, d = env.model, env.data
    prefix = HAND_PREFIX[side] + "_"
    out = []
    for c in d.contact[: d.ncon]:
        b1, b2 = m.body(m.geom_bodyid[c.geom1]).name, m.body(m.geom_bodyid[c.geom2]).name
        if b1.startswith(prefix) and b2.startswith(prefix):
            out.append((b1, b2, c.dist))
    return out


@pytest.mark.parametrize("side", SIDES)
def test_closed_fingers_and_thumb_reach_limits_without_self_collision(empty_scene, side):
    env = HumanoidEnv(empty_scene)
    hi = env.model.actuator_ctrlrange[env._act_ids, 1]
    sl = HAND_SLICE[side]
    # Four fingers fully closed, thumb open.
    a = _close(env, side, 0.0, 0.0, 1.7)
    assert np.allclose(env.hand_qpos(side)[2:], a[sl][2:], atol=0.03)
    assert _hand_self_contacts(env, side) == []
    # Thumb fully rotated and bent, fingers open.
    env.reset()
    a = _close(env, side, hi[sl][0], hi[sl][1], 0.0)
    assert np.allclose(env.hand_qpos(side)[:2], a[sl][:2], atol=0.03)
    assert _hand_self_contacts(env, side) == []
    # The follower joints obey the mimic couplings (thumb: 1.6x and 2.4x the pitch).
    qd = env.data.qpos
    pitch = qd[env.model.jnt_qposadr[env.model.joint(f"{HAND_PREFIX[side]}_thumb_proximal_pitch_joint").id]]
    inter = qd[env.model.jnt_qposadr[env.model.joint(f"{HAND_PREFIX[side]}_thumb_intermediate_joint").id]]
    assert inter == pytest.approx(1.6 * pitch, abs=0.02)


@pytest.mark.parametrize("side", SIDES)
def test_fist_stops_at_contact_without_interpenetration(empty_scene, side):
    env = HumanoidEnv(empty_scene)
    hi = env.model.actuator_ctrlrange[env._act_ids, 1]
    sl = HAND_SLICE[side]
    _close(env, side, hi[sl][0], hi[sl][1], 1.7)
    assert env.hand_qpos(side)[2:].min() > 1.3  # the fingers still close around the thumb
    for b1, b2, dist in _hand_self_contacts(env, side):
        assert dist > -0.002, f"{b1} and {b2} interpenetrate by {-dist * 1000:.1f} mm"


def test_bad_actions_are_rejected_with_clear_errors(empty_scene):
    env = HumanoidEnv(empty_scene)
    with pytest.raises(ActionError, match=r"shape \(26,\)"):
        env.step(np.zeros(25))
    bad = env.init_action()
    bad[16] = np.nan
    with pytest.raises(ActionError, match="non-finite.*16"):
        env.step(bad)
    with pytest.raises(ActionError, match="sequence"):
        validate_action("not an action")
    assert validate_action(list(range(26))).dtype == np.float64


def test_control_rate_is_configurable(empty_scene):
    assert HumanoidEnv(empty_scene).n_substeps == 10  # 50 Hz at a 2 ms physics step
    env = HumanoidEnv(empty_scene, control_hz=100)
    assert env.n_substeps == 5
    t0 = env.time
    env.step(env.init_action())
    assert env.time - t0 == pytest.approx(0.01)
    with pytest.raises(ValueError, match="whole number"):
        HumanoidEnv(empty_scene, control_hz=30)
    with pytest.raises(ValueError, match="control_hz"):
        HumanoidEnv(empty_scene, control_hz=0)


def test_hand_joint_names_cover_six_dof():
    for side in SIDES:
        assert len(HAND_JOINTS[side]) == 6
        assert len(ARM_JOINTS[side]) == 7
