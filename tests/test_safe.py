"""The safe (objects/safe.py): a door on a vertical hinge with a handle bar, and a knob with a joint of its own.
Its annotations fit its geometry, an openness asked for a knob point is the knob's, the openness predicates read
a part's own joint, and the safe tasks' specs and reference plan."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from pydantic import ValidationError  # noqa: E402

from humanoidgen.planning import skills
from humanoidgen.objects.library import add_object
from humanoidgen.objects import library  # noqa: E402
from humanoidgen.objects.articulated import set_openness  # noqa: E402
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env  # noqa: E402
from humanoidgen.objects.safe import SafeFamily  # noqa: E402
from humanoidgen.objects.schema import Articulation, ObjectAnnotations  # noqa: E402
from humanoidgen.tasks import predicates as P  # noqa: E402
from humanoidgen.tasks.registry import load_task, plan_path  # noqa: E402
from plan_runs import run_plan  # noqa: E402


@pytest.fixture(scope="module")
def safe_env():
    """The safe alone on the table, turned 10 deg, clear of the robot's hands."""
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder

    b = SceneBuilder()
    add_object(b, "safe", type_id=0, pos=(-0.05, -0.2), yaw=np.radians(10))
    env = HumanoidEnv(b.build())
    return env, env.scene.object("safe", 0)


def _joint_q(env, obj, joint: str) -> float:
    return float(env.data.qpos[env.model.jnt_qposadr[env.model.joint(f"{obj.body}_{joint}").id]])


def _set_knob(env, obj, openness: float) -> None:
    art = obj.annotations.articulation_for("knob")
    env.data.qpos[env.model.jnt_qposadr[env.model.joint(f"{obj.body}_{art.joint}").id]] = art.joint_position(openness)
    mujoco.mj_forward(env.model, env.data)


def test_the_library_gives_the_safe_with_a_knob_joint():
    fam = library.family("safe")  # the safe family, with any imported models of its name beside its own
    assert isinstance(getattr(fam, "base", fam), SafeFamily)
    assert library.annotations("safe", 0).articulation_for("knob") is not None


@pytest.mark.parametrize("type_id", [0, 1])
def test_safe_design_and_annotations_agree(type_id):
    fam = SafeFamily()
    p = fam._p(type_id)
    design = fam._design(p)
    door, knob = design.parts
    ann = library.annotations("safe", type_id)
    # The door turns about a vertical hinge; the knob about its own axis, normal to the door, on the door.
    assert door.joint.kind == "hinge" and door.joint.axis == (0, 0, 1) and ann.articulation.joint == door.joint.name
    assert knob.parent == "door" and knob.joint.kind == "hinge" and knob.joint.axis == (1, 0, 0)
    assert ann.axis("knob_axis").direction == (1.0, 0.0, 0.0) and ann.axis("knob_axis").part == "knob"
    (knob_art,) = ann.part_articulations
    assert knob_art.part == "knob" and knob_art.joint == knob.joint.name
    assert (knob_art.closed, knob_art.open) == pytest.approx(knob.joint.range)
    assert (ann.articulation.closed, ann.articulation.open) == pytest.approx(door.joint.range)
    # Every point and axis names a part the design has.
    parts = {None} | {q.name for q in design.parts}
    assert {kp.part for kp in ann.points} <= parts and {a.part for a in ann.axes} <= parts
    # The grasp point is the handle bar's middle, and the bar stands far enough off the door for open fingers.
    bar = next(g for g in door.geoms if g.name == "handle_bar")
    assert ann.point("handle").position == pytest.approx(bar.pos)
    assert -bar.pos[0] - p["door_thick"] >= 0.08
    # The fin's pinch points are its two ends; the knob sits 10+ cm above the bar's middle.
    fin = next(g for g in knob.geoms if g.name == "knob_fin")
    from humanoidgen.planning.constraint_gen import PART_PINCH_INSET_M

    # The pinch point is the fin's right end; the pads (the planner's inset further in) stay on the fin, 1.5+ cm
    # off the knob's axis, so that turning the hand presses on the fin with a lever.
    pinch = ann.point("knob_fin_right").position
    from humanoidgen.objects.safe import FIN_PINCH_IN

    # ... near the fin's outer face (the fingers point into the door and reach past the pinch point)
    assert pinch == pytest.approx((fin.pos[0] - fin.half[0] + FIN_PINCH_IN, -fin.half[1], 0.0))
    assert fin.pos[0] - fin.half[0] < pinch[0] < fin.pos[0] - fin.half[0] / 2
    assert 0.015 <= -(pinch[1] + PART_PINCH_INSET_M) <= fin.half[1] - 0.005
    assert ann.point("knob_fin_left").position == pytest.approx((fin.pos[0], fin.half[1], 0.0))
    assert knob.pos[2] - bar.pos[2] >= 0.1
    # Grasps: the palm's approach is perpendicular to the bar (the fingers line up with it); pinches: the index
    # edge leads along the fin, the squeeze is across it.
    for op in ann.operations:
        a, b = (np.array(ann.axis(n).direction) for n in (op.approach_axis, op.parallel_axis))
        assert abs(a @ b) < 1e-6, op
    assert {o.point for o in ann.operations_of("pinch")} == {"knob_fin_right"}  # clockwise: from the right end
    assert all(ann.point(o.point).part == "knob" for o in ann.operations_of("pinch"))
    assert {o.point for o in ann.operations_of("grasp")} == {"handle"}


