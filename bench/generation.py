"""LLM-side overheads: checking and sandboxing per step, and one full generate-and-execute run with a
replayed model (the reference plan served by a local scripted endpoint, so no LLM time is counted).

Usage: python bench/generation.py [--steps 50]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402

from humanoidgen.episodes.plans import load_plan  # noqa: E402
from humanoidgen.generation import generate_script  # noqa: E402
from humanoidgen.generation.worker import setup as worker_setup  # noqa: E402
from humanoidgen.llm import LLMClient, LLMConfig  # noqa: E402
from humanoidgen.llm.fake_server import Response, ScriptedServer  # noqa: E402
from humanoidgen.sandbox import SandboxWorker  # noqa: E402
from humanoidgen.tasks.registry import SPECS_DIR  # noqa: E402


def _trivial_setup() -> dict:
    return {"x": 0}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--steps", type=int, default=50)
    args = ap.parse_args()
    with SandboxWorker(_trivial_setup) as w:
        w.run_step("x = x + 1")  # start the process
        times = []
        for _ in range(args.steps):
            t0 = time.perf_counter()
            out = w.run_step("x = x + 1\ny = [i * 2 for i in range(10)]")
            times.append(time.perf_counter() - t0)
            assert out.ok, out.message
    print(f"check + sandbox round trip per step: median {1000 * np.median(times):.2f} ms, "
          f"max {1000 * np.max(times):.2f} ms ({args.steps} steps)")

    steps = load_plan(SPECS_DIR / "block_stack_single.py").steps
    reply = "\n".join(f"```python\n# step: {s.title}\n{s.code}\n```" for s in steps)
    with ScriptedServer([Response(reply)]) as server, tempfile.TemporaryDirectory() as tmp:
        client = LLMClient(LLMConfig(base_url=server.base_url, model="scripted", cache_dir=Path(tmp)))
        with SandboxWorker(worker_setup) as worker:
            t1 = time.perf_counter()
            result = generate_script("block_stack_single", client, attempts=1, seed=0, worker=worker)
            t_run = time.perf_counter() - t1
    print(f"generate-and-execute block_stack_single with a replayed model: {'success' if result.success else 'FAILED'}, "
          f"{t_run:.1f} s (includes starting the sandbox worker and building the scene)")


if __name__ == "__main__":
    main()
