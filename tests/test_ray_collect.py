"""Collection and benchmarks on Ray: a local Ray head on 127.0.0.1 with 2 worker CPUs is started for this module
(and stopped after). `--ray` keeps exactly the episodes of `--workers 1`, in a room and with a randomized look
too; the warm actors serve every collection without restarting their plan workers' fork server; a worker
killed during an attempt is retried and the dataset has no duplicate or gap; an interrupted Ray collection
resumes, and closing a runner stops the attempts it had in flight; a bad address is one line and exit 1."""

import json
import os
import socket
import subprocess
import sys
from functools import partial
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

ray = pytest.importorskip("ray")

from humanoidgen.cli.main import app  # noqa: E402
from humanoidgen.episodes.collect import collect  # noqa: E402
from humanoidgen.episodes.dataset import EpisodeStore  # noqa: E402
from humanoidgen.episodes.ray_collect import ray_collect  # noqa: E402
from humanoidgen.episodes.recorder import RecorderConfig  # noqa: E402

TASK = "block_stack_single"  # ~1.7 s an attempt here without cameras
REC = RecorderConfig(every=10, cameras=(), point_cloud=False)
N = 3


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _head_pids(temp_dir: Path) -> list[int]:
    pids = []
    for proc in Path("/proc").iterdir():
        try:
            if proc.name.isdigit() and str(temp_dir).encode() in (proc / "cmdline").read_bytes():
                pids.append(int(proc.name))
        except OSError:
            continue
    return pids


def _stop(temp_dir: Path) -> None:
    """End the processes of this head (those whose command line names its temp dir), not other Ray instances."""
    import shutil
    import signal
    import time

    for sig in (signal.SIGTERM, signal.SIGKILL):
        for pid in _head_pids(temp_dir):
            try:
                os.kill(pid, sig)
            except OSError:
                pass
        deadline = time.monotonic() + 5
        while _head_pids(temp_dir) and time.monotonic() < deadline:
            time.sleep(0.2)
    shutil.rmtree(temp_dir, ignore_errors=True)


@pytest.fixture(scope="module")
def head(tmp_path_factory):
    """A Ray head on 127.0.0.1 with 2 CPUs; this process stays connected to it, so its 2 workers (and their
    warm plan-worker servers) serve every test."""
    port = _free_port()
    temp_dir = Path(f"/tmp/hgen-ray-{port}")  # short: Ray's socket paths live under it
    mp = pytest.MonkeyPatch()
    mp.setenv("RAY_AUTH_MODE", "disabled")  # no token files shared between the head and the tests
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
           "RAY_USAGE_STATS_ENABLED": "0"}
    ray_cli = str(Path(sys.executable).with_name("ray"))
    try:
        subprocess.run([ray_cli, "start", "--head", "--node-ip-address=127.0.0.1", f"--port={port}",
                        "--num-cpus=2", "--num-gpus=0", "--include-dashboard=false", f"--temp-dir={temp_dir}",
                        f"--object-store-memory={300 << 20}", "--disable-usage-stats", '--system-config={"worker_niceness": 0}'], check=True, env=env,
                       capture_output=True)
        address = f"127.0.0.1:{port}"
        # The test module's functions travel by value: the workers cannot import tests/.
        ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
        ray.init(address=address, log_to_driver=False,
                 runtime_env={"env_vars": {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}})
        yield address
    finally:
        ray.shutdown()
        _stop(temp_dir)
        mp.undo()


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    root = tmp_path_factory.mktemp("local")
    stats = collect(TASK, N, root, workers=1, recorder=REC)
    assert stats.kept == N
    return root


def _same_episodes(a: Path, b: Path) -> None:
    sa, sb = EpisodeStore(a), EpisodeStore(b)
    ra, rb = sa.attempts(), sb.attempts()
    assert [(r["seed"], r["success"], r.get("episode")) for r in ra] == \
        [(r["seed"], r["success"], r.get("episode")) for r in rb]
    for rec in sa.kept():
        ea, eb = sa.load(rec["episode"]), sb.load(rec["episode"])
        assert set(ea) == set(eb)
        for key in ea:
            assert np.array_equal(ea[key], eb[key]), key


