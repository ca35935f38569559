"""A grasp-to-grasp hand-over of a round body: the hand that takes a bottle the other hand wraps takes it from
above by its shoulder (the bottle family's `shoulder` grasp), thumb and fingers pressing from different sides, and
holds it alone once the giver lets go; a bottle no hand holds is still wrapped round its body first.

The contract corpus's own task (bench/contract_plans/tasks/bottle_handover.yaml), seed 0: the right hand wraps
the 0.33 l bottle's body and presents it in mid-air, as every plan of that task does. Before the shoulder grasp,
the left hand's wraps of the body met the right hand and the fallback pinch of the neck closed with the index
only (or let the bottle fall the moment the right hand opened)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from humanoidgen.planning import constraint_gen
from humanoidgen.planning.recoveries import hand_over
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402

TASK = Path(__file__).resolve().parents[1] / "bench/contract_plans/tasks/bottle_handover.yaml"


def _first_grasp(planner, side: str) -> str:
    c = planner.generate_constraints("bottle", 0, "grasp", side)
    return c[0].name


def _presented():
    _, env = build_scene(load_task(TASK), 0)
    planner = task_planner(env, seed=0)
    planner.hand_pre_grasp("right")
    c = planner.generate_constraints("bottle", 0, "grasp", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right")
    planner.hand_grasp("right", "bottle", 0)
    c = planner.generate_constraints("bottle", 0, "target", "right")
    _, pose = planner.generate_end_effector_pose(c, "right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="bottle", object_id=0)
    return env, planner


def _contact_bearings(env, side: str, body: str) -> dict[str, list[float]]:
    """Where the hand's links touch the bottle: bearing about its axis (degrees) per finger."""
    m, d = env.model, env.data
    bid = m.body(body).id
    p, R = d.xpos[bid], d.xmat[bid].reshape(3, 3)
    prefix = "L_" if side == "left" else "R_"
    out: dict[str, list[float]] = {}
    for i in range(d.ncon):
        b1, b2 = m.geom_bodyid[d.contact[i].geom1], m.geom_bodyid[d.contact[i].geom2]
        if bid not in (b1, b2):
            continue
        name = m.body(b2 if b1 == bid else b1).name
        if name.startswith(prefix):
            loc = R.T @ (d.contact[i].pos - p)
            out.setdefault(name[2:].split("_")[0], []).append(float(np.degrees(np.arctan2(loc[1], loc[0]))))
    return out


def test_a_free_bottle_is_wrapped_round_its_body_first():
    _, env = build_scene(load_task(TASK), 0)
    planner = task_planner(env, seed=0)
    assert "shoulder" not in _first_grasp(planner, "right")
    ops = constraint_gen._rank_operations(env, "right", "bottle", 0, "grasp", None)
    assert ops[-1].point == "shoulder" and all(o.width is not None for o in ops[:-1])


@pytest.mark.slow
def test_the_taking_hand_holds_a_held_bottle_by_its_shoulder_thumb_opposed():
    env, planner = _presented()
    bottle = env.scene.object("bottle", 0)
    assert "shoulder" in _first_grasp(planner, "left")  # the free part: the right hand wraps the body
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints("bottle", 0, "grasp", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left")
    planner.hand_grasp("left", "bottle", 0)
    bearings = _contact_bearings(env, "left", bottle.body)
    assert "thumb" in bearings, bearings
    fingers = [b for f, bs in bearings.items() if f != "thumb" for b in bs]
    assert fingers, bearings
    # Thumb and fingers press from different sides of the shoulder: their mean bearings more than 100 deg apart
    # round it (measured 110: the thumb beside the curled fingers, not straight across; the shoulder's ledge
    # rests on them).
    mean = lambda bs: np.degrees(np.arctan2(np.mean(np.sin(np.radians(bs))), np.mean(np.cos(np.radians(bs)))))  # noqa: E731
    apart = abs((mean(bearings["thumb"]) - mean(fingers) + 180.0) % 360.0 - 180.0)
    assert apart > 100.0, bearings
    moved, held = hand_over.release_trial(planner.ctx, "right", "left", bottle)
    assert held and moved <= hand_over.DROP_M
    planner.open_hand("right")  # the left hand alone carries it on, as the task's plans do
    planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
    c = planner.generate_constraints("bottle", 0, "target", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left", attach_obj=True, object_name="bottle", object_id=0)
    assert planner.holding["left"] is bottle


@pytest.mark.slow
def test_both_arms_move_apart_from_a_hand_over_that_leaves_them_touching():
    """The giver's thumb stays on the bottle when it lets go (it wraps three quarters round): a move of both arms
    (the taker to the table, the giver home) starts with the arms in contact and may only take them apart; it
    used to be refused in either order ("the two arms' motions would collide")."""
    env, planner = _presented()
    planner.hand_pre_grasp("left")
    c = planner.generate_constraints("bottle", 0, "grasp", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw(pose, "left")
    planner.hand_grasp("left", "bottle", 0)
    planner.open_hand("right")
    ctx = planner.ctx
    ctx.kin.sync(env.data.qpos)
    for side in ("left", "right"):
        ctx.attach_held(side)
    assert ctx.collisions.arm_arm_distance() < 0.003  # the case: they start (nearly) touching
    ctx.kin.sync(env.data.qpos)
    c = planner.generate_constraints("bottle", 0, "target", "left")
    _, pose = planner.generate_end_effector_pose(c, "left")
    planner.move_to_pose_with_screw([pose, planner.right_hand_init_pose], "all", attach_obj=[True, False],
                                    object_name=["bottle", None], object_id=[0, 0])
    p = env.data.xpos[env.model.body(env.scene.object("bottle", 0).body).id]
    assert planner.holding["left"] is env.scene.object("bottle", 0)
    assert np.linalg.norm(p[:2] - np.array([-0.33, 0.20])) < 0.05
