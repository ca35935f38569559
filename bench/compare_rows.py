"""Trainings of one task side by side: the first row of each bench/results/policies_<name>.json as one bar (success
with its 95% Wilson interval) beside the random and no-op baselines of its own scenes, labelled. For comparing
training data or settings on one task (close_drawer's demonstrations as recorded, re-recorded, perturbed), where
`bench/policies.py --combine` plots against the number of demonstrations or by scenes.

    python bench/compare_rows.py --rows cpu_fast_close_drawer_thin_bar,cpu_fast_close_drawer_dart03 \
        --labels "recorded,DART 0.03" --name close_drawer_dart
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent


def load(names: list[str]) -> list[dict]:
    out = []
    for name in names:
        path = ROOT / "results" / f"policies_{name}.json"
        if not path.exists():
            raise SystemExit(f"error: no results at {path}")
        rows = json.loads(path.read_text()).get("rows") or []
        if not rows:
            raise SystemExit(f"error: {path} has no rows")
        out.append({"from": name, **rows[0]})
    return out


def plot(rows: list[dict], labels: list[str], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 0.55 * len(rows) + 1.4))
    ys = list(range(len(rows)))[::-1]
    for y, row in zip(ys, rows):
        mean = 100 * row["success_mean"]
        lo, hi = (100 * v for v in row.get("success_ci95", (row["success_mean"],) * 2))
        ax.barh(y, mean, color="tab:blue", alpha=0.75)
        # max(0, ...): a Wilson bound at 60 of 60 comes out a rounding error under the mean (0.9999999999999999)
        ax.errorbar(mean, y, xerr=[[max(0.0, mean - lo)], [max(0.0, hi - mean)]], color="black", capsize=3)
        ax.text(hi + 1, y, f"{mean:.1f}%", va="center", fontsize=8)
    ax.scatter([100 * r.get("baseline_random", 0.0) for r in rows], ys, marker="x", color="tab:red", label="random")
    ax.scatter([100 * r.get("baseline_noop", 0.0) for r in rows], ys, marker="|", s=120, color="tab:gray", label="no-op")
    ax.set_yticks(ys)
    ax.set_yticklabels(labels, fontsize=8)
    ax.set_xlim(0, 100)
    ax.set_xlabel("success (%), 95% interval")
    ax.set_title(", ".join(sorted({f"{r['task']} {r['policy'].upper()}" for r in rows})), fontsize=10)
    ax.grid(axis="x", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--rows", required=True, help="comma list of result names (bench/results/policies_<name>.json)")
    p.add_argument("--labels", required=True, help="comma list, one label per row")
    p.add_argument("--name", required=True, help="writes bench/results/<name>.json and .png")
    args = p.parse_args()
    names = [n.strip() for n in args.rows.split(",") if n.strip()]
    labels = [s.strip() for s in args.labels.split(",")]
    if len(names) != len(labels) or not names:
        print(f"error: {len(names)} rows and {len(labels)} labels; give one label per row", file=sys.stderr)
        return 2
    rows = load(names)
    out = ROOT / "results" / f"{args.name}.json"
    keep = ("task", "policy", "demos", "epochs", "success_mean", "success_std", "success_ci95", "rates",
            "baseline_random", "baseline_noop", "action_frame", "perturbation", "variant")
    out.write_text(json.dumps({"rows": [{"label": lab, "from": r["from"], **{k: r[k] for k in keep if k in r}}
                                        for lab, r in zip(labels, rows)]}, indent=2))
    plot(rows, labels, out.with_suffix(".png"))
    print(f"wrote {out} and {out.with_suffix('.png')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