def test_part_articulations_are_validated():
    ann = library.annotations("safe", 0)
    raw = ann.model_dump()
    knob = raw["part_articulations"][0]
    with pytest.raises(ValidationError, match="own part"):
        ObjectAnnotations.model_validate(raw | {"part_articulations": [knob, knob]})
    with pytest.raises(ValidationError, match="own part"):
        ObjectAnnotations.model_validate(raw | {"part_articulations": [dict(knob, part=None)]})
    with pytest.raises(ValidationError, match="joints of their own"):
        ObjectAnnotations.model_validate(raw | {"part_articulations": [dict(knob, joint="hinge")]})
    with pytest.raises(ValidationError, match="need a main articulation"):
        ObjectAnnotations.model_validate(raw | {"articulation": None})
    assert ann.articulation_for("knob").joint == "knob_hinge"
    assert ann.articulation_for("door") == ann.articulation_for(None) == ann.articulation
    assert Articulation(joint="x", closed=0, open=1).part is None


def test_openness_of_a_knob_point_turns_the_knob_not_the_door(safe_env):
    env, obj = safe_env
    set_openness(env.model, env.data, obj.body, obj.annotations, 0.0)
    _set_knob(env, obj, 0.0)
    axis = get_axis_in_env(env, "knob_axis", "safe", 0)
    centre = get_point_in_env(env, "knob", "safe", 0)
    p0 = get_point_in_env(env, "knob_fin_right", "safe", 0)
    p1 = get_point_in_env(env, "knob_fin_right", "safe", 0, openness=0.75)  # the knob turned 90 deg
    r0, r1 = p0 - centre, p1 - centre
    r0, r1 = r0 - (r0 @ axis) * axis, r1 - (r1 @ axis) * axis
    assert np.degrees(np.arccos(r0 @ r1 / np.linalg.norm(r0) / np.linalg.norm(r1))) == pytest.approx(90.0, abs=0.5)
    # Turning about +x into the door: the fin's right end goes down (clockwise as the robot sees it).
    assert p0[2] - p1[2] == pytest.approx(np.linalg.norm(r0), abs=1e-3)
    assert get_point_in_env(env, "knob", "safe", 0, openness=0.75) == pytest.approx(centre, abs=1e-9)
    # A door point at an openness moves with the door; the knob and the simulation stay as they are.
    h0, h1 = get_point_in_env(env, "handle", "safe", 0), get_point_in_env(env, "handle", "safe", 0, openness=1.0)
    hinge = env.data.xpos[env.model.body(f"{obj.body}_door").id]  # the door body's origin is on its hinge
    a0, a1 = (h - hinge for h in (h0, h1))
    assert abs(h1[2] - h0[2]) < 1e-9 and np.linalg.norm(a0[:2]) == pytest.approx(np.linalg.norm(a1[:2]))
    assert np.degrees(np.arctan2(a0[0] * a1[1] - a0[1] * a1[0], a0[:2] @ a1[:2])) == pytest.approx(90.0, abs=0.5)
    assert _joint_q(env, obj, "knob_hinge") == 0.0 and _joint_q(env, obj, "hinge") == 0.0


def test_knob_openness_predicate(safe_env):
    env, obj = safe_env
    knob = P.OpennessAtLeast(obj="safe[0]", part="knob", value=0.75)
    door = P.OpennessAtLeast(obj="safe[0]", value=0.7)
    set_openness(env.model, env.data, obj.body, obj.annotations, 1.0)
    _set_knob(env, obj, 0.5)  # 60 deg: not the 90 asked, with the door wide open
    r = knob.evaluate(env)
    assert not r.ok and "knob" in r.detail and "60 deg" in r.detail
    assert door.evaluate(env).ok
    _set_knob(env, obj, 0.8)  # 96 deg
    assert knob.evaluate(env).ok and "96 deg" in knob.evaluate(env).detail
    from humanoidgen.objects.describe import object_status

    status = object_status(env.model, env.data, obj)  # what prompts see: the door's openness and the knob's
    assert status["openness"] == pytest.approx(1.0) and status["knob openness"] == pytest.approx(0.8)
    assert P.OpennessAtMost(obj="safe[0]", part="knob", value=0.5).evaluate(env).ok is False
    set_openness(env.model, env.data, obj.body, obj.annotations, 0.0)
    assert knob.evaluate(env).ok and not door.evaluate(env).ok
    # A part without a joint of its own is not silently read as the door.
    assert not P.OpennessAtLeast(obj="safe[0]", part="door", value=0.0).evaluate(env).ok
    _set_knob(env, obj, 0.0)


