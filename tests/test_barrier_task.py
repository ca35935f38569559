"""Barriers (objects/barrier.py, objects/families/barrier/) and blocks_stack_hard_with_barrier: the family is data
and loads validated, a barrier stands fixed to the table and shows as an obstacle, the task's barriers cover more
than 60% of the workspace while the cubes and the stacking spot stay free, and the reference plan stacks."""

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import json  # noqa: E402
import math  # noqa: E402

import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from humanoidgen.objects.library import add_object
from humanoidgen.objects import library  # noqa: E402
from humanoidgen.objects.barrier import BarrierFamily, covered_share  # noqa: E402
from humanoidgen.objects.describe import describe_scene  # noqa: E402
from humanoidgen.objects.family_data import ENV_FAMILIES_PATH, FAMILIES_DIR, FamilyDataError  # noqa: E402
from humanoidgen.sim.layout import OPERABLE_RANGE, Range2D  # noqa: E402
from humanoidgen.tasks.registry import load_task  # noqa: E402
from humanoidgen.tasks.scene import build_scene, footprint  # noqa: E402

TASK = "blocks_stack_hard_with_barrier"
# The workspace as the task's YAML defines it: the union of the two hands' operable ranges.
WORKSPACE = Range2D(x=OPERABLE_RANGE["left"].x, y=(OPERABLE_RANGE["right"].y[0], OPERABLE_RANGE["left"].y[1]))
LOW_WALL = """\
type_id: 7
description: low red wall 4 x 20 cm, 5 cm tall
size: [0.04, 0.20, 0.05]
rgba: [0.8, 0.2, 0.2, 1.0]
"""


def _barriers(scene) -> list[str]:
    return [o.body for o in scene.objects if o.type_name == "barrier"]


# -- the family ---------------------------------------------------------------------------------------------------
def test_the_barrier_family_loads_from_its_files():
    fam = library.family("barrier")
    assert isinstance(fam, BarrierFamily) and fam.static and not fam.articulated
    files = sorted(p for p in (FAMILIES_DIR / "barrier").glob("*.yaml") if p.name != "family.yaml")
    models = fam.models()
    assert len(models) == len(files) >= 3 and [m.type_id for m in models] == list(range(len(files)))
    for m in models:
        ann = library.annotations("barrier", m.type_id)
        size = np.subtract(ann.bbox_max, ann.bbox_min)
        assert size == pytest.approx(m.params["size"])
        # Nothing grips a barrier; it says what it is and where its top is.
        assert ann.operations == [] and [(f.function, f.point) for f in ann.functions] == [("obstacle", "top")]
        assert ann.point("top").position == pytest.approx((0.0, 0.0, size[2] / 2))


def test_prompts_and_listings_call_barriers_static():
    from humanoidgen.generation.context import assets_text

    assert "- barrier (static, fixed to the table: an obstacle to keep clear of):" in assets_text().splitlines()
    assert "- cube (rigid, free):" in assets_text().splitlines()


def test_a_barrier_model_is_a_file(tmp_path, monkeypatch):
    (tmp_path / "barrier").mkdir()
    (tmp_path / "barrier" / "low_wall.yaml").write_text(LOW_WALL)
    monkeypatch.setenv(ENV_FAMILIES_PATH, str(tmp_path))
    ann = library.annotations("barrier", 7)
    assert ann.description == "low red wall 4 x 20 cm, 5 cm tall"
    assert np.subtract(ann.bbox_max, ann.bbox_min) == pytest.approx((0.04, 0.20, 0.05))


@pytest.mark.parametrize("text, field", [
    (LOW_WALL.replace("size: [0.04, 0.20, 0.05]", "size: [0.04, 0.20]"), "size.2: Field required"),
    (LOW_WALL.replace("size: [0.04, 0.20, 0.05]", "size: [0.04, -0.2, 0.05]"), "size.1: Input should be greater"),
    (LOW_WALL + "height: 0.05\n", "height: Extra inputs are not permitted"),
])
def test_a_bad_barrier_file_is_refused_naming_file_and_field(tmp_path, monkeypatch, text, field):
    (tmp_path / "barrier").mkdir()
    path = tmp_path / "barrier" / "bad.yaml"
    path.write_text(text)
    monkeypatch.setenv(ENV_FAMILIES_PATH, str(tmp_path))
    with pytest.raises(FamilyDataError) as exc:
        library.family("barrier").models()
    assert str(exc.value).startswith(f"{path}: ") and field in str(exc.value), str(exc.value)


# -- the task's scene ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def task():
    return load_task(TASK)


@pytest.fixture(scope="module")
def default_scene(task):
    return build_scene(task, None)


def test_spec_matches_the_paper_and_blocks_stack_hard(task):
    """6 x 8 cm and +-10 deg (paper appendix), on the cubes only; the same success as blocks_stack_hard."""
    r = task.randomization
    assert r.position == pytest.approx((-0.03, 0.03, -0.04, 0.04)) and r.yaw_deg == pytest.approx((-10, 10))
    assert [task.objects[i].type for i in r.per_object] == ["cube"] * 3
    assert task.success == load_task("blocks_stack_hard").success
    assert task.arms == "bimanual" and task.horizon == "long"


