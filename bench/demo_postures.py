"""How many arm postures a dataset's demonstrations reach their grips in: the spread a policy has to imitate.

A 7-joint arm reaches one hand pose in several postures (the shoulder turned one way and the forearm the other),
and the goal solver picks one per scene (the lowest-cost of the postures its seeds find). Where the scenes of one
task land in many posture families, the demonstrations show the same grip made with very different joint
trajectories, and a policy that outputs joint targets learns a many-moded action from few examples of each mode.

For every kept episode of each episode folder (`hgen collect`'s output) and each hand that closes in it, this takes
the arm's joint targets at the action where the hand first closes (the mean of the hand's joint targets past
CLOSED of the way from their smallest to their largest value in that episode), and groups those postures: two
postures are in one family when a chain of postures, each within --tol rad of the next on every joint, joins them
(single linkage, SciPy's `fcluster`; the result does not depend on the episodes' order).

    python bench/demo_postures.py DATA/close_drawer DATA/open_box_easy --name issue37
    python bench/demo_postures.py DATA/close_drawer --tol 0.5

Writes bench/results/demo_postures_<name>.json (one row per folder and hand: task, episodes, families, the largest
family's share, the family sizes) and a bar chart beside it.
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from provenance import commit  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
CLOSED = 0.5  # share of the hand's travel in the episode past which it counts as closed
TOL_RAD = 1.0  # default: postures this near on every joint (a chain of them) are one family
AT_LIMIT_RAD = 0.02  # a joint this near an end of its range counts as at its limit


def closing_index(hand: np.ndarray) -> int | None:
    """The first action at which the hand's mean joint target is past CLOSED of its travel in the episode, or
    None where it hardly moves (under 0.2 rad: a hand that does not grip in this episode)."""
    level = hand.mean(axis=1)
    lo, hi = float(level.min()), float(level.max())
    if hi - lo < 0.2:
        return None
    # Past the first minimum: a hand opened at the start (pre-grasp) then closed counts from its opening.
    start = int(np.argmin(level[: int(np.argmax(level)) + 1]))
    above = np.nonzero(level[start:] >= lo + CLOSED * (hi - lo))[0]
    return start + int(above[0]) if len(above) else None


def families(postures: np.ndarray, tol: float) -> np.ndarray:
    """Family labels (1..k) of postures (n, joints): single linkage at `tol` rad on the largest joint difference."""
    if len(postures) == 1:
        return np.ones(1, dtype=int)
    from scipy.cluster.hierarchy import fcluster, linkage

    return fcluster(linkage(postures, method="single", metric="chebyshev"), t=tol, criterion="distance")


def joint_ranges(robot) -> dict[str, tuple[float, float]]:
    """Each joint's range (rad) in the robot's compiled model."""
    from humanoidgen.assets.robot_files import resolve_assets_root
    from humanoidgen.sim.robot import build_robot_spec

    model = build_robot_spec(resolve_assets_root(), robot=robot).compile()
    return {model.joint(j).name: tuple(float(x) for x in model.joint(j).range) for j in range(model.njnt)}


def folder_rows(folder: Path, tol: float) -> list[dict]:
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.robots import load_robot
    from humanoidgen.robots.schema import SIDE_NAMES

    store = EpisodeStore(folder)
    meta = store.meta()
    names = list(meta["action_names"])
    robot = load_robot(meta["robot"])
    ranges = joint_ranges(robot)
    kept = store.kept()
    actions = [np.asarray(store.load(record["episode"])["action"]) for record in kept]  # each episode read once
    rows = []
    for side in SIDE_NAMES:
        arm = [names.index(j) for j in robot.arm_joints[side]]
        hand = [names.index(j) for j in robot.hand_joints[side]]
        closing = [(a, closing_index(a[:, hand])) for a in actions]
        postures = np.array([a[k, arm] for a, k in closing if k is not None])
        if not len(postures):
            continue
        labels = families(postures, tol)
        counts = np.bincount(labels)
        sizes = sorted((int(c) for c in counts[1:] if c), reverse=True)
        # Single linkage chains: a family may itself be wide where scenes' postures drift joint by joint.
        largest = postures[labels == int(np.argmax(counts))]
        # Where grips sit at a joint's end, the solver's postures for nearby scenes need not be near each other.
        lo, hi = (np.array([ranges[j][k] for j in robot.arm_joints[side]]) for k in (0, 1))
        at = (postures - lo < AT_LIMIT_RAD) | (hi - postures < AT_LIMIT_RAD)
        rows.append({"task": meta["task"], "data": str(folder), "side": side, "robot": meta["robot"],
                     "episodes": len(kept), "closing": len(postures), "tol_rad": tol,
                     "families": len(sizes), "largest_share": sizes[0] / len(postures), "family_sizes": sizes,
                     "spread_rad": np.round(np.ptp(postures, axis=0), 2).tolist(),
                     "largest_family_spread_rad": np.round(np.ptp(largest, axis=0), 2).tolist(),
                     "at_limit_share": round(float(at.any(axis=1).mean()), 3),
                     "at_limit_by_joint": at.sum(axis=0).astype(int).tolist(),
                     "arm_joints": list(robot.arm_joints[side])})
    return rows


def plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(max(4.0, 1.6 * len(rows)), 3.2))
    for i, r in enumerate(rows):
        bottom = 0
        for k, size in enumerate(r["family_sizes"]):
            share = size / r["closing"]
            ax.bar(i, share, bottom=bottom, color=plt.cm.tab20(k % 20), edgecolor="white", width=0.6)
            bottom += share
    ax.set_xticks(range(len(rows)), [f"{Path(r['data']).name}\n{r['side']} ({r['families']})" for r in rows],
                  fontsize=8)
    ax.set_ylabel("share of demonstrations")
    ax.set_title(f"arm posture families where the hand closes (tol {rows[0]['tol_rad']} rad)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("folders", nargs="+", type=Path, help="episode folders (hgen collect --out)")
    p.add_argument("--tol", type=float, default=TOL_RAD, help="rad on every joint (default %(default)s)")
    p.add_argument("--name", default="demos", help="results go to bench/results/demo_postures_<name>.json")
    p.add_argument("--results", type=Path, default=RESULTS, help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    rows = []
    for folder in args.folders:
        if not (folder / "meta.json").exists():
            print(f"error: {folder} is not an episode folder (no meta.json); pass what `hgen collect --out` wrote",
                  file=sys.stderr)
            return 2
        rows += folder_rows(folder, args.tol)
    if not rows:
        print("error: no hand closes in any kept episode of these folders", file=sys.stderr)
        return 1
    for r in rows:
        print(f"{r['task']:<26} {r['side']:<5} {r['closing']:>3} grips in {r['families']:>2} posture families "
              f"(largest {100 * r['largest_share']:.0f}%: {r['family_sizes']}); {100 * r['at_limit_share']:.0f}% with "
              f"a joint at its limit")
    args.results.mkdir(parents=True, exist_ok=True)
    out = args.results / f"demo_postures_{args.name}.json"
    out.write_text(json.dumps({"commit": commit(), "machine": f"{platform.machine()}, {platform.python_version()}",
                               "rows": rows}, indent=1))
    plot(rows, out.with_suffix(".png"))
    print(f"wrote {out} and {out.with_suffix('.png').name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