@pytest.mark.parametrize("task", ["open_safe_door", "rotate_safe_knob"])
def test_safe_task_specs_match_the_paper(task):
    spec = load_task(task)
    r = spec.randomization
    assert r.position[1] - r.position[0] == pytest.approx(0.05) and r.position[3] - r.position[2] == pytest.approx(0.05)
    assert r.yaw_deg == (-15.0, 15.0)
    assert plan_path(spec).is_file()


def test_rotate_safe_knob_asks_for_a_90_degree_turn_by_the_hand_holding_it():
    turned, held = load_task("rotate_safe_knob").success
    knob = library.annotations("safe", 0).articulation_for(turned.part)
    assert turned.part == "knob" and np.degrees(knob.joint_position(turned.value)) == pytest.approx(90.0)
    # the paper: "the robot precisely pinches and rotates a knob": turned by the right hand holding it
    assert (held.type, held.part, held.side, held.value) == ("moved_while_held", "knob", "right", turned.value)


def test_open_safe_door_reference_plan_succeeds(tmp_path):
    spec = load_task("open_safe_door")
    result = run_plan(tmp_path, "open_safe_door", 10, plan_path(spec).read_text())
    assert result.success, result


def test_a_ride_cut_short_by_reach_does_not_fail_the_step(tmp_path):
    """Seed 10 pulled to openness 1: the arm's reach ends with the door 88% of the way (it used to fail the step;
    then the move left the door there with an event). The second pull, which cannot be planned all the way from
    there, now goes as far as it gets and lets go (part_grip `_regrip_from_here`): the door swings on to 1."""
    text = plan_path(load_task("open_safe_door")).read_text().replace("openness=0.85)", "openness=1)")
    assert "openness=1)" in text
    result = run_plan(tmp_path, "open_safe_door", 10, text)
    assert result.success, result
    assert any("reached openness 0.9" in e and "of the 1 asked" in e for e in result.events), result.events
    assert any("lets go there" in e for e in result.events), result.events
    assert result.objects["safe[0]"]["openness"] > 0.95


def test_rotate_safe_knob_reference_plan_succeeds(tmp_path):
    spec = load_task("rotate_safe_knob")
    result = run_plan(tmp_path, "rotate_safe_knob", 2, plan_path(spec).read_text())
    assert result.success, result


def test_a_grip_on_the_knob_follows_the_knobs_own_joint(safe_env):
    """The planner's follow records: a pinch of the knob turned to an openness follows the knob's joint (and its
    grip does not roll about the knob's own axis); a grasp of the handle follows the door's."""
    from humanoidgen.planning.part_joint import follow_articulation, follow_openness, point_articulation, \
        rolls_about_joint

    env, obj = safe_env
    set_openness(env.model, env.data, obj.body, obj.annotations, 0.0)
    _set_knob(env, obj, 0.25)
    assert point_articulation(obj, "knob_fin_right").joint == "knob_hinge"
    assert point_articulation(obj, "handle") == obj.annotations.articulation
    pinch = skills.generate(env, {"left": None, "right": None}, "safe", 0, "pinch", "right", openness=0.75)
    f = pinch.follow
    assert f.joint == f"{obj.body}_knob_hinge" and np.degrees(f.q_target) == pytest.approx(90.0)
    assert follow_articulation(env, f).part == "knob" and follow_openness(env, f) == pytest.approx(0.25)
    grasp = skills.generate(env, {"left": None, "right": None}, "safe", 0, "grasp", "right", openness=1.0)
    assert grasp.follow.joint == f"{obj.body}_hinge" and follow_openness(env, grasp.follow) == 0.0
    assert np.degrees(grasp.follow.q_target) == pytest.approx(90.0)
    # A roll about the knob's own axis only undoes its turn; a roll about the handle bar (off the door's hinge)
    # does not, nor does a roll about an axis across the knob.
    m, d = env.model, env.data
    knob_axis, centre = get_axis_in_env(env, "knob_axis", "safe", 0), get_point_in_env(env, "knob", "safe", 0)
    assert rolls_about_joint(m, d, f.joint, knob_axis, centre + 0.01 * get_axis_in_env(env, "fin_normal", "safe", 0))
    assert not rolls_about_joint(m, d, f.joint, get_axis_in_env(env, "fin_normal", "safe", 0), centre)
    bar = get_point_in_env(env, "handle", "safe", 0)
    assert not rolls_about_joint(m, d, grasp.follow.joint, get_axis_in_env(env, "door_hinge", "safe", 0), bar)
    _set_knob(env, obj, 0.0)


def test_the_bodies_a_part_joint_moves(safe_env):
    from humanoidgen.planning.part_joint import moving_bodies

    env, obj = safe_env
    m = env.model
    names = lambda ids: {m.body(b).name for b in ids}  # noqa: E731
    assert names(moving_bodies(m, f"{obj.body}_knob_hinge")) == {f"{obj.body}_knob"}
    assert names(moving_bodies(m, f"{obj.body}_hinge")) == {f"{obj.body}_door", f"{obj.body}_knob"}
