"""Named training recipes: settings merged under a run's own (`--epochs`, `--config` ...), per policy.

- `paper`: the paper's (the configs' defaults: a 512/1024/2048 U-Net, batch 256, 3,000 epochs), for a GPU.
- `fast`: the CPU recipe measured in docs/results/policies.md (U-Net 64/128/256, 2 observation steps, horizon 8,
  4 executed actions, batch 64, AdamW peak 1e-3 after 200 warm-up steps; DP3 256 points, DP 60x80 images with
  one observation step; 40 epochs).
- `reduced`: the first CPU recipe (7 executed actions, lr 3e-4; DP3 512 points, DP 84x112 images).

With no recipe named, `default_recipe` picks by device: `paper` where CUDA is, `fast` on a CPU, where the
paper's recipe would take days (a step at batch 64 took about 7 s on a 2-core machine) without a word."""

from __future__ import annotations

REDUCED = {"unet": {"down_dims": [64, 128, 256]}, "n_obs_steps": 2, "n_action_steps": 7, "horizon": 8,
           "train": {"batch_size": 64, "lr": 3e-4, "lr_warmup_steps": 200}}
REDUCED_BY_POLICY = {"dp3": {**REDUCED, "num_points": 512},
                     "dp": {**REDUCED, "image_size": [84, 112], "crop_size": [76, 100]}}
# The faster CPU recipe (issue 13's 45-minute runs): the point encoder's cost grows with the points and dominates
# a step, so half the points (256, still the first of the recorded farthest-point order) and a higher peak rate
# (1e-3, cosine decay after 200 warm-up steps) buy about twice the optimizer steps per CPU-minute; 4 executed
# actions of the 8 predicted (a new prediction every 0.4 s instead of 0.7 s: the same 30-epoch DP3 closed
# close_drawer in 9 of 10 scenes instead of 2); DP at 60x80 (cropped 54x72) with one observation step. 40 epochs:
# what the measured runs trained (DP3 90% on open_box_easy, 100% on dual_bottles_pick_easy).
FAST = {**REDUCED, "n_action_steps": 4, "train": {**REDUCED["train"], "lr": 1e-3, "epochs": 40}}
FAST_BY_POLICY = {"dp3": {**FAST, "num_points": 256},
                  "dp": {**FAST, "n_obs_steps": 1, "image_size": [60, 80], "crop_size": [54, 72]}}
RECIPES: dict[str, dict[str, dict]] = {"paper": {"dp": {}, "dp3": {}}, "fast": FAST_BY_POLICY,
                                       "reduced": REDUCED_BY_POLICY}
RECIPE_NAMES = tuple(RECIPES)


def default_recipe(device: str) -> str:
    """The recipe a run gets when none is named: the paper's on a GPU, `fast` on a CPU."""
    return "paper" if str(device).startswith("cuda") else "fast"


def recipe_overrides(name: str, policy: str, overrides: dict | None = None) -> dict:
    """The recipe's settings for `policy` with `overrides` merged over them (nested dicts)."""
    if name not in RECIPES:
        raise ValueError(f"unknown recipe {name!r}; recipes: {', '.join(RECIPE_NAMES)}")
    return merge(RECIPES[name].get(policy, {}), overrides or {})


def merge(base: dict, extra: dict) -> dict:
    out = dict(base)
    for k, v in extra.items():
        out[k] = merge(out[k], v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out
