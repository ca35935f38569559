"""A carried object's goal near the arm's posture (planning/near_goal.py): a goal on another branch of the arm,
turning a joint past FAR_JOINT_DEG, is solved again from about the arm's posture; and the corpus plan that tipped
a cup over a bowl in stages, whose second stage swung the arm through 157-179 deg and threw the cubes, pours."""

from pathlib import Path

import numpy as np

from humanoidgen.objects.queries import get_point_in_env
from humanoidgen.planning.constraints import Constraint
from humanoidgen.planning.near_goal import FAR_JOINT_DEG, joint_turn, nearer_goal
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.scene import SceneBuilder

from plan_runs import task_planner  # noqa: E402


def _reach_above(env) -> list[Constraint]:
    """The right palm 8 cm up and 5 cm out: position only, so the arm has many postures for it."""
    key = get_point_in_env(env, "palm_center_right_hand")
    return [Constraint(env, "point2point", "r_hand_base_link", hand_key_point=key,
                       object_key_point=key + np.array([0.05, 0.0, 0.08]))]


def test_a_goal_on_a_far_branch_is_solved_again_near_the_arms_posture():
    env = HumanoidEnv(SceneBuilder().build())
    planner = task_planner(env)
    q_now = planner.ctx.kin.arm_q("right")
    cons = _reach_above(env)
    arm = planner.ctx.kin.arms["right"]
    far_seed = np.clip(q_now + np.array([0.0, 0.0, 2.2, 0.0, 2.2, 0.0, 0.0]), arm.lo, arm.hi)
    far = planner.ctx.solver.solve("right", cons, far_seed, far_seed, max_seeds=1)
    assert far.success and np.degrees(joint_turn(q_now, far.q)) > FAR_JOINT_DEG  # shoulder yaw and elbow roll
    near = nearer_goal(planner.ctx.solver, "right", cons, q_now, far)
    assert near is not None and near.success
    assert np.degrees(joint_turn(q_now, near.q)) < FAR_JOINT_DEG
    planner.ctx.kin.set_arm("right", near.q)
    planner.ctx.kin.forward()
    assert all(c.violation(planner.ctx.kin) < 1e-3 for c in cons)
    # A goal near already is left as found.
    assert nearer_goal(planner.ctx.solver, "right", cons, q_now, near) is None


def test_the_staged_cup_tip_keeps_the_arm_near_and_pours():
    """cup_pour_easy seed 3, a corpus plan (written apart from the planner): its 40 -> 80 deg stage was solved on
    the arm's other branch, and the cubes were thrown 52 cm."""
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    plan = Path(__file__).resolve().parents[1] / "bench" / "foreign_plans" / "cup_pour_easy" / "alt_lip_tilt.py"
    result, _ = run_task_episode(EpisodeRequest("cup_pour_easy", 3, plan_path=str(plan)))
    assert any("near its posture" in e for e in result.events), result.events
    assert result.success, [c["detail"] for c in result.checks]