def _no_duplicate_or_gap(root: Path) -> None:
    seeds = [r["seed"] for r in EpisodeStore(root).attempts()]
    assert seeds == list(range(seeds[0], seeds[0] + len(seeds))), seeds
    episodes = [r["episode"] for r in EpisodeStore(root).kept()]
    assert episodes == list(range(len(episodes)))
    assert not (root / "incoming").exists() or not any((root / "incoming").iterdir())


def test_ray_keeps_the_episodes_of_one_worker(head, reference, tmp_path):
    out = tmp_path / "ray"
    seen = []
    stats = ray_collect(TASK, N, out, head, recorder=REC, progress=lambda k, t, rates: seen.append((k, t, rates.text())))
    assert stats.kept == N and sum(stats.nodes.values()) >= stats.tried
    (node,) = stats.nodes  # one node, named by its address in the progress bar and the index
    assert seen[-1][0] == N and seen[-1][2].startswith(f"{node} ") and seen[-1][2].endswith("/min")
    _same_episodes(reference, out)
    _no_duplicate_or_gap(out)
    assert all(r["node"] == node for r in EpisodeStore(out).attempts())


def test_episodes_written_by_the_task_to_the_shared_folder_are_the_same(head, reference, tmp_path):
    out = tmp_path / "folder"
    stats = ray_collect(TASK, N, out, head, recorder=REC, transport="shared-folder")
    assert stats.staged == N and stats.through_store == 0
    _same_episodes(reference, out)
    _no_duplicate_or_gap(out)


def _same_dressing(a: Path, b: Path) -> None:
    ra, rb = EpisodeStore(a).attempts(), EpisodeStore(b).attempts()
    assert [r["dressing"] for r in ra] == [r["dressing"] for r in rb]
    assert all(r["dressing"]["room"] is not None and r["dressing"]["visuals"] is not None for r in ra)


def test_ray_collect_in_a_room_with_a_random_look_keeps_the_local_episodes(head, tmp_path):
    """`hgen collect --ray local --room 3 --randomize-visuals`: the dressing reaches each attempt as it does
    locally (same seeds, same recorded room and look, same state arrays as `--workers 1`)."""
    n = 2
    local = tmp_path / "room_local"
    assert collect(TASK, n, local, workers=1, recorder=REC, room=3, randomize_visuals=True).kept == n
    out = tmp_path / "room_ray"
    r = CliRunner().invoke(app, ["collect", TASK, "-n", str(n), "--out", str(out), "--ray", "local", "--room", "3",
                                 "--randomize-visuals", "--cameras", "none", "--no-point-cloud", "--every", "10"])
    assert r.exit_code == 0, r.output
    _same_episodes(local, out)
    _same_dressing(local, out)
    _no_duplicate_or_gap(out)


def _traced_attempt(req):
    """The attempt, with the process it ran in and whether that process's fork server was already up."""
    import multiprocessing.forkserver as fs
    import os

    from humanoidgen.episodes.collect import attempt

    server = getattr(fs._forkserver, "_forkserver_pid", None)
    record, arrays = attempt(req)
    return {**record, "pid": os.getpid(), "warm": server is not None, "server": server}, arrays


def test_the_actors_stay_warm_from_one_collection_to_the_next(head, tmp_path):
    """The cause of Ray's overhead was a fresh worker process (imports, fork server, mesh cache: 5-11 s) for
    about every other collection; the pool's actors serve every collection of a connection instead."""
    first = ray_collect(TASK, 2, tmp_path / "a", head, recorder=REC, attempt_fn=_traced_attempt, max_attempts=2)
    second = ray_collect(TASK, 2, tmp_path / "b", head, recorder=REC, attempt_fn=_traced_attempt, max_attempts=2,
                         seed=5)
    assert first.tried == second.tried == 2
    a, b = EpisodeStore(tmp_path / "a").attempts(), EpisodeStore(tmp_path / "b").attempts()
    assert all(r["warm"] for r in a + b), "an attempt had to start its fork server"
    from humanoidgen.episodes.ray_pool import _pool

    assert _pool is not None
    pids = set(ray.get([actor.run.remote(-1, os.getpid, ()) for actor in _pool.actors]))
    assert {r["pid"] for r in a + b} <= pids
    servers = {(r["pid"], r["server"]) for r in a + b}
    assert len(servers) == len({pid for pid, _ in servers}), "a fork server was restarted between collections"


