"""Annotation schema, hand annotations, world-frame queries and scene descriptions."""

import json

import numpy as np
import pytest

from humanoidgen.objects.library import add_object
from humanoidgen.objects.hands import HAND_POSTURES, hand_axes, hand_points
from humanoidgen.objects.schema import AnnotationError, ObjectAnnotations, load_annotations, save_annotations
from humanoidgen.sim.layout import SIDES

GOOD = {
    "family": "block",
    "type_id": 0,
    "description": "a test block",
    "bbox_min": [-0.02, -0.02, -0.02],
    "bbox_max": [0.02, 0.02, 0.02],
    "points": [{"name": "top", "position": [0, 0, 0.015]}],
    "axes": [{"name": "down", "direction": [0, 0, -1]}, {"name": "x", "direction": [1, 0, 0]},
             {"name": "y", "direction": [0, 1, 0]}],
    "operations": [{"operation": "pinch", "point": "top", "approach_axis": "down", "attach_axis": "x",
                    "parallel_axis": "y"}],
}


def test_valid_file_round_trips(tmp_path):
    ann = ObjectAnnotations.model_validate(GOOD)
    save_annotations(ann, tmp_path / "a.yaml")
    assert load_annotations(tmp_path / "a.yaml") == ann


@pytest.mark.parametrize(
    "mutate, field",
    [
        (lambda d: d["axes"][0].update(direction=[0, 0, -2]), "axes.0.direction"),
        (lambda d: d.pop("bbox_min"), "bbox_min"),
        (lambda d: d["operations"][0].update(operation="juggle"), "operations.0.operation"),
        (lambda d: d["operations"][0].update(point="bottom"), "point 'bottom' is not defined"),
        (lambda d: d["points"][0].update(colour="red"), "points.0.colour"),
    ],
)
def test_malformed_files_are_rejected_naming_file_and_field(tmp_path, mutate, field):
    import copy

    import yaml

    data = copy.deepcopy(GOOD)
    mutate(data)
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(AnnotationError) as exc:
        load_annotations(path)
    assert str(path) in str(exc.value) and field in str(exc.value)


def test_unknown_names_list_the_valid_ones():
    ann = ObjectAnnotations.model_validate(GOOD)
    with pytest.raises(KeyError, match="points: top"):
        ann.point("bottom")
    with pytest.raises(KeyError, match="down, x, y"):
        ann.axis("up")


def test_hand_annotations_are_named_as_the_paper_and_unit():
    for side in SIDES:
        assert f"grasp_point_base_{side}_hand" in hand_points(side)
        for name in (f"{side}_pinch_axis", f"{side}_ring_2_index", f"{side}_grasp_wrist_2_palm_axis"):
            assert np.linalg.norm(hand_axes(side)[name]) == pytest.approx(1.0)
    for name in ("open", "pre_grasp", "grasp", "pre_pinch", "pinch", "press"):
        assert len(HAND_POSTURES[name]) == 6


# -- queries in the world frame -------------------------------------------------------------------------
from humanoidgen.objects import library  # noqa: E402
from humanoidgen.objects.describe import describe_scene  # noqa: E402
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env  # noqa: E402
from humanoidgen.sim.env import HumanoidEnv  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402


@pytest.fixture(scope="module")
def query_env():
    b = SceneBuilder()
    add_object(b, "cube", 0, pos=(-0.35, -0.15))
    add_object(b, "cube", 1, pos=(-0.35, 0.15), yaw=np.pi / 2)
    add_object(b, "drawer", 0, pos=(-0.05, 0.30))
    return HumanoidEnv(b.build())


def test_axes_and_points_follow_object_pose(query_env):
    env = query_env
    assert np.allclose(get_axis_in_env(env, "x", obj_type="cube", obj_id=0), [1, 0, 0], atol=1e-9)
    assert np.allclose(get_axis_in_env(env, "x", obj_type="cube", obj_id=1), [0, 1, 0], atol=1e-9)
    assert np.allclose(get_axis_in_env(env, "y", obj_type="cube", obj_id=1), [-1, 0, 0], atol=1e-9)
    # A point 2 cm along the object's own x axis lies along world +y for the turned cube.
    c1 = get_point_in_env(env, "center", "cube", 1)
    assert np.allclose(get_point_in_env(env, "center", "cube", 1, related_point=[0.02, 0, 0]) - c1, [0, 0.02, 0],
                       atol=1e-9)
    assert c1[2] == pytest.approx(0.02, abs=1e-6)  # placed on the table by its bounding box


def test_part_points_at_an_openness_are_where_the_part_will_be(query_env):
    env = query_env
    closed = get_point_in_env(env, "handle_upper", "drawer", 0, openness=0.0)
    opened = get_point_in_env(env, "handle_upper", "drawer", 0, openness=1.0)
    now = get_point_in_env(env, "handle_upper", "drawer", 0)
    assert np.allclose(now, closed, atol=1e-6)  # the drawer starts closed
    delta = opened - closed
    assert delta[0] < -0.1 and abs(delta[1]) < 1e-6 and abs(delta[2]) < 1e-6  # slides out toward the robot
    with pytest.raises(ValueError, match="moving part"):
        get_point_in_env(env, "center", "cube", 0, openness=0.5)


def test_hand_points_move_with_the_hand(query_env):
    env = query_env
    p0 = get_point_in_env(env, "grasp_point_base_right_hand")
    a = env.init_action()
    a[7] -= 0.3  # right shoulder pitch
    for _ in range(40):
        env.step(a)
    p1 = get_point_in_env(env, "grasp_point_base_right_hand")
    assert np.linalg.norm(p1 - p0) > 0.05
    axis = get_axis_in_env(env, "right_grasp_axis")
    assert np.linalg.norm(axis) == pytest.approx(1.0)
    env.reset()


def test_unknown_names_raise_listing_valid_ones(query_env):
    env = query_env
    with pytest.raises(KeyError, match="points: "):
        get_point_in_env(env, "nose", "cube", 0)
    with pytest.raises(KeyError, match="Hand points: .*grasp_point_base_left_hand"):
        get_point_in_env(env, "nose")
    with pytest.raises(KeyError, match=r"objects: cube\[0\], cube\[1\], drawer\[0\]"):
        get_point_in_env(env, "center", "cube", 5)
    with pytest.raises(KeyError, match="known types: .*bottle"):
        library.family("unicorn")


def test_scene_description_lists_objects_poses_and_annotations(query_env):
    desc = json.loads(describe_scene(query_env))
    types = [(a["type"], a["obj_id"]) for a in desc["attributes"]]
    assert types == [("cube", 0), ("cube", 1), ("drawer", 0)]
    drawer = desc["attributes"][2]
    assert "handle_upper" in drawer["points"] and "grasp@handle_upper" in drawer["operations"]
    status = {(s["type"], s["obj_id"]): s for s in desc["status"]}
    assert status[("drawer", 0)]["openness"] == pytest.approx(0.0, abs=0.01)
    assert "openness" not in status[("cube", 0)]
    assert np.allclose(status[("cube", 0)]["p"][:2], [-0.35, -0.15], atol=1e-3)
