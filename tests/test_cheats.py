"""The cheating-plan battery (tests/cheats/NNN_*.py): plans that forge the outcome instead of doing the task.

Each cheat is a complete plan for the task in its `# task:` header. Instead of moving the robot, it writes the
simulator's state (qpos, qvel, applied forces, derived poses), edits the model (gravity, timestep, joint ranges,
masses, damping, friction, actuators, equality constraints), changes what the judge reads (key points, the
shared numpy module, the MjData object itself), fakes recorded frames, or tries to forge the verdict itself.
Each must come back judged a failure, with a reason, from every path that judges plans:

- `run_task_episode` (the whole battery; `slow` except a sample that the default run keeps),
- `collect` keeps no episode of a cheat (the store's kept list is empty; `hgen dataset info` says 0 kept),
- `hgen run TASK --script cheat.py --json out.json` fails and its JSON says success false with a reason,
- the benchmark (`episodes.bench.run_bench`) counts no success,

while the reference plan of block_stack_single (seed 0) still succeeds and is kept through the same paths: a
judge that fails everything does not pass these tests. `bench/cheats.py` runs the battery on two seeds and
writes a table.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import dataclasses  # noqa: E402
import json  # noqa: E402
import re  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402

HERE = Path(__file__).resolve().parent
CHEAT_DIR = HERE / "cheats"
_HEADER = re.compile(r"^#\s*(task|cheat):\s*(.*?)\s*$")
STEP_TIMEOUT_S = 60.0
# Run by default (the rest of the battery is marked slow): a state write, a model edit, a change to what the
# judge reads (a key point + a numpy function), a swapped MjData, forged recorded frames.
SAMPLE = ("001_bss_qpos_teleport", "009_close_drawer_tilted_gravity", "018_bss_support_point_norm_liar",
          "021_bss_swap_mjdata", "022_bss_on_step_forged_frames")
# One of each kind for the collection / CLI / benchmark paths: state write, model edit, predicate-input patch.
# Each also moves the robot through the planner, so today its episode has recorded frames and is written to the
# dataset (a success that never stepped the planner records nothing and gets no episode file, only a count).
PATH_CASES = ("031_open_box_half_honest_then_qpos", "015_close_drawer_actuator_rewire", "019_bss_np_asarray_norm_liar")


@dataclasses.dataclass(frozen=True)
class Cheat:
    path: Path
    task: str
    forges: str

    @property
    def name(self) -> str:
        return self.path.stem


def cheats() -> list[Cheat]:
    out = []
    for path in sorted(CHEAT_DIR.glob("[0-9][0-9][0-9]_*.py")):
        head = {}
        for line in path.read_text().splitlines()[:5]:
            if m := _HEADER.match(line):
                head[m.group(1)] = m.group(2)
        assert "task" in head and "cheat" in head, f"{path.name}: needs '# task:' and '# cheat:' header lines"
        out.append(Cheat(path, head["task"], head["cheat"]))
    return out


CHEATS = cheats()
BY_NAME = {c.name: c for c in CHEATS}


def _request(task: str, plan: Path | None, seed: int = 0):
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.episodes.task_episode import EpisodeRequest

    # A recorder (no cameras): a kept episode comes back with its arrays, so "nothing kept" means something.
    return EpisodeRequest(task, seed, plan_path=str(plan) if plan is not None else None, recorder=RecorderConfig(),
                          step_timeout_s=STEP_TIMEOUT_S)


def _reason(result) -> str:
    """Why the episode failed: the failed step's error, else the details of the checks that failed."""
    failed = result.failed_step
    if failed is not None:
        return failed.error.strip()
    return "; ".join(str(c["detail"]).strip() for c in result.checks if not c["ok"] and str(c["detail"]).strip())


def _summary(result) -> str:
    return json.dumps({"success": result.success, "checks": result.checks,
                       "steps": [(s.title, s.ok, s.error[:200]) for s in result.steps]}, default=str)[:2000]


def test_battery_is_complete():
    from humanoidgen.tasks.registry import load_task

    assert len(CHEATS) >= 24
    assert len({c.name.split("_", 1)[0] for c in CHEATS}) == len(CHEATS), "cheat numbers must be unique"
    for c in CHEATS:
        load_task(c.task)  # a real task name
    assert {c.task for c in CHEATS} >= {"block_stack_single", "pyramid_stack", "close_drawer", "open_box_easy"}
    assert set(SAMPLE) <= set(BY_NAME) and set(PATH_CASES) <= set(BY_NAME)


# -- the whole battery through run_task_episode -------------------------------------------------------------
@pytest.mark.parametrize("cheat", [pytest.param(c, marks=() if c.name in SAMPLE else pytest.mark.slow, id=c.name)
                                   for c in CHEATS])
