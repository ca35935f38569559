"""The paper's planner API as plans written outside the project use it: task target poses for action="target",
the default hand, object aliases and numbered names, "pour", an action mapped to the object's closest operation,
and the box lid's second push point."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from humanoidgen.objects.describe import describe_scene
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.planning.planner import PlanningError
from humanoidgen.tasks.registry import TaskSpecError, load_task, parse_task
from humanoidgen.tasks.scene import build_scene

from plan_runs import task_planner  # noqa: E402

# -- spec validation -----------------------------------------------------------------------------------------------
BASE = {
    "name": "t", "description": "stack", "arms": "single", "horizon": "short",
    "objects": [{"type": "cube", "type_id": 0, "pos": [-0.32, -0.05]},
                {"type": "cube", "type_id": 1, "pos": [-0.34, -0.19]}],
    "success": [{"type": "stacked", "objs": ["cube[0]", "cube[1]"]}],
}


def _spec(targets=None, **object_fields) -> dict:
    d = copy.deepcopy(BASE)
    if targets is not None:
        d["targets"] = targets
    for k, v in object_fields.items():
        d["objects"][0][k] = v
    return d


def test_valid_targets_and_aliases_load_and_survive_a_dump():
    spec = parse_task(_spec(
        [{"object": "cube[1]", "relative_to": "cube[0]", "offset": [0, 0, 0.045]},
         {"object": "cube[0]", "name": "target1", "hand": "right", "pos": [-0.3, 0.0, 0.05],
          "random": [0.01, -0.01, -0.01, 0.01]},
         {"object": "cube[0]", "name": "target2", "relative_to": ["cube[0]", "cube[1]"], "anchor": "initial",
          "offset": [0, 0, 0.1]}],
        aliases=["base_cube"]))
    assert spec.targets[1].random == (-0.01, 0.01, -0.01, 0.01)  # sorted like randomization ranges
    assert spec.aliases() == {"base_cube": ("cube", 0)}
    again = parse_task(spec.model_dump(mode="json"))  # what episode workers receive
    assert again == spec


@pytest.mark.parametrize("targets, objects, field", [
    ([{"object": "cube[2]", "pos": [-0.3, 0, 0.05]}], {}, "targets.0.object"),
    ([{"object": "cube[0]", "relative_to": "bowl[0]"}], {}, "targets.0.relative_to"),
    ([{"object": "cube[0]", "pos": [-0.3, 0, 0.05], "relative_to": "cube[1]"}], {}, "either pos"),
    ([{"object": "cube[0]"}], {}, "either pos"),
    ([{"object": "cube[0]", "pos": [0.2, 0, 0.05]}], {}, "targets.0.pos"),  # in front of the table: no reach
    ([{"object": "cube[0]", "pos": [-0.3, 0, 0.05], "random": [0, 0, 0.3, 0.4]}], {}, "targets.0.pos"),
    ([{"object": "cube[0]", "hand": "left", "pos": [-0.3, -0.3, 0.05]}], {}, "left hand"),
    ([{"object": "cube[0]", "pos": [-0.3, 0, float("nan")]}], {}, "finite"),
    ([{"object": "cube[0]", "pos": [-0.3, 0, 0.05], "offset": [0, 0, 1]}], {}, "offset applies only"),
    ([{"object": "cube[1]", "relative_to": "cube[0]", "random": [0, 0.01, 0, 0.01]}], {}, "random applies only"),
    ([{"object": "cube[0]", "relative_to": "cube[0]", "offset": [0, 0, 0.1]}], {}, "anchor: initial"),
    ([{"object": "cube[1]", "relative_to": "cube[0]", "point": "rim"}], {}, "targets.0.point"),
    ([{"object": "cube[1]", "relative_to": "cube[0]", "offset": [0, 0, 0.9]}], {}, "targets.0.offset"),
    ([{"object": "cube[0]", "pos": [-0.3, 0, 0.05]}, {"object": "cube[0]", "pos": [-0.3, 0, 0.06]}], {},
     "targets.1: cube[0] has two 'target'"),
    ([{"object": "cube[0]", "name": "target3", "pos": [-0.3, 0, 0.05]}], {}, "targets.0.name"),
    (None, {"aliases": ["cube0"]}, "objects.0.aliases"),
    (None, {"aliases": ["bowl"]}, "object type"),
    (None, {"aliases": ["Big cube"]}, "objects.0.aliases"),
])
def test_bad_targets_and_aliases_are_rejected_naming_the_field(targets, objects, field):
    with pytest.raises(TaskSpecError, match=field.replace(".", r"\.").replace("[", r"\[")):
        parse_task(_spec(targets, **objects))


def test_an_alias_names_one_object():
    d = _spec(aliases=["block"])
    d["objects"][1]["aliases"] = ["block"]
    with pytest.raises(TaskSpecError, match="already names objects.0"):
        parse_task(d)


def test_targets_do_not_change_the_layouts_and_random_offsets_follow_the_seed():
    plain = parse_task(_spec())
    with_targets = parse_task(_spec([{"object": "cube[0]", "pos": [-0.3, 0.0, 0.05], "random": [-0.01, 0.01, -0.01, 0.01]}]))
    assert plain.sample_layout(7) == with_targets.sample_layout(7)


# -- scenes ----------------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def handover():
    spec = load_task("block_handover")
    scene, env = build_scene(spec, 0)
    return spec, env, task_planner(env, seed=0)


def test_aliases_and_numbered_names_resolve_to_the_object(handover):
    _, env, _ = handover
    block, target_cube = env.scene.object("cube", 0), env.scene.object("cube", 1)
    assert env.scene.object("rectangular_cube") is block
    assert env.scene.object("target_cube", 0) is target_cube
    assert env.scene.object("cube1") is target_cube and env.scene.object("cube_1", 1) is target_cube
    assert np.allclose(get_point_in_env(env, "center", "target_cube"), get_point_in_env(env, "center", "cube", 1))
    assert np.allclose(get_axis_in_env(env, "z", obj_type="rectangular_cube"), get_axis_in_env(env, "z", obj_type="cube"))
    with pytest.raises(KeyError, match="obj_id 1 but obj_id=2"):
        env.scene.object("cube1", 2)
    with pytest.raises(KeyError, match="names one object"):
        env.scene.object("target_cube", 3)
    with pytest.raises(KeyError, match="aliases: rectangular_cube = cube"):
        env.scene.object("bottle", 0)


def test_describe_scene_shows_aliases_and_targets(handover):
    _, env, _ = handover
    desc = describe_scene(env, as_json=False)
    block = desc["attributes"][0]
    assert block["aliases"] == ["rectangular_cube"]
    assert set(block["targets"]) == {"target (right hand)", "target (left hand)", "target1", "target2"}
    assert "cube[1]" in block["targets"]["target (left hand)"]
    now = desc["status"][0]["targets"]
    cube1 = get_point_in_env(env, "center", "cube", 1)
    assert np.allclose(now["target (left hand)"], cube1 + [0, 0, 0.063], atol=1e-3)  # follows cube 1
    assert now["target1"] == [-0.32, 0.0, 0.15]  # the mid-air hand-over pose
    assert "targets" not in desc["attributes"][1]
    assert "target (left hand)" in describe_scene(env)  # the JSON the prompts show


def test_hand_specific_targets_and_alias_lookup_in_generate_constraints(handover):
    _, env, planner = handover
    block = env.scene.object("cube", 0)
    planner.ctx.hands["left"].held = block  # constraints only: no motion, so pretend the left hand holds the block
    try:
        c = planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="target", hand_name="left")
        goal = c[0].object_key_point
        assert np.allclose(goal, get_point_in_env(env, "center", "target_cube") + [0, 0, 0.063], atol=1e-6)
        assert c[0].meta.approach_axis is not None  # set down from above
        c = planner.generate_constraints("cube", 0, "target2", "left")
        assert np.allclose(c[0].object_key_point, goal)
    finally:
        planner.ctx.hands["left"].held = None


def test_target_without_holding_says_what_to_do(handover):
    _, _, planner = handover
    with pytest.raises(PlanningError, match="holds nothing.*action='pinch'"):
        planner.generate_constraints(obj_name="rectangular_cube", obj_id=0, action="target", hand_name="right")
    planner.ctx.hands["left"].held = planner.env.scene.object("cube", 0)
    try:
        with pytest.raises(PlanningError, match="held by the left hand.*hand_name='left'"):
            planner.generate_constraints(obj_name="cube0", action="target")
    finally:
        planner.ctx.hands["left"].held = None


def test_default_hand_is_right(handover):
    _, _, planner = handover
    c = planner.generate_constraints(obj_name="cube", obj_id=0, action="pinch")
    assert c[0].side == "right"
    c = planner.generate_constraints("cube0", action="pinch")
    assert c[0].side == "right" and "cube 0" in c[0].name
    with pytest.raises(PlanningError, match="give action="):
        planner.generate_constraints("cube", 0)


def test_fallback_lift_where_the_task_defines_no_target(handover):
    _, env, planner = handover
    planner.ctx.hands["right"].held = env.scene.object("cube", 1)  # the target cube has no target of its own
    try:
        before = len(planner.events)
        c = planner.generate_constraints(obj_name="target_cube", action="target")
        centre = get_point_in_env(env, "center", "cube", 1)
        assert np.allclose(c[0].object_key_point, centre + [0, 0, 0.10])
        assert any("no 'target' pose in this task" in e and "lifted it 10 cm" in e for e in planner.events[before:])
        with pytest.raises(PlanningError, match="no 'target1' pose in this task.*action='move'"):
            planner.generate_constraints(obj_name="target_cube", action="target1")
    finally:
        planner.ctx.hands["right"].held = None


def test_unknown_action_lists_the_actions(handover):
    _, _, planner = handover
    with pytest.raises(PlanningError, match="use one of grasp, pinch, target.*pour"):
        planner.generate_constraints("cube", 0, "lift")


# -- "target" in a short episode --------------------------------------------------------------------------------
def test_pinch_then_target_puts_the_held_cube_at_its_target():
    spec = load_task("block_stack_single")
    _, env = build_scene(spec, 0)
    planner = task_planner(env, seed=0)
    planner.hand_pre_pinch("right")
    c = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
    planner.hand_pinch("right", pinch_object="cube", obj_id=1)
    c = planner.generate_constraints(obj_name="cube", obj_id=1, action="target", hand_name="right")
    goal = c[0].object_key_point.copy()
    assert np.allclose(goal, get_point_in_env(env, "center", "cube", 0) + [0, 0, 0.045], atol=1e-6)
    _, pose = planner.generate_end_effector_pose(c, hand_name="right")
    planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
    held = get_point_in_env(env, "center", "cube", 1)
    assert np.linalg.norm(held - goal) < 0.015, f"cube 1 at {held.round(3)}, target {goal.round(3)}"
    planner.open_hand("right")
    assert planner.events[-1] == "released cube 1 and it stayed on cube 0"


# -- pour, mapped operations, the box lid's second point --------------------------------------------------------
def test_pour_tips_the_held_cup_toward_the_bowl():
    _, env = build_scene(load_task("cup_pour_easy"), None)
    planner = task_planner(env, seed=0)
    planner.ctx.hands["right"].held = env.scene.object("cup", 0)
    c = planner.generate_constraints(obj_name="cup", obj_id=0, action="pour")
    bowl, cup = get_point_in_env(env, "center", "bowl", 0), get_point_in_env(env, "center", "cup", 0)
    goal = c[0].object_key_point
    side = (cup - bowl)[:2] / np.linalg.norm((cup - bowl)[:2])
    assert np.allclose(goal[:2], bowl[:2] + 0.06 * side, atol=1e-6)  # beside the bowl, on the cup's side
    assert goal[2] > bowl[2] + 0.15
    tilt = c[1].object_axis  # the cup's axis: mostly down, leaning toward the bowl
    assert math.degrees(math.acos(tilt[2])) == pytest.approx(160, abs=0.5) and tilt[:2] @ side < 0
    assert "pour lip" in c[2].name and c[2].soft  # the cup's functional "pour" annotation, as a preference
    assert [len(a.constraints) for a in c[0].meta.alternatives] == [3, 3]  # less steep tilts to fall back on
    planner.ctx.hands["right"].held = None
    with pytest.raises(PlanningError, match="holds nothing"):
        planner.generate_constraints(obj_name="cup", obj_id=0, action="pour")
    planner.ctx.hands["right"].held = env.scene.object("cube", 0)
    with pytest.raises(PlanningError, match="cube cannot pour.*cup"):
        planner.generate_constraints(obj_name="cube", obj_id=0, action="pour")
    planner.ctx.hands["right"].held = None


def test_grasp_on_a_laptop_screen_takes_its_top_edge():
    # The screen has its own grasp now (the hand over the top edge, test_part_holding); it used to map to the
    # pinch, which did not hold the screen.
    _, env = build_scene(load_task("close_laptop_hard"), None)
    planner = task_planner(env, seed=0)
    c = planner.generate_constraints(obj_name="laptop", obj_id=0, action="grasp")
    assert c[0].name.startswith("grasp point on laptop 0 screen_grip")
    assert c[0].meta.posture is None  # hand_grasp closes the whole hand


def test_an_action_with_no_close_operation_lists_what_the_object_has():
    from humanoidgen.objects import library
    from humanoidgen.planning.constraint_gen import ConstraintGenerationError
    from humanoidgen.planning.target_actions import operation_for
    from humanoidgen.sim.scene import SceneObject

    toaster = SceneObject("toaster", 0, "toaster_0", 2, annotations=library.annotations("toaster", 0))
    with pytest.raises(ConstraintGenerationError, match="no 'grasp' annotation; it supports: press.*target1 \\(press"):
        operation_for(toaster, "grasp")


def test_box_lid_has_two_push_points():
    # Without the task's push target (tests/test_push_targets.py), target1/target2 are the annotated push points.
    _, env = build_scene(load_task("close_box_easy").model_copy(update={"targets": []}), None)
    planner = task_planner(env, seed=0)
    t1 = planner.generate_constraints(obj_name="box", obj_id=0, action="target1")
    t2 = planner.generate_constraints(obj_name="box", obj_id=0, action="target2")
    assert t1[0].name == "fingertip on box lid_front" and t2[0].name == "fingertip on box lid_top"
    assert np.allclose(t2[0].object_key_point, get_point_in_env(env, "lid_top", "box", 0))
    lid_in = get_axis_in_env(env, "lid_in", obj_type="box", obj_id=0)
    assert np.allclose(t2[0].meta.approach_axis, lid_in)  # pushing the lid's outer face, into the lid
    t2_shut = planner.generate_constraints(obj_name="box", obj_id=0, action="target2", openness=0.0)
    assert t2_shut[0].meta.follow is not None  # with openness: the fingertip rides the lid down
