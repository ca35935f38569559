"""Reference plans on the library's models: `hgen run TASK --seed S --randomize-models` for held-out seeds, each
episode on the models its seed draws (needs `hgen assets fetch --objects`). Writes one JSON row per episode:
the task, the seed, the models drawn, success and the failing step.

Usage: python bench/model_randomization.py --tasks empty_cup_place,open_drawer --seeds 1000-1009
       [--out bench/results/model_randomization.json] [--baseline]   (--baseline: the task's own models)
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tasks", required=True)
    ap.add_argument("--seeds", default="1000-1009")
    ap.add_argument("--baseline", action="store_true")
    ap.add_argument("--out", type=Path, default=Path("bench/results/model_randomization.json"))
    args = ap.parse_args()
    a, b = (int(x) for x in args.seeds.split("-"))
    from humanoidgen.tasks.models import with_models
    from humanoidgen.tasks.registry import load_task

    rows = json.loads(args.out.read_text()) if args.out.is_file() else []
    for task in args.tasks.split(","):
        drawn = with_models(load_task(task), {}, randomize=True)
        for seed in range(a, b + 1):
            models = {f"{o.type}[{i}]": o.type_id for i, o in enumerate(drawn.sample_layout(seed))}
            with tempfile.TemporaryDirectory() as tmp:
                out = Path(tmp) / "r.json"
                cmd = [sys.executable, "-m", "humanoidgen.cli.main", "run", task, "--seed", str(seed), "--json",
                       str(out)] + ([] if args.baseline else ["--randomize-models"])
                r = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
                res = json.loads(out.read_text()) if out.is_file() else {}
            failed = next((s.get("error") for s in res.get("steps", []) if not s.get("ok")), None)
            row = {"task": task, "seed": seed, "randomize_models": not args.baseline,
                   "models": None if args.baseline else models, "success": bool(res.get("success")),
                   "failed_step": failed if res else (r.stderr or r.stdout)[-300:]}
            rows.append(row)
            print(json.dumps(row), flush=True)
            args.out.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
