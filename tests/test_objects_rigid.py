import math
import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from humanoidgen.objects.rigid import RIGID_FAMILIES  # noqa: E402
from humanoidgen.objects.schema import ObjectAnnotations  # noqa: E402

CASES = [(name, m.type_id) for name, fam in RIGID_FAMILIES.items() for m in fam.models()]
CONTAINERS = ("cup", "bowl", "pot")
IDS = [f"{n}{k}" for n, k in CASES]


def _world(name: str, type_id: int, xy=(0.0, 0.0), with_cube: bool = False, kick: float = 0.0):
    """A plane at z = 0 and the object resting on it (plus, optionally, a 2 cm cube above its opening)."""
    fam = RIGID_FAMILIES[name]
    spec = mujoco.MjSpec()
    spec.option.timestep = 0.002
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    spec.option.impratio = 10.0
    spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[2, 2, 0.05],
                            friction=[0.8, 0.01, 0.001])
    ann = fam.annotations(type_id)
    z0 = -ann.bbox_min[2] + 0.0005
    body = spec.worldbody.add_body(name=f"{name}_0", pos=[xy[0], xy[1], z0])
    body.add_freejoint(name=f"{name}_0_free")
    fam.build(spec, body, type_id)
    if with_cube:
        geo = fam.geometry(type_id)
        cx, cy = xy[0] + geo.axis_xy[0], xy[1] + geo.axis_xy[1]
        cube = spec.worldbody.add_body(name="probe", pos=[cx, cy, z0 + geo.rim_z + 0.03])
        cube.add_freejoint()
        cube.add_geom(name="probe_geom", type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.01] * 3, mass=0.01,
                      friction=[1.0, 0.01, 0.001], condim=4)
    model = spec.compile()
    data = mujoco.MjData(model)
    if with_cube and kick:  # thrown sideways toward the wall (+x), so the walls must catch it
        data.qvel[model.body("probe").dofadr[0]] = kick
    mujoco.mj_forward(model, data)
    return model, data, ann


def _body_geoms(model, body_name):
    bid = model.body(body_name).id
    return [g for g in range(model.ngeom) if model.geom_bodyid[g] == bid]


def _mat(q):
    m = np.zeros(9)
    mujoco.mju_quat2Mat(m, np.asarray(q, float))
    return m.reshape(3, 3)


def _geom_corners(model, g):
    """Corners of the geom's exact AABB, in its body's frame (boxes: rotated corners; cylinders: z-aligned)."""
    size, pos, rot = model.geom_size[g], model.geom_pos[g], _mat(model.geom_quat[g])
    signs = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)], float)
    if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX:
        return (signs * size) @ rot.T + pos
    assert model.geom_type[g] == mujoco.mjtGeom.mjGEOM_CYLINDER
    assert np.allclose(rot, np.eye(3), atol=1e-9), "cylinders are z-aligned"
    return signs * np.array([size[0], size[0], size[1]]) + pos


def _signed_distance(model, g, p):
    """Signed distance from point p (body frame) to geom g (negative inside)."""
    q = _mat(model.geom_quat[g]).T @ (np.asarray(p) - model.geom_pos[g])
    size = model.geom_size[g]
    if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX:
        d = np.abs(q) - size
    else:
        d = np.array([math.hypot(q[0], q[1]) - size[0], abs(q[2]) - size[1]])
    return float(np.linalg.norm(np.maximum(d, 0.0)) + min(d.max(), 0.0))


def _surface_distance(model, geoms, p):
    return min(_signed_distance(model, g, p) for g in geoms)


def _tilt_deg(quat):
    return math.degrees(math.acos(np.clip(_mat(quat)[2, 2], -1.0, 1.0)))


