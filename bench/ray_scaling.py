"""Ray against local processes: episodes per minute of `collect` with 1 and 2 Ray workers (warm actors,
`episodes.ray_pool`) vs `--workers 1|2`,
and how a kept camera episode best reaches the dataset (object store vs the task writing into the shared
folder), in MB/s of raw arrays per episode.

    python bench/ray_scaling.py --episodes 6 --rounds 6                 # a local Ray with 2 CPUs
    python bench/ray_scaling.py --ray auto --workers 1,8,32 --episodes 64   # unchanged on a cluster

The configurations run interleaved (round 1: each of them, round 2: each again), after one warm-up run each
(plan-worker servers started, Ray actors up), so that the machine's other load falls on all of them alike;
each run records the machine's 1-minute load average when it started.
Writes bench/results/ray_scaling.json (+ .png) and, with --transport, bench/results/ray_transport.json."""

from __future__ import annotations

import argparse
import json
import os
import shutil
import tempfile
import time
from pathlib import Path

for _k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_k, "1")
os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402

from humanoidgen.episodes.collect import collect  # noqa: E402
from humanoidgen.episodes.ray_collect import ray_collect  # noqa: E402
from humanoidgen.episodes.recorder import RecorderConfig  # noqa: E402

RESULTS = Path(__file__).parent / "results"
TASK = "block_stack_single"
NO_CAMERAS = RecorderConfig(every=10, cameras=(), point_cloud=False)


def _run(kind: str, workers: int, episodes: int, seed: int, scratch: Path) -> dict:
    out = Path(tempfile.mkdtemp(dir=scratch))
    load = os.getloadavg()[0]  # other work on the machine: the comparison holds only within one run
    t0 = time.perf_counter()
    if kind == "local":
        stats = collect(TASK, episodes, out, workers=workers, seed=seed, recorder=NO_CAMERAS)
    else:  # the Ray of this process (ray.init below): `workers` caps the attempts in flight
        stats = ray_collect(TASK, episodes, out, "auto", workers=workers, seed=seed, recorder=NO_CAMERAS)
    wall = time.perf_counter() - t0
    shutil.rmtree(out)
    return {"kind": kind, "workers": workers, "kept": stats.kept, "tried": stats.tried, "wall_s": round(wall, 2),
            "episodes_per_min": round(60 * stats.kept / wall, 2), "load_1min": round(load, 2)}


def scaling(args, ray) -> dict:
    workers = [int(w) for w in args.workers.split(",")]
    configs = [(kind, w) for w in workers for kind in ("local", "ray")]
    scratch = Path(tempfile.mkdtemp(prefix="hgen-ray-scaling-"))
    runs = []
    try:
        for kind, w in configs:  # warm-up, not counted
            _run(kind, w, max(w, 1), 10_000, scratch)
        from humanoidgen.episodes.ray_pool import pool_for

        ray.get(pool_for(ray, max(workers)).ready_refs)  # every actor up: none is starting during a timed run
        for r in range(args.rounds):
            for kind, w in configs if r % 2 == 0 else configs[::-1]:  # neither kind always runs first
                row = {**_run(kind, w, args.episodes, args.seed + 1000 * r, scratch), "round": r}
                print(row, flush=True)
                runs.append(row)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    summary = []
    for w in workers:
        # episodes over wall time of all rounds, and the paired per-round ratio (the same load on both runs)
        rate = {}
        for k in ("local", "ray"):
            rows = [x for x in runs if x["kind"] == k and x["workers"] == w]
            rate[k] = 60 * sum(x["kept"] for x in rows) / sum(x["wall_s"] for x in rows)
        per_round = [a["episodes_per_min"] / b["episodes_per_min"] - 1 for r in range(args.rounds)
                     for a in runs if (a["kind"], a["workers"], a["round"]) == ("local", w, r)
                     for b in runs if (b["kind"], b["workers"], b["round"]) == ("ray", w, r)]
        summary.append({"workers": w, "local_episodes_per_min": round(rate["local"], 2),
                        "ray_episodes_per_min": round(rate["ray"], 2),
                        "ray_overhead_per_episode": round(rate["local"] / rate["ray"] - 1, 3),
                        "ray_overhead_median_of_rounds": round(float(np.median(per_round)), 3)})
    return {"task": TASK, "recorder": "no cameras, every 10", "episodes_per_run": args.episodes,
            "rounds": args.rounds, "cluster_cpus": ray.cluster_resources().get("CPU"), "machine_cpus": os.cpu_count(),
            "mean_load_1min": round(float(np.mean([x["load_1min"] for x in runs])), 2), "summary": summary,
            "runs": runs}


