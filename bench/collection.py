"""Data-collection cost per kept episode, through `collect` itself (plan workers, rendering, writing the
dataset): without cameras, and with the default recording (six 320x240 RGB-D cameras and the 1024-point
cloud) at 10 Hz and at the full 50 Hz control rate; the ratio to the camera-less time and MB per episode.

Usage: python bench/collection.py [--tasks block_stack_single,handover_and_storage] [--episodes 1]
                                  [--rates 10,50] [--json bench/results/collection.json]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from humanoidgen.episodes.collect import collect  # noqa: E402
from humanoidgen.episodes.recorder import RecorderConfig  # noqa: E402
from humanoidgen.sim.cameras import CAMERA_NAMES  # noqa: E402

CONTROL_HZ = 50


def run(task: str, n: int, recorder: RecorderConfig | None, max_attempts: int) -> dict:
    from humanoidgen.episodes.dataset import EpisodeStore

    load_before = os.getloadavg()[0]
    with tempfile.TemporaryDirectory(prefix="hgen-bench-") as tmp:
        out = Path(tmp) / "ds"
        stats = collect(task, n, out, recorder=recorder or RecorderConfig(every=CONTROL_HZ // 10),
                        max_attempts=max_attempts)
        size = sum(p.stat().st_size for p in (out / "episodes").glob("*.npz"))
        errors = [a.get("error", "") for a in EpisodeStore(out).attempts() if not a["success"]]
    kept = stats.kept
    row = {"kept": kept, "tried": stats.tried, "seconds_per_kept": round(stats.wall_seconds / kept, 2) if kept else None,
           "mb_per_episode": round(size / kept / 1e6, 2) if kept else None,
           # other work on the machine skews times: the 1-minute load average before and after the row
           "load_average": [round(load_before, 2), round(os.getloadavg()[0], 2)]}
    if errors:
        row["failures"] = [e[:200] for e in errors]
    return row


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--tasks", default="block_stack_single,handover_and_storage")
    ap.add_argument("--episodes", type=int, default=1, help="kept episodes per recording configuration")
    ap.add_argument("--baseline-episodes", type=int, default=3, help="kept episodes without cameras")
    ap.add_argument("--rates", default="10,50", help="recording rates in Hz (divisors of 50)")
    ap.add_argument("--max-attempts", type=int, default=3, help="attempts per configuration at most")
    ap.add_argument("--json", type=Path, default=None, help="written after every row")
    args = ap.parse_args()
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    # The plan workers' fork server starts and imports everything on the first attempt: not timed.
    run_task_episode(EpisodeRequest("block_stack_single", seed=0))
    results = {"machine": f"{platform.machine()}, {os.cpu_count()} CPUs", "episodes": args.episodes,
               "baseline_episodes": args.baseline_episodes, "tasks": {}}
    for task in [t.strip() for t in args.tasks.split(",") if t.strip()]:
        t0 = time.perf_counter()
        base = run(task, args.baseline_episodes, None, args.max_attempts + args.baseline_episodes)
        rows = results["tasks"][task] = {"no cameras": base}
        print(f"{task}: no cameras: {base['seconds_per_kept']:.1f} s per kept episode "
              f"({base['kept']}/{base['tried']} kept), {base['mb_per_episode']:.2f} MB", flush=True)
        for hz in [int(r) for r in args.rates.split(",")]:
            rec = RecorderConfig(every=CONTROL_HZ // hz, cameras=CAMERA_NAMES, point_cloud=True)
            row = run(task, args.episodes, rec, args.max_attempts)
            rows[f"6 cameras 320x240 + point cloud, {hz} Hz"] = row
            save(args.json, results)
            if not row["kept"] or not base["kept"]:
                print(f"{task}: {hz} Hz: no episode kept in {row['tried']} attempts: {row.get('failures')}")
                continue
            row["ratio"] = round(row["seconds_per_kept"] / base["seconds_per_kept"], 2)
            print(f"{task}: 6 cameras 320x240 + point cloud, {hz} Hz: {row['seconds_per_kept']:.1f} s per kept "
                  f"episode ({row['kept']}/{row['tried']} kept), {row['ratio']:.1f}x the camera-less time, "
                  f"{row['mb_per_episode']:.1f} MB per episode", flush=True)
        rows["load_average_1min_after"] = round(os.getloadavg()[0], 2)  # other work on the machine skews times
        save(args.json, results)
        print(f"({task}: {time.perf_counter() - t0:.0f} s)", flush=True)
    if args.json is not None:
        print(f"wrote {args.json}")


def save(path: Path | None, results: dict) -> None:
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    main()