def _spin_in_a_plan_worker(i: int) -> float:
    """Item 0 returns at once; the others run a plan step that loops until its 60 s budget."""
    import time

    from humanoidgen.sandbox import SandboxWorker

    t0 = time.perf_counter()
    if i > 0:
        with SandboxWorker(dict) as worker:
            worker.run_step("x = 0\nwhile True:\n    x += 1", timeout_s=60)
    return time.perf_counter() - t0


def test_closing_a_runner_stops_the_attempts_it_has_in_flight(head):
    """Ctrl-C or the end of a dataset: queued calls are dropped and running ones lose their plan worker, so the
    actors are free at once (a sync actor's running call cannot be cancelled by Ray itself)."""
    import time

    from humanoidgen.episodes.ray_pool import PoolRunner, pool_for

    pool = pool_for(ray, 2)
    runner = PoolRunner(pool, 2, _spin_in_a_plan_worker, lambda i: (i,))
    for item, _ in runner.results(range(6)):
        assert item == 0
        time.sleep(3)  # items 1.. are spinning on both actors, others are queued
        break  # closes the runner
    t0 = time.perf_counter()
    quick = PoolRunner(pool, 2, _spin_in_a_plan_worker, lambda i: (0,))
    assert [item for item, _ in quick.results(range(2))] == [0, 1]
    assert time.perf_counter() - t0 < 20, "an actor was still running a spinning step"


def _dying_attempt(marker: str, victim: int, req):
    """The first try of seed `victim` kills its own Ray worker process 0.4 s into the attempt (its plan is
    running then); the retry runs normally."""
    import os
    import signal
    import threading

    from humanoidgen.episodes.collect import attempt

    if req.seed == victim and not os.path.exists(marker):
        open(marker, "w").close()
        threading.Timer(0.4, os.kill, (os.getpid(), signal.SIGKILL)).start()
    return attempt(req)


def test_a_worker_killed_mid_attempt_is_retried_without_duplicate_or_gap(head, reference, tmp_path):
    marker = tmp_path / "killed"
    out = tmp_path / "killed_ds"
    stats = ray_collect(TASK, N, out, head, recorder=REC, attempt_fn=partial(_dying_attempt, str(marker), 1))
    assert marker.exists(), "the hook did not fire"
    assert stats.kept == N
    _same_episodes(reference, out)
    _no_duplicate_or_gap(out)


def test_an_interrupted_ray_collection_resumes(head, reference, tmp_path):
    out = tmp_path / "resumed"

    def stop_after_first(kept, tried, rates):
        if kept == 1:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        ray_collect(TASK, N, out, head, recorder=REC, progress=stop_after_first)
    assert len(EpisodeStore(out).kept()) == 1
    with pytest.raises(Exception, match="--resume"):
        ray_collect(TASK, N, out, head, recorder=REC)
    stats = ray_collect(TASK, N, out, head, recorder=REC, resume=True)
    assert stats.kept == N
    _same_episodes(reference, out)
    _no_duplicate_or_gap(out)


def _session_processes(sid: int) -> list[str]:
    found = []
    for proc in Path("/proc").iterdir():
        try:
            if proc.name.isdigit() and os.getsid(int(proc.name)) == sid:
                found.append((proc / "cmdline").read_bytes().replace(b"\0", b" ")[:100].decode(errors="replace"))
        except OSError:
            continue
    return found


