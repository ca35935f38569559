"""Random baseline on open_box_easy scenes (seeds 0-2, episodes 0-4): the 5-reference-plan range of
bench/results/baselines.json (as baselines.md measured it at 3bf137c) against the 50 demonstrations' zarr range."""
import json, sys, time  # usage: python bench/baseline_range_check.py DATA/open_box_easy.zarr
import numpy as np, torch
torch.set_num_threads(1)
from humanoidgen.policies.baselines import ActionRange
from humanoidgen.policies.baseline_eval import evaluate_baseline, zarr_range
from humanoidgen.envs.config import TaskEnvConfig
b = json.load(open("bench/results/baselines.json"))["plan_ranges"]["open_box_easy"]
ranges = {"plans5": ActionRange.of(np.array(b["low"]), np.array(b["high"]), "5 reference plans (baselines.json)"),
          "demos50": zarr_range(sys.argv[1])[0]}
out = {}
for name, r in ranges.items():
    t0 = time.time()
    rep = evaluate_baseline("random", "open_box_easy", 5, (0, 1, 2), env_config=TaskEnvConfig(), action_range=r, progress=False)
    out[name] = {"success_mean": rep.success_mean, "successes": [o.scene_seed for o in rep.outcomes if o.success],
                 "steps": [o.steps for o in rep.outcomes if o.success], "finals": [o.final for o in rep.outcomes if o.success],
                 "seconds": round(time.time() - t0)}
    print(name, json.dumps(out[name]), flush=True)