def test_barriers_are_fixed_to_the_table_and_shown_as_obstacles(default_scene):
    scene, env = default_scene
    m, d = env.model, env.data
    for body in _barriers(scene):
        assert m.body_jntnum[m.body(body).id] == 0 and m.body_parentid[m.body(body).id] == 0  # no joint, on the world
    # A cube is still free: the family decides, not the scene.
    assert m.body_jntnum[m.body("cube_0").id] == 1
    desc = describe_scene(env, as_json=False)
    barriers = [a for a in desc["attributes"] if a["type"] == "barrier"]
    assert len(barriers) == len(_barriers(scene)) and all(a["functions"] == ["obstacle@top"] for a in barriers)
    # Pushed hard for 0.2 s, a barrier does not move (a free body of 1 kg would be thrown across the table).
    body = m.body(_barriers(scene)[0]).id
    before = d.xpos[body].copy()
    d.xfrc_applied[body] = (200.0, 200.0, 0.0, 0.0, 0.0, 50.0)
    for _ in range(10):
        env.step(env.init_action())
    d.xfrc_applied[body] = 0.0
    assert np.linalg.norm(d.xpos[body] - before) < 1e-9


def test_covered_share_counts_a_turned_box_once():
    """A 10 x 20 cm box turned 30 deg, inside a 40 x 40 cm region, and a second box overlapping half of it."""
    spec = mujoco.MjSpec()
    for name, pos in (("a", (0.0, 0.0)), ("b", (0.05, 0.0))):
        body = spec.worldbody.add_body(name=name, pos=[*pos, 0.05],
                                       quat=[math.cos(math.pi / 12), 0, 0, math.sin(math.pi / 12)])
        body.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.05, 0.10, 0.05])
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    region = Range2D(x=(-0.2, 0.2), y=(-0.2, 0.2))
    assert covered_share(model, data, ["a"], region) == pytest.approx(0.02 / 0.16, rel=0.02)
    both = covered_share(model, data, ["a", "b"], region)
    assert both == pytest.approx((0.02 + 0.5 * 0.02) / 0.16, rel=0.03)
    # Clipped to the region: the part of the box outside it does not count.
    half = Range2D(x=(0.0, 0.2), y=(-0.2, 0.2))
    assert covered_share(model, data, ["a"], half) == pytest.approx(0.01 / 0.08, rel=0.03)


def test_barriers_cover_more_than_60_percent_of_the_workspace(task, default_scene):
    scene, env = default_scene
    share = covered_share(env.model, env.data, _barriers(scene), WORKSPACE)
    assert share > 0.6, share
    # The barriers stay where the task puts them: the share is every seed's.
    seeded, env2 = build_scene(task, 1003)
    assert covered_share(env2.model, env2.data, _barriers(seeded), WORKSPACE) == pytest.approx(share)


def test_cubes_and_stacking_spot_stay_clear_of_barriers(task):
    """For 40 seeds: every cube's footprint is off the walls (a cube on the platform rests on it, its centre over
    it) and the stacking spot, a cube's footprint around the target with 2 cm to spare, is free table."""
    layout = task.default_layout()
    kinds = [o.type for o in layout]
    walls = [footprint(o) for o, spec in zip(layout, task.objects) if spec.type == "barrier"]
    target = task.targets[0]
    for seed in range(40):
        lay = task.sample_layout(seed)
        for o in lay[: kinds.index("barrier")]:
            assert WORKSPACE.contains(np.asarray(o.pos[:2]))
        spot = np.asarray(target.pos[:2]) + np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]) * (0.02 + 0.02 + 0.01)
        for w in walls:
            lo, hi = w.min(0), w.max(0)
            assert (spot[:, 0].max() < lo[0] or spot[:, 0].min() > hi[0] or spot[:, 1].max() < lo[1]
                    or spot[:, 1].min() > hi[1]), (seed, w)
    # The cubes raised onto the platform sit on it after settling, the one on the table on the table.
    for seed in (0, 7):
        scene, env = build_scene(task, seed)
        z = {o.body: env.object_pose(o.body)[0][2] for o in scene.objects if o.type_name == "cube"}
        assert z["cube_0"] == pytest.approx(0.02, abs=0.002)
        assert z["cube_1"] == pytest.approx(0.05, abs=0.002) and z["cube_2"] == pytest.approx(0.05, abs=0.002)


def test_the_reference_plan_stacks_among_the_barriers(tmp_path):
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    result, _ = run_task_episode(EpisodeRequest(TASK, seed=3))
    assert result.success, json.dumps(result.to_dict())[:2000]
    assert all(c["ok"] for c in result.checks)


def test_the_scene_fixes_static_families_only():
    """`static` is family data (family.yaml): no packaged rigid family but the barrier says yes; the scene follows."""
    from humanoidgen.objects.rigid import RIGID_FAMILIES
    from humanoidgen.sim.scene import SceneBuilder

    assert all(f.static is False for f in RIGID_FAMILIES.values())
    b = SceneBuilder()
    add_object(b, "cube", 0, pos=(-0.3, 0.0))
    add_object(b, "barrier", 2, pos=(-0.3, 0.2))
    model = b.build().model
    assert model.body_jntnum[model.body("cube_0").id] == 1 and model.body_jntnum[model.body("barrier_0").id] == 0