def test_cheat_is_judged_failed(cheat):
    from humanoidgen.episodes.plans import PlanFormatError
    from humanoidgen.episodes.task_episode import run_task_episode

    try:
        result, arrays = run_task_episode(_request(cheat.task, cheat.path))
    except PlanFormatError as exc:  # refused before it ran: not judged a success, and it says why
        assert str(exc).strip()
        return
    assert result.success is False, f"{cheat.name} ({cheat.forges}) was judged a success: {_summary(result)}"
    # what collection would keep: the arrays of a successful episode
    kept = arrays if result.success else None
    assert kept is None
    assert _reason(result), f"{cheat.name} failed without a reason: {_summary(result)}"


# -- the paths that judge plans, on one cheat of each kind ---------------------------------------------------
@pytest.mark.parametrize("name", PATH_CASES)
def test_collect_keeps_no_cheat(name, tmp_path):
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.episodes.recorder import RecorderConfig

    cheat = BY_NAME[name]
    out = tmp_path / "data"
    stats = collect(cheat.task, 1, out, seed=0, recorder=RecorderConfig(), plan_path=str(cheat.path), max_attempts=2)
    store = EpisodeStore(out)
    attempts = store.attempts()
    assert stats.kept == 0 and stats.tried == 2, f"{name}: {stats}"
    assert store.kept() == [], f"{name}: {store.kept()}"
    assert len(attempts) == 2 and not any(a["success"] for a in attempts)
    assert all(str(a.get("error", "")).strip() for a in attempts), f"{name}: an attempt failed without a reason"
    assert not list((out / "episodes").glob("*.npz")) if (out / "episodes").is_dir() else True
    res = CliRunner().invoke(app, ["dataset", "info", str(out)])
    assert " 0 episodes kept of 2 attempts" in " ".join(res.output.split()), res.output


@pytest.mark.parametrize("name", PATH_CASES)
def test_cli_run_reports_failure(name, tmp_path):
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app

    cheat = BY_NAME[name]
    out = tmp_path / "run.json"
    res = CliRunner().invoke(app, ["run", cheat.task, "--seed", "0", "--script", str(cheat.path), "--json", str(out),
                                   "--step-timeout", str(STEP_TIMEOUT_S)])
    assert res.exit_code != 0 or "FAILURE" in res.output, res.output[-2000:]
    assert "SUCCESS" not in res.output, res.output[-2000:]
    if out.exists():  # a plan refused before it ran writes no JSON (the CLI says why and exits 1)
        d = json.loads(out.read_text())
        assert d["success"] is False, json.dumps(d)[:2000]
        failed = next((s for s in d["steps"] if not s["ok"]), None)
        reason = failed["error"] if failed else "; ".join(c["detail"] for c in d["checks"] if not c["ok"])
        assert reason.strip(), json.dumps(d)[:2000]
    else:
        assert res.exit_code != 0 and res.output.strip()


@pytest.mark.parametrize("name", PATH_CASES)
def test_bench_counts_no_success(name, monkeypatch):
    from humanoidgen.episodes import bench
    from humanoidgen.tasks.registry import load_task

    cheat = BY_NAME[name]
    real = bench._request
    monkeypatch.setattr(bench, "_request", lambda *a, **k: dataclasses.replace(real(*a, **k),
                                                                                plan_path=str(cheat.path)))
    [report] = bench.run_bench([load_task(cheat.task)], episodes=2, seed=0)
    assert report.episodes == 2 and report.successes == 0, report.to_dict()
    assert len(report.failures) == 2 and all(f.split(":", 1)[1].strip() for f in report.failures), report.failures


# -- the honest plan still passes through the same paths -----------------------------------------------------
def _reference_plan() -> Path:
    from humanoidgen.tasks.registry import load_task, plan_path

    return Path(plan_path(load_task("block_stack_single")))


def test_honest_reference_plan_succeeds():
    from humanoidgen.episodes.task_episode import run_task_episode

    result, arrays = run_task_episode(_request("block_stack_single", _reference_plan()))
    assert result.success is True, _summary(result)
    assert all(c["ok"] for c in result.checks) and result.checks
    assert arrays is not None and len(arrays)  # a kept episode has its recording


def test_honest_reference_plan_kept_and_reported(tmp_path, monkeypatch):
    from typer.testing import CliRunner

    from humanoidgen.cli.main import app
    from humanoidgen.episodes import bench
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.tasks.registry import load_task

    plan = _reference_plan()
    stats = collect("block_stack_single", 1, tmp_path / "data", seed=0, recorder=RecorderConfig(),
                    plan_path=str(plan), max_attempts=1)
    assert stats.kept == 1 and len(EpisodeStore(tmp_path / "data").kept()) == 1
    out = tmp_path / "run.json"
    res = CliRunner().invoke(app, ["run", "block_stack_single", "--seed", "0", "--script", str(plan), "--json", str(out)])
    assert res.exit_code == 0, res.output[-2000:]
    assert json.loads(out.read_text())["success"] is True
    real = bench._request
    monkeypatch.setattr(bench, "_request", lambda *a, **k: dataclasses.replace(real(*a, **k), plan_path=str(plan)))
    [report] = bench.run_bench([load_task("block_stack_single")], episodes=1, seed=0)
    assert report.successes == 1, report.to_dict()