# -- families and annotations -----------------------------------------------------------------------------------
def test_families_and_models():
    assert set(RIGID_FAMILIES) == {"cube", "bottle", "can", "plate", "cup", "bowl", "pot"}
    for name, fam in RIGID_FAMILIES.items():
        assert fam.name == name and fam.articulated is False
        models = fam.models()
        assert [m.type_id for m in models] == list(range(len(models)))
        assert 2 <= len(models) <= 5
        assert all(m.family == name and m.description for m in models)
    cubes = RIGID_FAMILIES["cube"].models()
    assert [m.params["size"] for m in cubes] == [(0.04,) * 3] * 3 + [(0.03,) * 3, (0.03, 0.03, 0.08)]
    with pytest.raises(ValueError):
        RIGID_FAMILIES["cube"].annotations(99)


@pytest.mark.parametrize("name,type_id", CASES, ids=IDS)
def test_annotations_match_geometry(name, type_id):
    model, data, ann = _world(name, type_id)
    assert isinstance(ann, ObjectAnnotations)
    ObjectAnnotations.model_validate(ann.model_dump())  # round-trips through the validator
    assert ann.family == name and ann.type_id == type_id
    body = f"{name}_0"
    geoms = _body_geoms(model, body)
    names = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) for g in geoms]
    assert all(n.startswith(body + "_") for n in names) and len(set(names)) == len(names)
    # total mass and friction
    assert 0.01 < model.body_mass[model.body(body).id] < 2.0
    assert np.all(model.geom_friction[geoms, 0] >= 0.4)
    # bbox = the compiled geoms' extent; origin at its centre
    pts = np.concatenate([_geom_corners(model, g) for g in geoms])
    assert np.allclose(pts.min(0), ann.bbox_min, atol=0.005)
    assert np.allclose(pts.max(0), ann.bbox_max, atol=0.005)
    assert np.allclose((pts.min(0) + pts.max(0)) / 2, 0.0, atol=0.005)
    # axes
    axes = {a.name: np.array(a.direction) for a in ann.axes}
    for k, v in (("x", (1, 0, 0)), ("y", (0, 1, 0)), ("z", (0, 0, 1))):
        assert np.allclose(axes[k], v)
    assert all(abs(np.linalg.norm(v) - 1) < 1e-6 for v in axes.values())
    # points: the centre is the frame origin; the others on (within 1 cm of) the surface, storage in the opening
    points = {p.name: np.array(p.position) for p in ann.points}
    assert np.allclose(points["center"], 0.0)
    storage = {f.point for f in ann.functions if f.function == "storage"}
    geo = RIGID_FAMILIES[name].geometry(type_id)
    for pname, p in points.items():
        if pname == "center":
            continue
        if pname in storage:
            r = math.hypot(p[0] - geo.axis_xy[0], p[1] - geo.axis_xy[1])
            assert r < geo.opening_radius and geo.inner_bottom_z <= p[2] < geo.rim_z, pname
            assert _surface_distance(model, geoms, p) > 0.0, f"{pname} inside material"
        else:
            d = _surface_distance(model, geoms, p)
            # A long block's second end pinch sits 1.5 cm in, on its axis (rigid.END_PINCH_DEPTH): half its width; a
            # bottle's grasp from above (`shoulder`) is on its axis below the cap, inside the shoulder by its radius.
            limit = {"pinch_bottom": 0.0155, "shoulder": 0.02}.get(pname, 0.01)
            if pname == "shoulder":
                assert np.allclose(p[:2], geo.axis_xy, atol=1e-6), f"{name}{type_id} shoulder off the axis"
            assert abs(d) <= limit, f"{name}{type_id} point {pname} is {d:.4f} m from the surface"
    # every family has its expected operations and functions
    ops = {o.operation for o in ann.operations}
    fns = {f.function for f in ann.functions}
    expected = {
        "cube": ({"pinch", "grasp"}, {"support"}), "bottle": ({"grasp"}, set()), "can": ({"grasp"}, set()),
        "plate": ({"pinch"}, {"support"}), "cup": ({"grasp", "pinch"}, {"pour", "storage"}),
        "bowl": ({"pinch"}, {"storage"}), "pot": ({"grasp"}, {"storage"}),
    }[name]
    assert expected[0] <= ops and expected[1] <= fns
    if name == "pot":  # a handle on each side, by the handle's style: a bar (a tab) or an upright grip (a post)
        style = RIGID_FAMILIES["pot"]._model(type_id).params["handle_style"]
        point = {"bar": "handle", "post": "grip"}[style]
        assert {o.point for o in ann.operations_of("grasp")} == {f"{point}_left", f"{point}_right"}
    if name == "cube":
        pinch = ann.operations_of("pinch")[0]
        assert ann.axis(pinch.approach_axis).direction == (0.0, 0.0, -1.0)
        assert ann.point(pinch.point).position[2] < ann.bbox_max[2]


