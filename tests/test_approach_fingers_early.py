"""A hand that comes in to a part with its fingers open (approach.check_way_in: the pre-grasp thumb would push the
drawer's handle) opens them before the transit, where the hand starts, and carries them open all the way
(approach.change_early); where they cannot change there, it opens them at the pre-pose as before. A policy
learning from the demonstrations then sees one stop near the handle, the grip, instead of two."""

from __future__ import annotations

import numpy as np
from humanoidgen.objects.hands import HAND_POSTURES
from humanoidgen.planning import approach
from humanoidgen.sim.action import ARM_SLICE, HAND_SLICE
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene
from plan_runs import task_planner

OPEN = np.array(HAND_POSTURES["open"])


def _move_to_handle(monkeypatch=None, room_at_start=True):
    _, env = build_scene(load_task("close_drawer"), 0)
    planner = task_planner(env, seed=0)
    planner.hand_pre_grasp("left")
    pose = planner.generate_end_effector_pose(planner.generate_constraints("drawer", 0, "grasp", "left"), "left")[1]
    if not room_at_start:  # as if something beside the hand were in the fingers' way where it starts
        real = approach.finger_sweep_clearance
        start = planner.ctx.kin.arm_q("left").copy()

        def sweep(kin, *args):
            return (-0.01, None) if np.allclose(kin.arm_q("left"), start) else real(kin, *args)

        monkeypatch.setattr(approach, "finger_sweep_clearance", sweep)
    actions: list[np.ndarray] = []
    planner.on_step = actions.append
    home = planner.ctx.kin.arm_q("left").copy()
    planner.move_to_pose_with_screw(pose, "left")
    return np.array(actions), home, planner


def _first_open(a: np.ndarray) -> int:
    return int(np.argmax(np.all(np.abs(a[:, HAND_SLICE["left"]] - OPEN) < 1e-9, axis=1)))


def test_fingers_open_where_the_hand_starts_and_stay_open_on_the_way_in():
    a, home, planner = _move_to_handle()
    assert any("came in" in e and "with the fingers open" in e for e in planner.events)
    k = _first_open(a)
    assert k > 0
    # the arm did not move while the fingers changed: they opened where the hand started
    assert np.abs(a[: k + 1, ARM_SLICE["left"]] - home).max() < 1e-9
    # ... and stayed open every step after, the arm's whole way to the handle
    assert np.all(np.abs(a[k:, HAND_SLICE["left"]] - OPEN) < 1e-9)
    assert np.abs(a[-1, ARM_SLICE["left"]] - home).max() > 0.5


def test_without_room_where_the_hand_starts_the_fingers_open_at_the_pre_pose(monkeypatch):
    a, home, planner = _move_to_handle(monkeypatch, room_at_start=False)
    k = _first_open(a)
    # the transit ran with the pre-grasp fingers; they opened with the arm still, far from where it started
    assert np.abs(a[k, ARM_SLICE["left"]] - home).max() > 0.5
    assert np.abs(a[k - 3: k + 1, ARM_SLICE["left"]] - a[k, ARM_SLICE["left"]]).max() < 1e-9
    assert np.abs(a[k // 2, HAND_SLICE["left"]] - np.array(HAND_POSTURES["pre_grasp"])).max() < 1e-9


def test_change_early_refuses_a_transit_the_new_fingers_would_strike():
    _, env = build_scene(load_task("close_drawer"), 0)
    planner = task_planner(env, seed=0)
    kin = planner.ctx.kin
    start = kin.arm_q("left").copy()
    # a "transit" straight through the drawer cabinet: the fingers, open or not, meet it on the way
    pose = planner.generate_end_effector_pose(planner.generate_constraints("drawer", 0, "grasp", "left"), "left")[1]
    through = np.vstack([start + (pose.joint_q - start) * t for t in np.linspace(0, 1, 20)])
    from humanoidgen.planning.motion import JointPath, first_collision

    assert first_collision(kin, planner.ctx.collisions, "left", through) is not None
    assert not approach.change_early(planner.ctx, "left", JointPath(through, "direct"), "open")
    assert approach.change_early(planner.ctx, "left", JointPath(through[:1].repeat(2, 0), "direct"), "open")
