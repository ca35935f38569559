"""Tasks on other models of their objects' families: `--model FAMILY=MODEL` and `--model FAMILY[K]=MODEL` pin
models, `--randomize-models` draws one per object and episode from the seed, and every record (`hgen collect`'s
index, `hgen bench`'s report, the gym env's reset info) names each object's model so that the episode runs again
exactly with `--model REF=NAME`. Two imported "bottles" of different heights (convex cylinders: no CoACD) make
the families' choice here."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
import trimesh
from typer.testing import CliRunner

from humanoidgen.cli.main import app
from humanoidgen.objects import library
from humanoidgen.objects.family_data import ENV_FAMILIES_PATH
from humanoidgen.objects.stand_ins import drawable_models
from humanoidgen.tasks.models import (ModelChoiceError, episode_models, model_options, parse_models,
                                      with_models)
from humanoidgen.tasks.registry import load_task

TASK = "dual_bottles_pick_easy"


@pytest.fixture(scope="module")
def bottles(tmp_path_factory) -> dict[str, int]:
    """Two imported bottle models, by name -> type_id, on $HGEN_FAMILIES_PATH for the module."""
    from humanoidgen.objects.imported.importer import ImportRequest, import_model

    work = tmp_path_factory.mktemp("bottles")
    old = os.environ.get(ENV_FAMILIES_PATH)
    os.environ[ENV_FAMILIES_PATH] = str(work / "models")
    out = {}
    for name, height in (("tall_tin", 0.20), ("short_tin", 0.17)):
        trimesh.creation.cylinder(radius=0.03, height=height, sections=40).export(work / f"{name}.obj")
        r = import_model(ImportRequest(work / f"{name}.obj", "bottle", name=name, out=work / "models",
                                       preview=False))
        out[name] = r.model.info.type_id
    yield out
    if old is None:
        os.environ.pop(ENV_FAMILIES_PATH, None)
    else:
        os.environ[ENV_FAMILIES_PATH] = old


def test_model_options_name_a_family_or_one_object():
    assert parse_models(["cup=my_mug", "bottle[1]=ketchup"]) == {"cup": "my_mug", "bottle[1]": "ketchup"}
    for bad in ("bottle", "=x", "bottle[x]=y", "Bottle=y"):
        with pytest.raises(ModelChoiceError, match="expected FAMILY=MODEL"):
            parse_models([bad])


def test_one_object_is_pinned_and_the_others_draw(bottles):
    spec = load_task(TASK)
    mixed = with_models(spec, {"bottle[1]": "short_tin"}, randomize=True)
    assert [o.type_id for o in mixed.objects] == [spec.objects[0].type_id, bottles["short_tin"]]
    assert mixed.randomize_models == ["bottle[0]"]
    drawable = {m.type_id for m in drawable_models("bottle")}
    assert set(bottles.values()) <= drawable
    for seed in range(6):
        first, second = mixed.sample_layout(seed)
        assert first.type_id in drawable and second.type_id == bottles["short_tin"]
    every = with_models(spec, {}, randomize=True)
    assert every.randomize_models == ["bottle"]
    with pytest.raises(ModelChoiceError, match="has no object bottle\\[2\\]"):
        with_models(spec, {"bottle[2]": "tall_tin"}, randomize=False)
    with pytest.raises(ModelChoiceError, match="bottle has no model 'nope'"):
        with_models(spec, {"bottle[0]": "nope"}, randomize=False)


def test_the_record_pins_the_drawn_models_and_the_episode_comes_back_exactly(bottles):
    spec = load_task(TASK)
    assert episode_models(spec, 3) is None  # a task on its own models has nothing to record
    drawn = with_models(spec, {}, randomize=True)
    seen = set()
    for seed in range(12):
        record = episode_models(drawn, seed)
        assert set(record) == {"bottle[0]", "bottle[1]"}
        for ref, m in record.items():
            info = next(i.info for i in library.family("bottle").imported() if i.info.type_id == m["type_id"])
            assert m["model"] == info.name and m["sha256"] == info.source.sha256
            seen.add(m["model"])
        again = with_models(spec, parse_models(model_options(record)), randomize=False)
        assert again.sample_layout(seed) == drawn.sample_layout(seed)  # poses and models, exactly
        # the draw comes from a stream of its own: the poses are those the task draws without it
        assert [o.pos for o in drawn.sample_layout(seed)] == [o.pos for o in spec.sample_layout(seed)]
    drawable = {m.params["name"] for m in drawable_models("bottle", like=spec.objects[0].type_id)}
    assert {"tall_tin", "short_tin"} <= drawable and len(seen) >= 2 and seen <= drawable


def _hgen(*args: str) -> subprocess.CompletedProcess:
    """An `hgen` command in a fresh process: its plan workers' server starts with this environment, the extra
    models' folder in it (a server started earlier in this test process would not know of them)."""
    return subprocess.run([sys.executable, "-m", "humanoidgen.cli.main", *args], env=dict(os.environ),
                          capture_output=True, text=True, timeout=900)


def test_bench_records_each_episodes_models(bottles, tmp_path):
    out = tmp_path / "bench.json"
    r = _hgen("bench", "--tasks", TASK, "--episodes", "1", "--seed", "2", "--model", "bottle[0]=tall_tin",
              "--randomize-models", "--json", str(out))
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    (report,) = json.loads(out.read_text())
    (rec,) = report["records"]
    assert rec["models"]["bottle[0]"]["model"] == "tall_tin"
    assert rec["models"] == episode_models(with_models(load_task(TASK), {"bottle[0]": "tall_tin"}, True), 2)
    assert report["successes"] == 1, report["failures"]  # a plain cylinder is a bottle the plan lifts
    r = CliRunner().invoke(app, ["bench", "--tasks", TASK, "--episodes", "1", "--model", "cup=x"])
    assert r.exit_code == 1 and "has no family cup" in r.output


def test_collect_writes_each_episodes_models_into_its_index(bottles, tmp_path):
    out = tmp_path / "data"
    r = _hgen("collect", TASK, "-n", "1", "--out", str(out), "--seed", "4", "--randomize-models", "--cameras",
              "none", "--no-point-cloud", "--every", "10")
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    task = load_task(str(tmp_path / ".data.task" / f"{TASK}.models.yaml"))  # the task as collected, beside it
    records = [json.loads(line) for line in (out / "index.jsonl").read_text().splitlines()]
    assert records and all(r["models"] == episode_models(task, r["seed"]) for r in records)
    assert all(set(r["models"]) == {"bottle[0]", "bottle[1]"} for r in records)


def test_the_gym_env_takes_models_and_says_which_it_drew(bottles):
    pytest.importorskip("gymnasium")
    from humanoidgen.envs import HumanoidTaskEnv

    env = HumanoidTaskEnv(TASK, models=["bottle[1]=tall_tin"], randomize_models=True, every=10, cameras=(),
                          point_cloud=False)
    try:
        _, info = env.reset(seed=5)
        assert info["models"]["bottle[1]"]["model"] == "tall_tin"
        assert info["models"] == episode_models(env.spec_task, 5)
        built = [env.sim.scene.object("bottle", k).type_id for k in (0, 1)]
        assert built == [info["models"][f"bottle[{k}]"]["type_id"] for k in (0, 1)]
    finally:
        env.close()
    with pytest.raises(ModelChoiceError):
        HumanoidTaskEnv(TASK, models={"cup": "x"})

