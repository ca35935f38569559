"""What the locked-down plan worker costs: per episode and per plan step, against running the same plan in
this process without a worker (how plans ran before the worker existed).

Episodes alternate between the two ways on the same seeds, so that the load of a busy 2-core machine
falls on both alike; the figure is the ratio of their medians. Writes bench/results/sandbox.json.

    python bench/sandbox.py --tasks block_stack_single,open_drawer,handover_and_storage --seeds 5
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

RESULTS = Path(__file__).resolve().parent / "results"


def in_process(task: str, seed: int) -> tuple[float, bool]:
    """The episode without a worker: build, check and exec each step here (the old way)."""
    import math

    import numpy

    from humanoidgen.episodes.episode_worker import FINISH, PLAN, EpisodeSetup
    from humanoidgen.episodes.task_episode import load_spec, plan_file, read_plan_text
    from humanoidgen.sandbox.checker import check_code, safe_builtins

    t0 = time.perf_counter()
    spec = load_spec(task)
    ns = EpisodeSetup(spec.model_dump(mode="json"), read_plan_text(plan_file(task, spec, None)), seed)()
    ns["__builtins__"] = safe_builtins({"numpy": numpy, "math": math})
    ok = True
    for step in ns[PLAN]():
        try:
            exec(check_code(step["code"], {k for k in ns if not k.startswith("__")}).compile(), ns)  # noqa: S102
        except Exception:  # noqa: BLE001 - a failed step ends the episode, as in the worker
            ok = False
            break
    end = ns[FINISH]()
    return time.perf_counter() - t0, ok and all(c["ok"] for c in end["checks"])


def in_worker(task: str, seed: int) -> tuple[float, bool]:
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    t0 = time.perf_counter()
    result, _ = run_task_episode(EpisodeRequest(task, seed))
    return time.perf_counter() - t0, result.success


def step_round_trip(n: int = 200) -> dict:
    """A trivial step in a warm worker vs exec here: the fixed cost of checking + the pipe."""
    import math

    import numpy

    from humanoidgen.sandbox import SandboxWorker, check_code
    from humanoidgen.sandbox.checker import safe_builtins

    code = "x = x + 1\ny = [i * 2 for i in range(10)]"
    ns = {"x": 0, "np": numpy, "math": math, "__builtins__": safe_builtins({"numpy": numpy, "math": math})}
    local = []
    for _ in range(n):
        t0 = time.perf_counter()
        exec(check_code(code, {"x", "np", "math"}).compile(), ns)  # noqa: S102
        local.append(time.perf_counter() - t0)
    with SandboxWorker(_counter_setup) as w:
        w.run_step("x = 0")
        remote = []
        for _ in range(n):
            t0 = time.perf_counter()
            assert w.run_step(code).ok
            remote.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        w.close()
        w.start()
        start = time.perf_counter() - t0
        lockdown = w.lockdown
    return {"in_process_ms": 1e3 * statistics.median(local), "worker_ms": 1e3 * statistics.median(remote),
            "worker_start_s": start, "lockdown": lockdown}


def _counter_setup() -> dict:
    import math

    import numpy

    return {"x": 0, "np": numpy, "math": math}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tasks", default="block_stack_single,open_drawer,handover_and_storage")
    ap.add_argument("--seeds", type=int, default=5, help="seeds 1000.. per task, each run both ways")
    ap.add_argument("--out", type=Path, default=RESULTS / "sandbox.json")
    args = ap.parse_args()
    in_worker("block_stack_single", 0)  # start the fork server (once per process, not per episode)
    in_process("block_stack_single", 0)  # and warm this process the same way
    rows = []
    for task in args.tasks.split(","):
        old, new, ok_old, ok_new = [], [], 0, 0
        for seed in range(1000, 1000 + args.seeds):
            t, ok = in_process(task, seed)
            old.append(t)
            ok_old += ok
            t, ok = in_worker(task, seed)
            new.append(t)
            ok_new += ok
        row = {"task": task, "episodes": args.seeds, "in_process_s": statistics.median(old),
               "worker_s": statistics.median(new), "successes_in_process": ok_old, "successes_worker": ok_new}
        row["overhead_pct"] = 100 * (row["worker_s"] / row["in_process_s"] - 1)
        rows.append(row)
        print(f"{task:40s} in process {row['in_process_s']:.2f} s  worker {row['worker_s']:.2f} s  "
              f"overhead {row['overhead_pct']:+.1f}%  (successes {ok_old}/{ok_new} of {args.seeds})")
    steps = step_round_trip()
    print(f"trivial step: in process {steps['in_process_ms']:.2f} ms, worker {steps['worker_ms']:.2f} ms; "
          f"worker start {steps['worker_start_s'] * 1e3:.0f} ms; lockdown {steps['lockdown']}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({"episodes": rows, "step": steps, "cpus": os.cpu_count()}, indent=2))
    print(f"-> {args.out}")


if __name__ == "__main__":
    main()
