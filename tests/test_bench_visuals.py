"""`hgen bench --randomize-visuals`: each episode runs with its own randomized look, drawn from its seed, and
the report's per-episode records carry it as collection's index records do (so an episode re-runs exactly)."""

from __future__ import annotations

import json
import os
from types import SimpleNamespace

os.environ.setdefault("MUJOCO_GL", "egl")

from typer.testing import CliRunner  # noqa: E402

from humanoidgen.cli.main import app  # noqa: E402
from humanoidgen.episodes.bench import run_bench  # noqa: E402
from humanoidgen.scenes.dressing import SceneDressing, episode_dressing  # noqa: E402


def test_bench_records_each_episode_and_its_dressing_only_when_asked():
    missing = SimpleNamespace(name="no_such_task", arms="single", horizon="short")  # fails fast, no simulation
    (plain,) = run_bench([missing], episodes=2, seed=7)
    assert [(r["seed"], r["success"]) for r in plain.records] == [(7, False), (8, False)]
    assert "no_such_task" in plain.records[0]["error"]
    assert all("dressing" not in r for r in plain.records)
    (dressed,) = run_bench([missing], episodes=2, seed=7, randomize_visuals=True, room=2)
    for r in dressed.records:
        assert r["dressing"] == episode_dressing(2, True, r["seed"])
        assert SceneDressing.from_dict(r["dressing"]).visuals.seed == r["seed"]
    assert dressed.records[0]["dressing"]["visuals"] != dressed.records[1]["dressing"]["visuals"]


def test_cli_bench_with_randomized_visuals_runs_and_reports_the_look(tmp_path):
    out = tmp_path / "bench.json"
    r = CliRunner().invoke(app, ["bench", "--tasks", "block_stack_single", "--episodes", "1", "--seed", "3",
                                 "--randomize-visuals", "--json", str(out)])
    assert r.exit_code == 0, r.output
    (report,) = json.loads(out.read_text())
    assert report["task"] == "block_stack_single" and report["episodes"] == 1
    assert report["successes"] == 1, report["failures"]  # the look changes pixels, not the physics
    (rec,) = report["records"]
    assert rec["seed"] == 3 and rec["success"] is True
    assert rec["dressing"] == json.loads(json.dumps(episode_dressing(None, True, 3)))  # as JSON has it
    assert rec["dressing"]["room"] is None and rec["dressing"]["visuals"]["seed"] == 3