def transport(args, ray) -> dict:
    """One real camera episode (head + front 320x240, point cloud), then `--transport-episodes` hand-overs each
    way, interleaved: time from the arrays being ready in the task to the episode indexed on disk."""
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.episodes.ray_collect import Staging
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    rec = RecorderConfig(every=5, cameras=("head", "front"), width=320, height=240, point_cloud=True)
    result, arrays = run_task_episode(EpisodeRequest(TASK, 0, recorder=rec))
    assert result.success and arrays is not None
    scratch = Path(tempfile.mkdtemp(prefix="hgen-ray-transport-"))
    raw = scratch / "arrays.npz"
    np.savez(raw, **{k.replace("/", "__"): v for k, v in arrays.items()})  # uncompressed: cheap for tasks to read
    mb = sum(v.nbytes for v in arrays.values()) / 1e6

    @ray.remote(num_cpus=1)
    def hand_over(path: str, staging):
        from humanoidgen.episodes.dataset import write_episode_file

        with np.load(path) as z:
            data = {k.replace("__", "/"): z[k] for k in z.files}
        t_ready = time.time()
        if staging is None:
            return {"t_ready": t_ready, "arrays": data}
        out = staging.path_for(0)
        write_episode_file(out, data)
        return {"t_ready": t_ready, "staged": str(out), "length": len(data["action"])}

    store = EpisodeStore(scratch / "ds")
    store.create({"task": TASK})
    store.staging_dir.mkdir()
    staging = Staging(str(store.staging_dir), "bench")
    staging.marker.touch()
    rows = []
    try:
        for i in range(args.transport_episodes):
            for mode in ("object-store", "shared-folder"):
                cpu0 = time.process_time()
                res = ray.get(hand_over.remote(str(raw), None if mode == "object-store" else staging))
                if mode == "object-store":
                    store.add({"seed": i, "success": True}, res["arrays"])
                else:
                    store.adopt({"seed": i, "success": True}, Path(res["staged"]), res["length"])
                seconds = time.time() - res["t_ready"]
                rows.append({"mode": mode, "seconds": round(seconds, 3), "mb_per_s": round(mb / seconds, 1),
                             "driver_cpu_s": round(time.process_time() - cpu0, 3)})
                print(rows[-1], flush=True)
                del res
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    summary = {m: {"mb_per_s": round(float(np.mean([r["mb_per_s"] for r in rows if r["mode"] == m])), 1),
                   "seconds": round(float(np.mean([r["seconds"] for r in rows if r["mode"] == m])), 2),
                   "driver_cpu_s": round(float(np.mean([r["driver_cpu_s"] for r in rows if r["mode"] == m])), 2)}
               for m in ("object-store", "shared-folder")}
    return {"episode": f"{TASK} seed 0, head+front 320x240 every 5, point cloud; {len(arrays['action'])} frames",
            "raw_mb": round(mb, 1), "summary": summary, "runs": rows}


def plot(result: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = result["summary"]
    x = np.arange(len(rows))
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.bar(x - 0.2, [r["local_episodes_per_min"] for r in rows], 0.4, label="--workers K (processes)")
    ax.bar(x + 0.2, [r["ray_episodes_per_min"] for r in rows], 0.4, label="--ray, K workers")
    for i, r in enumerate(rows):
        ax.text(i + 0.2, r["ray_episodes_per_min"], f"{100 * r['ray_overhead_per_episode']:+.0f}%", ha="center",
                va="bottom", fontsize=8)
    ax.set_xticks(x, [f"K={r['workers']}" for r in rows])
    ax.set_ylabel("episodes / minute")
    top = max(max(r["local_episodes_per_min"], r["ray_episodes_per_min"]) for r in rows)
    ax.set_ylim(0, 1.35 * top)  # room for the legend above the bars
    load = f", load {result['mean_load_1min']:g} on {result['machine_cpus']} CPUs" if "mean_load_1min" in result else ""
    ax.set_title(f"{result['task']}: local processes vs Ray{load}", fontsize=9)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ray", default="local", help="local (a Ray with max(--workers) CPUs here), auto or ray://...")
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--episodes", type=int, default=4)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--transport", action="store_true", help="also measure object store vs shared folder")
    ap.add_argument("--transport-episodes", type=int, default=3)
    ap.add_argument("--out", type=Path, default=RESULTS / "ray_scaling.json")
    args = ap.parse_args()
    import ray

    from humanoidgen.episodes.ray_session import LOCAL_OBJECT_STORE_BYTES, LOCAL_SYSTEM_CONFIG, WORKER_ENV

    if args.ray == "local":
        ray.init(address="local", num_cpus=max(int(w) for w in args.workers.split(",")), include_dashboard=False,
                 object_store_memory=LOCAL_OBJECT_STORE_BYTES, runtime_env={"env_vars": WORKER_ENV},
                 log_to_driver=False, _system_config=LOCAL_SYSTEM_CONFIG)
    else:
        ray.init(address=args.ray, runtime_env={"env_vars": WORKER_ENV}, log_to_driver=False)
    try:
        if args.transport:
            out = args.out.with_name("ray_transport.json")
            out.write_text(json.dumps(transport(args, ray), indent=2))
            print(f"wrote {out}")
        result = scaling(args, ray)
    finally:
        ray.shutdown()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(result, indent=2))
    plot(result, args.out.with_suffix(".png"))
    print(json.dumps(result["summary"], indent=2))
    print(f"wrote {args.out} and {args.out.with_suffix('.png')}")


if __name__ == "__main__":
    main()
