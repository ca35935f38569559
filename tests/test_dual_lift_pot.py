"""dual_lift_pot, the paper's additional task: both hands grasp a pot's two handles at the same time and lift it.

The pot with upright grips (objects/families/pot/2_*.yaml, handle_style post), the task's spec and success
predicates, one object held by both hands in planning (planning/shared_hold.py), and the reference plan."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import math  # noqa: E402

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from humanoidgen.objects import library  # noqa: E402
from humanoidgen.objects.family_data import ENV_FAMILIES_PATH, FamilyDataError  # noqa: E402
from humanoidgen.planning import shared_hold  # noqa: E402
from humanoidgen.tasks.predicates import evaluate_all  # noqa: E402
from humanoidgen.tasks.registry import load_task, plan_path  # noqa: E402
from humanoidgen.tasks.scene import build_scene  # noqa: E402
from plan_runs import run_plan, task_planner  # noqa: E402

TASK = "dual_lift_pot"
POT = 2  # the stock pot with an upright grip on each side


# -- the pot ------------------------------------------------------------------------------------------------------
def test_the_pot_has_a_wrapped_upright_grip_on_each_side():
    ann = library.annotations("pot", POT)
    params = library.family("pot")._model(POT).params
    ops = {o.point: o for o in ann.operations_of("grasp")}
    assert set(ops) == {"grip_left", "grip_right"}
    for point, sign in (("grip_left", 1.0), ("grip_right", -1.0)):
        op, p = ops[point], np.array(ann.point(point).position)
        # Wrapped like a bottle, its width the grip's own (not the pot's), approached from its own side.
        assert op.width == pytest.approx(params["handle_thick"])
        assert ann.axis(op.approach_axis).direction == pytest.approx((0.0, -sign, 0.0))
        assert ann.axis(op.parallel_axis).direction == pytest.approx((0.0, 0.0, 1.0))
        # The point is the grip's outer surface, beyond the wall by the reach and the grip's radius.
        assert sign * p[1] == pytest.approx(params["radius"] + params["handle_reach"] + params["handle_thick"] / 2)
    # The tab-handled pots keep their own grasps.
    assert {o.point for o in library.annotations("pot", 0).operations_of("grasp")} == {"handle_left", "handle_right"}


def test_a_post_handled_pot_file_needs_the_grips_height(tmp_path, monkeypatch):
    (tmp_path / "pot").mkdir()
    path = tmp_path / "pot" / "bad.yaml"
    path.write_text("type_id: 9\ndescription: a pot without a grip height\nradius: 0.08\nheight: 0.12\nwall: 0.005\n"
                    "bottom: 0.008\nn_walls: 16\nhandle_reach: 0.07\nhandle_thick: 0.04\nhandle_style: post\n"
                    "rgba: [0.7, 0.7, 0.7, 1.0]\nhandle_rgba: [0.1, 0.1, 0.1, 1.0]\nmass: 0.6\n")
    monkeypatch.setenv(ENV_FAMILIES_PATH, str(tmp_path))
    with pytest.raises(FamilyDataError) as exc:
        library.family("pot").models()
    assert str(exc.value).startswith(f"{path}: ") and "handle_height" in str(exc.value), str(exc.value)


# -- the task -----------------------------------------------------------------------------------------------------
def test_spec_matches_the_paper():
    """12 x 6 cm (x, then y, as the other extra tasks read the paper's sizes) and +-15 deg; lifted, level, both
    hands on it."""
    spec = load_task(TASK)
    r = spec.randomization
    assert r.position == pytest.approx((-0.06, 0.06, -0.03, 0.03)) and r.yaw_deg == pytest.approx((-15, 15))
    assert spec.arms == "bimanual" and [(o.type, o.type_id) for o in spec.objects] == [("pot", POT)]
    kinds = sorted((p.type, getattr(p, "side", "")) for p in spec.success)
    assert kinds == [("held", "left"), ("held", "right"), ("lifted", ""), ("upright", "")]
    assert plan_path(spec).is_file()


def _pose_pot(env, dz: float = 0.0, tilt_deg: float = 0.0) -> None:
    """Put the pot `dz` higher and tilted about y (kinematics only, no stepping)."""
    body = env.model.body(env.scene.object("pot", 0).body)
    adr = env.model.jnt_qposadr[body.jntadr[0]]
    env.data.qpos[adr + 2] += dz
    half = math.radians(tilt_deg) / 2
    env.data.qpos[adr + 3:adr + 7] = (math.cos(half), 0.0, math.sin(half), 0.0)
    mujoco.mj_forward(env.model, env.data)


def test_success_predicates_positive_and_negative():
    spec = load_task(TASK)
    _, env = build_scene(spec, 1000)
    checks = {p.type: p for p in spec.success}
    # On the table: not lifted, level, in no hand.
    assert not checks["lifted"].evaluate(env).ok and checks["upright"].evaluate(env).ok
    assert not evaluate_all(spec.success, env).ok
    _pose_pot(env, dz=0.08)
    assert checks["lifted"].evaluate(env).ok and checks["upright"].evaluate(env).ok
    assert not evaluate_all(spec.success, env).ok  # lifted and level, but no hand holds it
    _pose_pot(env, tilt_deg=15.0)
    assert not checks["upright"].evaluate(env).ok


# -- one object in both hands ---------------------------------------------------------------------------------------
@pytest.fixture()
def planner():
    _, env = build_scene(load_task(TASK), None)
    return task_planner(env)


def test_an_object_in_both_hands_is_carried_by_both_in_planning(planner):
    pot = planner.env.scene.object("pot", 0)
    body = planner.env.model.body(pot.body).id
    right_arm = planner.ctx.collisions._arm_bodies["right"]
    # One hand holds it: the other arm is an obstacle as ever.
    planner.ctx.hands["left"].held = pot
    planner.ctx.attach_held("left")
    assert set(planner.ctx.kin.attached) == {"left"} and shared_hold.shared_object(planner.holding) is None
    bodies = lambda geoms: {int(planner.env.model.geom_bodyid[g]) for g in geoms}  # noqa: E731
    assert bodies(planner.ctx.collisions.obstacles("left")) & right_arm
    # Both hands hold it: attached to both, the left arm (planned) places it, the right arm is no obstacle of the
    # left arm's plan, and the pot is no contact between the arms.
    planner.ctx.hands["right"].held = pot
    planner.ctx.attach_held("left")
    assert list(planner.ctx.kin.attached) == ["right", "left"] and planner.ctx.collisions.shared_body() == body
    assert not bodies(planner.ctx.collisions.obstacles("left")) & right_arm
    assert body in bodies(planner.ctx.collisions.movers("left")) and body in bodies(planner.ctx.collisions.movers("right"))
    assert planner.ctx.collisions.arm_arm_distance() > 0.05  # the hands are far apart; through the pot they touch it


def test_arms_carrying_one_object_move_in_step(planner):
    """Two straight joint moves timed on their own (different lengths and profiles) come back as many steps as
    the longer one, each hand at the same share of its way at every step."""
    kin = planner.ctx.kin
    q = {s: kin.arm_q(s) for s in ("left", "right")}
    fingers = np.zeros(6)

    def move(side: str, dq: np.ndarray, n: int, ease: float) -> np.ndarray:
        s = np.linspace(0.0, 1.0, n) ** ease  # ease > 1: slow start
        return np.hstack([q[side] + s[:, None] * dq, np.repeat(fingers[None], n, 0)])

    samples = {"left": move("left", np.array([0.3, 0.1, 0.0, -0.3, 0.0, 0.1, 0.0]), 40, 1.0),
               "right": move("right", np.array([0.3, -0.1, 0.0, -0.3, 0.0, 0.1, 0.0]), 70, 2.0)}
    before = [shared_hold._progress(kin, s, samples[s]) for s in ("left", "right")]
    assert np.max(np.abs(before[0][:40] - before[1][:40])) > 0.3  # timed on their own, the left runs far ahead
    out = shared_hold.in_step(kin, samples)
    assert {len(v) for v in out.values()} == {70}
    after = [shared_hold._progress(kin, s, out[s]) for s in ("left", "right")]
    assert np.max(np.abs(after[0] - after[1])) < 0.02
    for s in ("left", "right"):  # same start and end, the fingers untouched
        assert out[s][0] == pytest.approx(samples[s][0]) and out[s][-1] == pytest.approx(samples[s][-1])
    kin.sync(planner.env.data.qpos)


# -- the reference plan ---------------------------------------------------------------------------------------------
def test_the_reference_plan_lifts_the_pot_with_both_hands(tmp_path):
    result = run_plan(tmp_path, TASK, 3, plan_path(load_task(TASK)).read_text())
    assert result.success, result
    assert "grasped pot 0 with the left hand" in result.events and "grasped pot 0 with the right hand" in result.events
