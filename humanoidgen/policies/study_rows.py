"""The rows of a policy study's table: one row per (run, scenes) with its baselines beside it and 95% Wilson
intervals; rows of one checkpoint evaluated on other seeds pooled into one; and rows from a saved
`hgen policy eval --out` report, so that a run trained by hand joins a table (`bench/policies.py --from-eval`).
Training, evaluating and plotting are `policies.bench`'s."""

from __future__ import annotations

SCENES = ("clean", "randomized")


def _baseline_columns(baselines: dict) -> dict:
    """A row's baseline columns: baseline_<name> (success mean on the row's scenes) and their details, from the
    baselines as a report's dict holds them (`EvalReport.to_dict`, a saved report)."""
    from humanoidgen.policies.report import wilson_interval

    out: dict = {f"baseline_{name}": b["success_mean"] for name, b in baselines.items()}
    if baselines:
        out["baselines"] = {name: {"success_mean": b["success_mean"], "success_std": b["success_std"],
                                   "success_ci95": list(wilson_interval(sum(o["success"] for o in b["outcomes"]),
                                                                       len(b["outcomes"]))),
                                   "rates": [r["success"] for r in b["rates"]], **b.get("info", {}),
                                   "successes": [o["scene_seed"] for o in b["outcomes"] if o["success"]]}
                            for name, b in baselines.items()}
    return out


def rows_from_eval(report: dict, demos: int, recipe: str | None, epochs: int | None,
                   train_scenes: str = "clean") -> list[dict]:
    """Study rows from a saved `hgen policy eval --out` report (one scenes' report, or `--randomize`'s clean and
    randomized pair), so that a run trained and evaluated by hand joins a study's table and plot (`--combine`).
    What the report does not hold (demonstrations, recipe, epochs, the training data's scenes) is passed in."""
    parts = [report] if "task" in report else [report[k] for k in SCENES if k in report]
    if not parts:
        raise ValueError("not an evaluation report: no task, and neither clean nor randomized results")
    rows = []
    for part in parts:
        if len(part["checkpoints"]) != 1:
            raise ValueError(f"the report evaluates {len(part['checkpoints'])} checkpoints; a row is one")
        row = {"task": part["task"], "policy": part["policy"], "demos": demos, "scenes": part["scenes"],
               "recipe": recipe, "train_scenes": train_scenes, "epochs": epochs,
               "success_mean": part["success_mean"], "success_std": part["success_std"],
               "rates": [r["success"] for r in part["rates"]], "checkpoint": part["checkpoints"][0],
               "episodes": [{k: o[k] for k in ("seed", "scene_seed", "success", "steps", "final")}
                            for o in part["outcomes"]],
               **_baseline_columns(part.get("baselines") or {})}
        if (part.get("info") or {}).get("temporal_ensemble") is not None:  # executed through ensemble.py
            row["temporal_ensemble"] = part["info"]["temporal_ensemble"]
        rows.append(with_intervals(row))
    return rows


def with_intervals(row: dict) -> dict:
    """The row with `success_ci95` (95% Wilson, episodes pooled) for the policy and each baseline, from its
    episodes where a row written before the column lacks it (a baseline's episodes are the policy's scenes)."""
    from humanoidgen.policies.report import wilson_interval

    out = dict(row)
    total = len(row.get("episodes", []))
    if "success_ci95" not in out and total:
        out["success_ci95"] = list(wilson_interval(sum(e["success"] for e in row["episodes"]), total))
    if total and row.get("baselines"):
        out["baselines"] = {name: b if "success_ci95" in b else {**b, "success_ci95": list(
            wilson_interval(len(b.get("successes", [])), total))} for name, b in row["baselines"].items()}
    return out


def pool_rows(rows: list[dict]) -> list[dict]:
    """Rows of one checkpoint on the same kind of scenes, evaluated on other seeds (a study run again with
    `--seeds 2` beside one of `--seeds 0,1`), as one row over all their seeds: the rates and episodes of each,
    the mean and spread over every seed, the baselines likewise, the intervals over the pooled episodes."""
    import numpy as np

    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        key = (r["task"], r["policy"], r["demos"], r.get("train_scenes"), r.get("scenes"), r.get("checkpoint"))
        groups.setdefault(key, []).append(r)
    out = []
    for part in groups.values():
        if len(part) == 1:
            out.append(part[0])
            continue
        part = sorted(part, key=lambda r: min(e["seed"] for e in r["episodes"]))
        seeds = [{e["seed"] for e in r["episodes"]} for r in part]
        if len(set().union(*seeds)) != sum(len(x) for x in seeds):
            raise ValueError(f"rows of {part[0]['checkpoint']} on {part[0].get('scenes')} scenes share seeds")
        rates = [x for r in part for x in r["rates"]]
        row = {k: v for k, v in part[0].items() if k != "success_ci95"}
        row.update(rates=rates, success_mean=float(np.mean(rates)), success_std=float(np.std(rates)),
                   episodes=[e for r in part for e in r["episodes"]],
                   eval_seconds=sum(r.get("eval_seconds") or 0.0 for r in part))
        if all(r.get("baselines") for r in part):
            row["baselines"] = {}
            for name in part[0]["baselines"]:
                b_rates = [x for r in part for x in r["baselines"][name]["rates"]]
                b = {k: v for k, v in part[0]["baselines"][name].items() if k != "success_ci95"}
                b.update(rates=b_rates, success_mean=float(np.mean(b_rates)), success_std=float(np.std(b_rates)),
                         successes=[x for r in part for x in r["baselines"][name]["successes"]])
                row["baselines"][name] = b
                row[f"baseline_{name}"] = b["success_mean"]
        out.append(with_intervals(row))
    return out
