"""How many of a policy's points fall on a part that its task turns on: the env's point cloud at reset (the
recorded farthest-point order, as DP3 reads its first N points), counted within `radius` of the scene's geoms whose
names contain `--near`, for each N. A 1 cm post that three points of 256 land near is a post the policy has to
guess the place of; close_drawer's grip is such a post (bench/replay_tolerance.py).

Distance is to each geom's bounding box in its own frame (MuJoCo's `geom_aabb`), so a bar and a post count alike.

    python bench/cloud_coverage.py --task close_drawer --near handle --points 256,512,1024 --scenes 20
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from provenance import commit, machine  # noqa: E402

ROOT = Path(__file__).resolve().parent


def distance_to_geoms(points: np.ndarray, data, model, geoms: list[int]) -> np.ndarray:
    """(P,) each point's distance to the nearest of `geoms`' boxes (0 inside one)."""
    best = np.full(len(points), np.inf)
    for g in geoms:
        centre, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
        local = (points - data.geom_xpos[g]) @ data.geom_xmat[g].reshape(3, 3) - centre  # world -> geom frame
        outside = np.maximum(np.abs(local) - half, 0.0)
        best = np.minimum(best, np.linalg.norm(outside, axis=1))
    return best


def coverage(task: str, near: str, radius: float, points: list[int], scenes: list[int]) -> list[dict]:
    import mujoco

    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv

    env = HumanoidTaskEnv(task, config=TaskEnvConfig(cameras=(), num_points=max(points)))
    rows = []
    try:
        for seed in scenes:
            obs, _ = env.reset(seed=seed)
            model, data = env.sim.model, env.sim.data
            geoms = [g for g in range(model.ngeom)
                     if near in (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or "")]
            if not geoms:
                raise SystemExit(f"error: no geom of {task}'s scene has {near!r} in its name")
            d = distance_to_geoms(np.asarray(obs["point_cloud"])[:, :3], data, model, geoms)
            rows.append({"scene_seed": seed, "geoms": len(geoms),
                         "within": {str(n): int((d[:n] <= radius).sum()) for n in points}})
    finally:
        env.close()
    return rows


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--task", required=True)
    p.add_argument("--near", required=True, help="count points near geoms whose names contain this")
    p.add_argument("--radius", type=float, default=0.01, help="m from a geom's box (default 1 cm)")
    p.add_argument("--points", default="256,512,1024", help="comma list: the first N points of the cloud")
    p.add_argument("--scenes", type=int, default=20, help="evaluation scenes 100000, 100001, ...")
    p.add_argument("--name", default=None, help="writes bench/results/cloud_coverage_<name>.json")
    a = p.parse_args()
    points = sorted(int(n) for n in a.points.split(","))
    head = commit()
    rows = coverage(a.task, a.near, a.radius, points, list(range(100000, 100000 + a.scenes)))
    summary = {str(n): {"mean": float(np.mean([r["within"][str(n)] for r in rows])),
                        "min": min(r["within"][str(n)] for r in rows)} for n in points}
    for n in points:
        print(f"{a.task}: first {n} points, within {a.radius * 100:g} cm of '{a.near}': "
              f"mean {summary[str(n)]['mean']:.1f}, min {summary[str(n)]['min']} ({len(rows)} scenes)")
    out = ROOT / "results" / f"cloud_coverage_{a.name or a.task + '_' + a.near}.json"
    out.write_text(json.dumps({"commit": head, "machine": machine(), "task": a.task, "near": a.near,
                               "radius_m": a.radius, "points": points, "summary": summary, "scenes": rows}, indent=1))
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