# -- physics ---------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name,type_id", CASES, ids=IDS)
def test_rests_stably_on_plane(name, type_id):
    model, data, _ = _world(name, type_id)
    bid = model.body(f"{name}_0").id
    p0 = data.xpos[bid].copy()
    for _ in range(1000):  # 2 s
        mujoco.mj_step(model, data)
    drift = np.linalg.norm(data.xpos[bid] - p0)
    assert drift < 0.005, f"{name}{type_id} drifted {drift * 1000:.1f} mm"
    assert _tilt_deg(data.xquat[bid]) < 3.0
    assert np.linalg.norm(data.cvel[bid]) < 0.01


@pytest.mark.parametrize("kick", [0.0, 0.4], ids=["drop", "thrown"])
@pytest.mark.parametrize("name,type_id", [c for c in CASES if c[0] in CONTAINERS],
                         ids=[i for c, i in zip(CASES, IDS) if c[0] in CONTAINERS])
def test_cube_dropped_into_container_stays_inside(name, type_id, kick):
    model, data, _ = _world(name, type_id, with_cube=True, kick=kick)
    geo = RIGID_FAMILIES[name].geometry(type_id)
    obj, probe = model.body(f"{name}_0").id, model.body("probe").id
    for _ in range(750):  # 1.5 s
        mujoco.mj_step(model, data)
    rot = data.xmat[obj].reshape(3, 3)
    local = rot.T @ (data.xpos[probe] - data.xpos[obj])  # the cube's centre in the container's frame
    r = math.hypot(local[0] - geo.axis_xy[0], local[1] - geo.axis_xy[1])
    assert r < geo.opening_radius, f"cube left the opening (r = {r:.3f})"
    assert local[2] < geo.rim_z and local[2] > geo.inner_bottom_z
    # it rests on the bottom, not on the rim
    assert local[2] < geo.inner_bottom_z + 0.02


# -- the table scene ------------------------------------------------------------------------------------------------
def test_one_of_each_family_in_table_scene():
    from humanoidgen.sim.scene import SceneBuilder

    b = SceneBuilder()
    placed = []
    slots = [(-0.40, -0.55), (-0.40, -0.25), (-0.40, 0.05), (-0.40, 0.35),
             (-0.12, -0.45), (-0.12, -0.05), (-0.12, 0.35)]
    for (x, y), (name, fam) in zip(slots, RIGID_FAMILIES.items()):
        k = len(fam.models()) - 1
        ann = fam.annotations(k)
        obj, body = b.add_object_body(name, np.array([x, y, -ann.bbox_min[2] + 0.0005]), quat=(1, 0, 0, 0),
                                      type_id=k)
        fam.build(b.spec, body, k)
        placed.append(obj)
    scene = b.build()
    model = scene.model
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    ids = [model.body(o.body).id for o in placed]
    p0 = data.xpos[ids].copy()
    for o in placed:
        geoms = _body_geoms(model, o.body)
        assert geoms and all(scene.geom_labels[g] == o.label for g in geoms)
    for _ in range(250):  # 0.5 s
        mujoco.mj_step(model, data)
    drift = np.linalg.norm(data.xpos[ids] - p0, axis=1)
    assert np.all(drift < 0.005), dict(zip([o.body for o in placed], drift))
    assert all(_tilt_deg(data.xquat[i]) < 3.0 for i in ids)