def test_ctrl_c_on_the_command_line_stops_everything(tmp_path):
    """SIGINT to `hgen collect --ray local`: one line, exit 1, the attempts written so far without a gap, and
    no process of the command left (driver, its Ray, the actors, their fork servers and plan workers)."""
    import signal
    import time

    out = tmp_path / "sigint"
    hgen = str(Path(sys.executable).with_name("hgen"))
    # its own session, to find every process it started; SIGINT as a terminal would deliver it
    proc = subprocess.Popen([hgen, "collect", TASK, "-n", "20", "--out", str(out), "--ray", "local", "--workers", "2",
                             "--cameras", "none", "--no-point-cloud", "--every", "10"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    index = out / "index.jsonl"
    deadline = time.monotonic() + 240
    while not (index.exists() and len(index.read_text().splitlines()) >= 1) and time.monotonic() < deadline:
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.2)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 1 and "interrupted" in err and "--resume" in err, err[-2000:]
    assert len(EpisodeStore(out).attempts()) < 20
    _no_duplicate_or_gap(out)
    deadline = time.monotonic() + 15
    while _session_processes(proc.pid) and time.monotonic() < deadline:
        time.sleep(0.5)
    assert _session_processes(proc.pid) == []


def test_cli_collect_and_bench_over_ray(head, reference, tmp_path):
    runner = CliRunner()
    out = tmp_path / "cli"
    r = runner.invoke(app, ["collect", TASK, "-n", "2", "--out", str(out), "--ray", head, "--cameras", "none",
                            "--no-point-cloud", "--every", "10"])
    assert r.exit_code == 0, r.output
    assert [k["seed"] for k in EpisodeStore(out).kept()] == [k["seed"] for k in EpisodeStore(reference).kept()][:2]
    report = tmp_path / "bench.json"
    r = runner.invoke(app, ["bench", "--tasks", TASK, "--episodes", "2", "--seed", "3", "--ray", head,
                            "--json", str(report)])
    assert r.exit_code == 0, r.output
    (row,) = json.loads(report.read_text())
    assert row["task"] == TASK and row["episodes"] == 2 and row["success_rate"] == 1.0


def test_a_bad_address_is_one_line_and_exit_1(tmp_path):
    hgen = str(Path(sys.executable).with_name("hgen"))
    for address in ("nonsense", f"127.0.0.1:{_free_port()}"):
        r = subprocess.run([hgen, "collect", TASK, "-n", "1", "--out", str(tmp_path / "x"), "--ray", address,
                            "--cameras", "none"], capture_output=True, text=True, timeout=120)
        assert r.returncode == 1
        lines = [ln for ln in r.stderr.splitlines() if ln.strip() and "collect " not in ln]
        assert len(lines) == 1 and ("--ray must be" in lines[0] or "cannot reach a Ray cluster" in lines[0]), r.stderr
        assert not (tmp_path / "x").exists()  # no empty dataset left behind


def test_policy_eval_over_ray_meets_the_same_episodes(head, tmp_path):
    """A tiny DP3 trained on two recorded demonstrations: each eval episode a Ray task, the same outcomes as
    local evaluation."""
    pytest.importorskip("torch")
    from humanoidgen.episodes.dataset import export_zarr
    from humanoidgen.policies.eval import evaluate
    from humanoidgen.policies.train import train

    rec = RecorderConfig(every=5, cameras=(), point_cloud=True, num_points=64)
    data = tmp_path / "demos"
    collect("close_drawer", 2, data, recorder=rec)
    export_zarr(EpisodeStore(data), tmp_path / "cd.zarr")
    tiny = {"unet": {"down_dims": [32, 64], "diffusion_step_embed_dim": 32}, "horizon": 8, "num_points": 64,
            "encoder_output_dim": 32, "point_mlp": [32, 64], "state_mlp": [32, 32],
            "train": {"batch_size": 32, "lr": 1e-3, "lr_warmup_steps": 0, "epochs": 1, "checkpoint_every": 1}}
    train("dp3", tmp_path / "cd.zarr", tmp_path / "run", tiny, device="cpu", progress=False)
    kw = dict(episodes=1, seeds=(0, 1), device="cpu", progress=False, max_steps=4)
    local = evaluate(tmp_path / "run", "close_drawer", **kw)
    remote = evaluate(tmp_path / "run", "close_drawer", ray_address=head, **kw)
    strip = lambda r: [(o.checkpoint, o.seed, o.scene_seed, o.success, o.steps) for o in r.outcomes]  # noqa: E731
    assert strip(remote) == strip(local) and len(local.outcomes) == 2
