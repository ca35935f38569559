"""Articulated object families: they compile, hold their openness, and their annotations fit their geometry."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from humanoidgen.objects.articulated import ARTICULATED_FAMILIES, get_openness, set_openness  # noqa: E402
from humanoidgen.objects.schema import ObjectAnnotations  # noqa: E402

MODELS = [(f.name, m.type_id) for f in ARTICULATED_FAMILIES.values() for m in f.models()]
MODEL_IDS = [f"{n}-{t}" for n, t in MODELS]
SCENE_Y = {"drawer": -0.45, "laptop": -0.2, "box": 0.05, "toaster": 0.55}  # the safe: tests/test_safe.py
SCENE_X = -0.1  # clear of the robot's hands at their initial posture (x ~ -0.4)


def _standalone(family: str, type_id: int):
    """A tiny world: a plane at z=0 and the object resting on it."""
    fam = ARTICULATED_FAMILIES[family]
    ann = fam.annotations(type_id)
    spec = mujoco.MjSpec()
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.worldbody.add_geom(name="ground", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[2, 2, 0.1])
    body = spec.worldbody.add_body(name=f"{family}_0", pos=[0, 0, -ann.bbox_min[2]])
    fam.build(spec, body, type_id)
    model = spec.compile()
    return model, mujoco.MjData(model), f"{family}_0", ann


@pytest.fixture(scope="module")
def table_scene():
    """One table scene with one model of each family side by side (type_id 1 where there is one)."""
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.scene import SceneBuilder

    builder = SceneBuilder()
    objs = {}
    for name, fam in ARTICULATED_FAMILIES.items():
        type_id = fam.models()[-1].type_id
        ann = fam.annotations(type_id)
        obj, body = builder.add_object_body(name, np.array([SCENE_X, SCENE_Y[name], -ann.bbox_min[2]]),
                                            type_id=type_id, free=False)
        fam.build(builder.spec, body, type_id)
        objs[name] = (obj.body, ann)
    env = HumanoidEnv(builder.build())  # holds the robot at its initial posture while we step
    return env, objs


def _falls_shut(family, type_id) -> bool:
    """A model with a free-running hinge (its file gives the hinge less friction than its family's default): its
    part falls shut when let go low."""
    fam = ARTICULATED_FAMILIES[family]
    own = next(m for m in fam.models() if m.type_id == type_id).params
    default = fam._data().info.defaults.get("hinge")
    return "hinge" in own and default is not None and own["hinge"]["frictionloss"] < default["frictionloss"]


def _hold(model, data, body, ann, openness, seconds):
    set_openness(model, data, body, ann, openness)
    mujoco.mj_step(model, data, nstep=int(round(seconds / model.opt.timestep)))
    return get_openness(model, data, body, ann)


def _part_world(model, data, body, kp):
    bid = model.body(body if kp.part is None else f"{body}_{kp.part}").id
    return data.xpos[bid] + data.xmat[bid].reshape(3, 3) @ np.asarray(kp.position)


def _object_boxes(model, body):
    root = model.body(body).id
    return [g for g in range(model.ngeom) if model.body_rootid[model.geom_bodyid[g]] == root]


def _dist_to_boxes(model, data, geoms, p):
    best = np.inf
    for g in geoms:
        assert model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX
        local = data.geom_xmat[g].reshape(3, 3).T @ (p - data.geom_xpos[g])
        best = min(best, float(np.linalg.norm(np.maximum(np.abs(local) - model.geom_size[g], 0.0))))
    return best


# -- families ---------------------------------------------------------------------------------------------------
def test_registry_has_the_four_families():
    assert set(ARTICULATED_FAMILIES) == {"drawer", "laptop", "box", "toaster"}
    for name, fam in ARTICULATED_FAMILIES.items():
        assert fam.name == name and fam.articulated is True
        assert 1 <= len(fam.models()) <= 2
        assert all(m.family == name for m in fam.models())
    with pytest.raises(KeyError):
        ARTICULATED_FAMILIES["drawer"].annotations(99)


@pytest.mark.parametrize("family,type_id", MODELS, ids=MODEL_IDS)
def test_model_compiles_alone_with_prefixed_names(family, type_id):
    model, data, body, ann = _standalone(family, type_id)
    mujoco.mj_forward(model, data)
    for kind, n in ((mujoco.mjtObj.mjOBJ_BODY, model.nbody), (mujoco.mjtObj.mjOBJ_GEOM, model.ngeom),
                    (mujoco.mjtObj.mjOBJ_JOINT, model.njnt)):
        for i in range(n):
            name = mujoco.mj_id2name(model, kind, i)
            if name not in (None, "world", "ground"):
                assert name.startswith(body + "_") or name == body, name
    # at openness 0, the geoms' extent is the annotated bounding box around the body's origin
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    origin = data.xpos[model.body(body).id]
    for g in _object_boxes(model, body):
        c = data.geom_xpos[g] - origin
        ext = np.abs(data.geom_xmat[g].reshape(3, 3)) @ model.geom_size[g]
        lo, hi = np.minimum(lo, c - ext), np.maximum(hi, c + ext)
    np.testing.assert_allclose(lo, ann.bbox_min, atol=1e-6)
    np.testing.assert_allclose(hi, ann.bbox_max, atol=1e-6)
    np.testing.assert_allclose(lo, -hi, atol=1e-6)  # origin at the bounding box's centre
    assert data.ncon == 0  # no part rests against its own shell or the ground


@pytest.mark.parametrize("family,type_id", MODELS, ids=MODEL_IDS)
def test_annotations_validate_and_axes_are_unit(family, type_id):
    ann = ARTICULATED_FAMILIES[family].annotations(type_id)
    again = ObjectAnnotations.model_validate(ann.model_dump(mode="json"))
    assert again == ann and ann.family == family and ann.type_id == type_id
    for ax in ann.axes:
        assert np.linalg.norm(ax.direction) == pytest.approx(1.0, abs=1e-9)
    assert ann.articulation is not None and ann.articulation.open != ann.articulation.closed
    assert ann.operations and ann.functions


def test_required_operations_are_annotated():
    ops = {n: {o.operation for o in f.annotations(0).operations} for n, f in ARTICULATED_FAMILIES.items()}
    assert {"grasp", "pull", "push"} <= ops["drawer"]
    assert {"push", "flip", "pinch"} <= ops["laptop"]
    assert {"grasp", "pinch", "flip"} <= ops["box"]
    assert "press" in ops["toaster"]
    drawer = ARTICULATED_FAMILIES["drawer"].annotations(0)
    assert {o.point for o in drawer.operations_of("grasp")} == {"handle_upper", "handle_lower"}
    assert drawer.functions[0].function == "storage" and drawer.axis("opening").direction == (0.0, 0.0, 1.0)
    assert all(p.part == "drawer" for p in drawer.points)


# -- openness -------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("family,type_id", MODELS, ids=MODEL_IDS)
def test_openness_round_trips_and_holds_alone(family, type_id):
    model, data, body, ann = _standalone(family, type_id)
    if _falls_shut(family, type_id):  # stays up when left high, falls shut when let go low
        assert _hold(model, data, body, ann, 0.75, 2.0) == pytest.approx(0.75, abs=0.02)
        assert _hold(model, data, body, ann, 0.3, 3.0) <= 0.05
    else:
        assert _hold(model, data, body, ann, 0.3, 1.0) == pytest.approx(0.3, abs=0.02)
        assert _hold(model, data, body, ann, 0.5, 2.0) == pytest.approx(0.5, abs=0.02)
    set_openness(model, data, body, ann, 1.7)  # clipped
    assert get_openness(model, data, body, ann) == pytest.approx(1.0)
    j = model.joint(f"{body}_{ann.articulation.joint}").id
    assert data.qpos[model.jnt_qposadr[j]] == pytest.approx(ann.articulation.open)


def test_table_scene_compiles_and_openness_holds(table_scene):
    env, objs = table_scene
    model, data = env.model, env.data
    objs = {n: (b, a) for n, (b, a) in objs.items() if not _falls_shut(n, a.type_id)}
    for name, (body, ann) in objs.items():
        assert model.body(body).jntnum == 0  # fixed to the table
        set_openness(model, data, body, ann, 0.3)
    mujoco.mj_step(model, data, nstep=500)  # 1 s
    for name, (body, ann) in objs.items():
        assert get_openness(model, data, body, ann) == pytest.approx(0.3, abs=0.02), name
    for name, (body, ann) in objs.items():
        set_openness(model, data, body, ann, 0.5)
    mujoco.mj_step(model, data, nstep=1000)  # 2 s
    for name, (body, ann) in objs.items():
        assert get_openness(model, data, body, ann) == pytest.approx(0.5, abs=0.02), name
    # nothing touched the objects: neither the robot nor each other
    roots = {model.body(b).id for b, _ in objs.values()}
    for c in data.contact[:data.ncon]:
        r1, r2 = (int(model.body_rootid[model.geom_bodyid[g]]) for g in (c.geom1, c.geom2))
        assert not ({r1, r2} & roots and r1 != r2 and {r1, r2} - {0}), (model.geom(c.geom1).name,
                                                                          model.geom(c.geom2).name)


# -- annotations follow the geometry --------------------------------------------------------------------------
def _moved_by(model, joint):
    """The bodies that a joint moves: its body and that body's descendants."""
    jb, moved = model.jnt_bodyid[joint], set()
    for b in range(model.nbody):
        a = b
        while a != 0 and a != jb:
            a = model.body_parentid[a]
        if a == jb:
            moved.add(b)
    return moved


def _rotate(p, anchor, axis, angle):
    axis = axis / np.linalg.norm(axis)
    v = p - anchor
    return anchor + (v * np.cos(angle) + np.cross(axis, v) * np.sin(angle)
                     + axis * np.dot(axis, v) * (1 - np.cos(angle)))


@pytest.mark.parametrize("family,type_id", MODELS, ids=MODEL_IDS)
def test_part_points_move_with_the_joint(family, type_id):
    model, data, body, ann = _standalone(family, type_id)
    art = ann.articulation
    j = model.joint(f"{body}_{art.joint}").id
    moving = _moved_by(model, j)
    part_points = [p for p in ann.points if p.part is not None and model.body(f"{body}_{p.part}").id in moving]
    assert part_points, "the openness part carries annotation points"
    set_openness(model, data, body, ann, 0.0)
    p0 = {p.name: _part_world(model, data, body, p) for p in part_points}
    anchor, axis = data.xanchor[j].copy(), data.xaxis[j].copy()
    set_openness(model, data, body, ann, 1.0)
    delta = art.open - art.closed
    for p in part_points:
        p1 = _part_world(model, data, body, p)
        if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_SLIDE:
            expected = p0[p.name] + axis * delta
            assert np.linalg.norm(p1 - p0[p.name]) == pytest.approx(abs(delta), abs=1e-9)
        else:
            expected = _rotate(p0[p.name], anchor, axis, delta)
        np.testing.assert_allclose(p1, expected, atol=1e-9, err_msg=p.name)
    # part-bound axes turn with the part
    for ax in (a for a in ann.axes if a.part is not None):
        bid = model.body(f"{body}_{ax.part}").id
        set_openness(model, data, body, ann, 0.0)
        d0 = data.xmat[bid].reshape(3, 3) @ np.asarray(ax.direction)
        set_openness(model, data, body, ann, 1.0)
        d1 = data.xmat[bid].reshape(3, 3) @ np.asarray(ax.direction)
        if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_SLIDE or bid not in moving:
            np.testing.assert_allclose(d1, d0, atol=1e-9)
        else:
            np.testing.assert_allclose(d1, _rotate(d0, np.zeros(3), axis, delta), atol=1e-9)


def test_laptop_screen_edge_rises_when_opened_and_drawer_comes_toward_the_robot():
    model, data, body, ann = _standalone("laptop", 0)
    edge = ann.point("screen_edge")
    set_openness(model, data, body, ann, 0.0)
    z0 = _part_world(model, data, body, edge)[2]
    set_openness(model, data, body, ann, 1.0)
    assert _part_world(model, data, body, edge)[2] > z0 + 0.15
    model, data, body, ann = _standalone("drawer", 0)
    handle = ann.point("handle")
    set_openness(model, data, body, ann, 0.0)
    x0 = _part_world(model, data, body, handle)[0]
    set_openness(model, data, body, ann, 1.0)
    assert _part_world(model, data, body, handle)[0] == pytest.approx(x0 - ann.articulation.open)
    model, data, body, ann = _standalone("toaster", 0)
    top = ann.point("lever_top")
    set_openness(model, data, body, ann, 0.0)
    z0 = _part_world(model, data, body, top)[2]
    set_openness(model, data, body, ann, 1.0)
    assert _part_world(model, data, body, top)[2] == pytest.approx(z0 - ann.articulation.open)


@pytest.mark.parametrize("family,type_id", MODELS, ids=MODEL_IDS)
@pytest.mark.parametrize("openness", [0.0, 1.0])
def test_annotated_points_lie_on_the_object(family, type_id, openness):
    model, data, body, ann = _standalone(family, type_id)
    set_openness(model, data, body, ann, openness)
    geoms = _object_boxes(model, body)
    for p in ann.points:
        assert _dist_to_boxes(model, data, geoms, _part_world(model, data, body, p)) < 0.01, p.name
