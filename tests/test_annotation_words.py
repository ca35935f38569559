"""Every point and axis of the hands and of each object family is described in words (the schema requires it), an
articulated family says what its openness moves in physical units, and the prompts and docs show that text."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import math  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import mujoco  # noqa: E402
import pytest  # noqa: E402
import yaml  # noqa: E402

from humanoidgen.generation import object_text, prompts  # noqa: E402
from humanoidgen.objects import library  # noqa: E402
from humanoidgen.objects.family_data import FAMILIES_DIR, FamilyDataError, _validated, family_file  # noqa: E402
from humanoidgen.objects.hands import HAND_AXIS_NAMES, HAND_POINT_NAMES, hand_description  # noqa: E402
from humanoidgen.objects.params import FamilyFile  # noqa: E402

FAMILIES = sorted(library.families())


@pytest.mark.parametrize("name", FAMILIES)
def test_every_point_and_axis_of_every_model_is_described(name: str) -> None:
    info = family_file(name)
    points = {p.name: p for p in info.points}
    axes = {a.name for a in info.axes}
    for m in library.family(name).models():
        ann = library.annotations(name, m.type_id)
        missing = [p.name for p in ann.points if p.name != "center" and p.name not in points]
        assert not missing, f"{name}/{m.type_id}: points without a description in family.yaml: {missing}"
        assert {a.name for a in ann.axes} <= axes
        for p in ann.points:  # a point on a moving part says which (the text shows it)
            if p.name in points:
                assert points[p.name].part == p.part, f"{name}/{m.type_id}: {p.name} is on {p.part!r}"
    assert all(p.description.strip() for p in info.points) and all(a.description.strip() for a in info.axes)


@pytest.mark.parametrize("kind, entry", [("points", {"name": "rim"}), ("axes", {"name": "up", "direction": [0, 0, 1]})])
def test_a_new_point_or_axis_without_a_description_is_refused(kind: str, entry: dict, tmp_path: Path) -> None:
    raw = yaml.safe_load((FAMILIES_DIR / "bowl" / "family.yaml").read_text())
    raw.setdefault(kind, []).append(entry)
    with pytest.raises(FamilyDataError, match=rf"{kind}\.\d+\.description"):
        _validated(FamilyFile, raw, tmp_path / "family.yaml")


def test_an_articulated_family_must_say_what_its_openness_moves(tmp_path: Path) -> None:
    raw = yaml.safe_load((FAMILIES_DIR / "drawer" / "family.yaml").read_text())
    raw.pop("openness")
    with pytest.raises(FamilyDataError, match="openness"):
        _validated(FamilyFile, raw, tmp_path / "family.yaml")


def test_every_hand_point_and_axis_is_described() -> None:
    for name in HAND_POINT_NAMES + HAND_AXIS_NAMES:
        assert len(hand_description(name)) > 10, name
    with pytest.raises(KeyError):
        hand_description("left_elbow_axis")


def _joint_type(name: str, type_id: int, joint: str) -> int:
    spec = mujoco.MjSpec()
    body = spec.worldbody.add_body(name=f"{name}_0")
    library.family(name).build(spec, body, type_id)
    model = spec.compile()
    return int(model.jnt_type[model.joint(f"{name}_0_{joint}").id])


@pytest.mark.parametrize("name", [n for n in FAMILIES if library.family(n).articulated])
def test_each_joint_of_an_articulated_family_has_its_openness_in_the_right_unit(name: str) -> None:
    info = family_file(name)
    for m in library.family(name).models():
        ann = library.annotations(name, m.type_id)
        joints = [ann.articulation, *ann.part_articulations]
        specs = [object_text._spec_for(info, ann, a) for a in joints]
        assert None not in specs and len({s.part for s in specs}) == len(joints), f"{name}/{m.type_id}"
        for art, spec in zip(joints, specs):
            assert any(p.part == spec.part for p in ann.points), f"{name}: no point on the {spec.part}"
            kind = _joint_type(name, m.type_id, art.joint)
            assert kind == (mujoco.mjtJoint.mjJNT_HINGE if spec.unit == "deg" else mujoco.mjtJoint.mjJNT_SLIDE)
            assert spec.recommended_max is None or spec.note, "a recommended maximum says why"


def test_the_text_says_which_part_openness_moves_in_physical_units() -> None:
    text = object_text.objects_text([("safe", 0), ("box", 1), ("drawer", 0)])
    knob = library.annotations("safe", 0).part_articulations[0]
    assert f"0 to {math.degrees(knob.open):.0f} deg" in text and "`knob openness`" in text and "part: knob" in text
    assert "0 to 90 deg (0.1 openness = 9 deg)" in text  # the door
    assert "Ask for at most 0.85" in text and "Ask for at most 0.9" in text
    assert "from openness 0.65 up" in text  # the storage box's lid falls shut below
    assert "0 to 150 mm" in text  # the drawer's travel
    for p in family_file("safe").points:
        assert f"`{p.name}`" in text and p.description in text


def test_the_script_prompt_describes_the_scene_objects_only() -> None:
    scene = {"attributes": [{"type": "cube", "obj_id": 0, "type_id": 0}, {"type": "bowl", "obj_id": 0, "type_id": 1}],
             "status": []}
    text = prompts.script_prompt("put the cube in the bowl", scene, {"right": {"p": [0, 0, 0], "q": [1, 0, 0, 0]}},
                                 ["planner"])
    assert object_text.objects_text([("cube", 0), ("bowl", 1)]) in text
    assert "- drawer (" not in text and "where a pinch from above closes" in text


def test_the_docs_show_every_family() -> None:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "docs"))
    import hooks

    text = hooks.on_page_markdown("<!-- annotation-vocabulary -->", None, None, None)
    assert all(f"- {n} (" in text for n in FAMILIES)
