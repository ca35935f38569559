"""The way in starts where the transit to the pre-approach pose ends (planning/approach.py `join`).

A 7-joint arm reaches a hand pose in many postures; a transit may end at the pre-pose in another posture than the
way in was tracked from (on the G1, near its shoulder's roll singularity, 1.0-1.4 rad apart). Played one after the
other, the arm's targets jumped there in one control step and the swing threw a pinched block out of the fingers.
"""

from __future__ import annotations

import numpy as np

from humanoidgen.planning import approach
from humanoidgen.planning.motion import JointPath

from plan_runs import cube_pinch_pose  # noqa: E402


def _pinch_way():
    planner, pose = cube_pinch_pose()
    reasons: list[str] = []
    way = next(approach.ways_in(planner.ctx, "right", pose, reasons))
    return planner, pose, way


def test_a_transit_ending_where_the_way_in_starts_keeps_the_way_in():
    planner, pose, way = _pinch_way()
    transit = JointPath(np.vstack([planner.ctx.kin.arm_q("right"), way.path[0]]), "screw")
    assert approach.join(planner.ctx, "right", transit, way, pose, []) is way


def test_a_transit_ending_in_another_posture_gets_the_way_in_tracked_from_there():
    planner, pose, way = _pinch_way()
    ctx = planner.ctx
    # Another posture at (nearly) the pre-pose: the elbow's roll turned, the wrist making up for most of it.
    other = way.path[0].copy()
    other[4] += 0.35
    other[6] -= 0.25
    transit = JointPath(np.vstack([ctx.kin.arm_q("right"), other]), "screw")
    assert np.max(np.abs(other - way.path[0])) > approach.JOIN_TOL
    reasons: list[str] = []
    joined = approach.join(ctx, "right", transit, way, pose, reasons)
    assert joined is not None, reasons
    assert np.array_equal(joined.path[0], other)  # no jump between the legs
    assert np.max(np.abs(np.diff(joined.path, axis=0))) < 0.3  # and none inside the way in
    ctx.kin.set_arm("right", joined.path[-1])
    ctx.kin.forward()
    p, _ = ctx.kin.ee_pose("right")
    assert np.linalg.norm(p - pose.p) < 0.005  # it still ends at the goal pose
    ctx.kin.sync(ctx.env.data.qpos)


def test_a_lift_before_a_turn_is_kept_before_the_approach_that_starts_where_it_ends(monkeypatch):
    """A carried object resting on something is lifted before the hand turns it (`arm_moves.turns_standing_object`).
    When the move then comes in along an approach axis, the approach is planned from the lift's end: the lift must
    stay the first leg, else the arm's targets jump from where the arm is to where the lift would have ended."""
    from humanoidgen.planning import arm_moves

    planner, pose, _ = _pinch_way()
    ctx = planner.ctx
    q_now = ctx.kin.arm_q("right").copy()
    starts: list[np.ndarray] = []

    def stub_approach(ctx_, side, q0, target):
        starts.append(np.array(q0))
        return approach.ApproachPlan(legs=[JointPath(np.vstack([q0, target.joint_q]), "screw")], posture=None,
                                     label="along its axis")

    monkeypatch.setattr(arm_moves, "turns_standing_object", lambda ctx_, side, target: True)
    monkeypatch.setattr(approach, "plan_approach", stub_approach)
    out = arm_moves.plan_side_timed(ctx, "right", pose, [])
    assert len(starts) == 1 and np.max(np.abs(starts[0] - q_now)) > 1e-4  # the approach starts after a lift
    assert np.max(np.abs(out[0, :7] - q_now)) < 0.05  # the targets start where the arm is
    assert np.max(np.abs(np.diff(out[:, :7], axis=0))) < 0.05  # and never jump on the way
