"""Still layers (`sim.still_layer`) against drawing every geom in every frame, on recorded episodes.

For each task, one episode is recorded the way `collect` records it (physics only, six 320x240 cameras and
the point cloud at 10 Hz, seed 0); its images are then rendered from the recorded configurations by
`render_replay.render_recording` (two renderer threads, as `collect` does), with and without still layers,
taking turns for several rounds (this 2-core machine's speed moves with other jobs; each round sees both
under about the same load). Reported: CPU and wall seconds of each render, the share of geoms and cameras
found still, and whether every array (RGB, depth in millimetres, point cloud) is identical.

Usage: python bench/still_layers.py [--tasks handover_and_storage,block_stack_single] [--rounds 3]
                                    [--json bench/results/still_layers.json]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

from render_levers import episode_job  # noqa: E402  (bench/ is the script's folder: the same recorded episode)

from humanoidgen.episodes.render_replay import render_recording  # noqa: E402
from humanoidgen.sim.still_layer import still_parts  # noqa: E402

RESULTS = Path(__file__).parent / "results"


def render(job, model, layered: bool) -> tuple[dict, float, float]:
    r = job.recorder
    cpu, wall = time.process_time(), time.perf_counter()
    out = render_recording(model, job.configurations, r.cameras, r.width, r.height, r.depth,
                           r.point_cloud_cameras if r.point_cloud else (), r.num_points, still_layers=layered,
                           cloud_floor=r.point_cloud_floor)
    return out, time.process_time() - cpu, time.perf_counter() - wall


def measure(task: str, rounds: int) -> dict:
    job = episode_job(task)
    model = job.model()
    still = still_parts(model, job.configurations)
    drawn = np.isin(model.geom_group, (0, 1, 2))
    rows = {"plain": [], "still layers": []}
    identical = True
    for _ in range(rounds):
        plain, cpu0, wall0 = render(job, model, False)
        layered, cpu1, wall1 = render(job, model, True)
        rows["plain"].append((cpu0, wall0))
        rows["still layers"].append((cpu1, wall1))
        identical &= set(plain) == set(layered) and all(np.array_equal(plain[k], layered[k]) for k in plain)
        print(f"{task}: plain {cpu0:.2f} s CPU / {wall0:.2f} s wall, still layers {cpu1:.2f} / {wall1:.2f}")
    med = {k: (statistics.median(c for c, _ in v), statistics.median(w for _, w in v)) for k, v in rows.items()}
    return {
        "frames": job.frames,
        "still_geoms": int(still.geoms.sum()), "drawn_geoms": int(drawn.sum()),
        "still_cameras": sorted(still.cameras),
        "cpu_s": {k: [round(c, 2) for c, _ in v] for k, v in rows.items()},
        "wall_s": {k: [round(w, 2) for _, w in v] for k, v in rows.items()},
        "median_cpu_saved_pct": round(100 * (1 - med["still layers"][0] / med["plain"][0]), 1),
        "median_wall_saved_pct": round(100 * (1 - med["still layers"][1] / med["plain"][1]), 1),
        "arrays_identical": bool(identical),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tasks", default="handover_and_storage,block_stack_single")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--json", type=Path, default=RESULTS / "still_layers.json")
    args = ap.parse_args()
    out = {"machine": f"{platform.machine()}, {os.cpu_count()} CPUs",
           "recording": "six 320x240 RGB-D cameras + 1024-point cloud, 10 Hz, recording detail, seed 0",
           "load_average_before": round(os.getloadavg()[0], 2), "tasks": {}}
    for task in args.tasks.split(","):
        out["tasks"][task] = measure(task, args.rounds)
        t = out["tasks"][task]
        print(f"{task}: {t['frames']} frames, {t['still_geoms']}/{t['drawn_geoms']} drawn geoms and "
              f"{len(t['still_cameras'])} cameras still; median CPU {t['median_cpu_saved_pct']}% less, wall "
              f"{t['median_wall_saved_pct']}% less; arrays identical: {t['arrays_identical']}")
    out["load_average_after"] = round(os.getloadavg()[0], 2)
    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
