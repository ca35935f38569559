"""Annotation schema, hand annotations, world-frame queries and scene descriptions."""

import json

import numpy as np
import pytest

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
