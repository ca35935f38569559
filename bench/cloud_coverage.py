"""How many of a policy's points fall on a part that its task turns on: the env's point cloud at reset (the
recorded farthest-point order, as DP3 reads its first N points), counted within `radius` of the scene's geoms whose
names contain `--near`, for each N. A 1 cm post that three points of 256 land near is a post the policy has to
guess the place of; close_drawer's grip is such a post (bench/replay_tolerance.py).

Distance is to each geom's bounding box in its own frame (MuJoCo's `geom_aabb`), so a bar and a post count alike.

    python bench/cloud_coverage.py --task close_drawer --near handle --points 256,512,1024 --scenes 20

`--near-hands SHARE` draws that share of the cloud near the hands (`point_cloud_near_hands`). At reset the hands are
far from everything, so `--dataset D` counts instead at the recorded frames of D's first `--episodes` kept episodes
where a hand's grasp point is within `--hand-within` of the part: the cloud a policy reads as it closes on it.

    python bench/cloud_coverage.py --near handle --points 256 --dataset data/close_drawer --near-hands 0.5
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


def _geoms(model, task: str, near: str) -> list[int]:
    import mujoco

    geoms = [g for g in range(model.ngeom) if near in (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or "")]
    if not geoms:
        raise SystemExit(f"error: no geom of {task}'s scene has {near!r} in its name")
    return geoms


def coverage(task: str, near: str, radius: float, points: list[int], scenes: list[int],
             near_hands: float = 0.0) -> list[dict]:
    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv

    env = HumanoidTaskEnv(task, config=TaskEnvConfig(cameras=(), num_points=max(points),
                                                     point_cloud_near_hands=near_hands))
    rows = []
    try:
        for seed in scenes:
            obs, _ = env.reset(seed=seed)
            model, data = env.sim.model, env.sim.data
            geoms = _geoms(model, task, near)
            d = distance_to_geoms(np.asarray(obs["point_cloud"])[:, :3], data, model, geoms)
            rows.append({"scene_seed": seed, "geoms": len(geoms),
                         "within": {str(n): int((d[:n] <= radius).sum()) for n in points}})
    finally:
        env.close()
    return rows


def coverage_at_grip(dataset: Path, near: str, radius: float, points: list[int], episodes: int, near_hands: float,
                     hand_within: float) -> list[dict]:
    """Per kept episode of `dataset`: the counts at each recorded frame where a hand's grasp point is within
    `hand_within` of the part, the cloud drawn from the recorded configuration as the recorder draws it."""
    import mujoco

    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.episodes.render_replay import focus_points, render_configuration
    from humanoidgen.sim.cameras import CameraRig
    from humanoidgen.sim.pointcloud import workspace_cloud

    store = EpisodeStore(dataset)
    task = store.meta()["task"]
    rec = store.meta().get("recorder") or {}
    cams = tuple(rec.get("point_cloud_cameras") or TaskEnvConfig().point_cloud_cameras)
    pc = workspace_cloud(max(points), float(rec.get("point_cloud_floor", TaskEnvConfig().point_cloud_floor)),
                         near_hands)
    env = HumanoidTaskEnv(task, config=TaskEnvConfig(cameras=(), point_cloud=False))
    rows = []
    try:
        for kept in store.kept()[:episodes]:
            # a randomized collection's room and look, as it was recorded in (None: the clean tabletop)
            env.reset(seed=int(kept["seed"]), options={"dressing": kept.get("dressing")})
            model = env.sim.model
            data = mujoco.MjData(model)
            geoms = _geoms(model, task, near)
            rig = CameraRig(model, int(rec.get("width", 320)), int(rec.get("height", 240)))
            try:
                frames = []
                for t, qpos in enumerate(store.load(kept["episode"], ("qpos",))["qpos"]):
                    data.qpos[:] = qpos
                    mujoco.mj_kinematics(model, data)
                    hand = distance_to_geoms(focus_points(model, data), data, model, geoms).min()
                    if hand > hand_within:
                        continue
                    _, cloud = render_configuration(rig, model, data, qpos, (), False, cams, pc)
                    d = distance_to_geoms(np.asarray(cloud)[:, :3], data, model, geoms)
                    frames.append({str(n): int((d[:n] <= radius).sum()) for n in points})
            finally:
                rig.close()
            if frames:
                rows.append({"scene_seed": int(kept["seed"]), "frames": len(frames), "geoms": len(geoms),
                             "within": {str(n): float(np.mean([f[str(n)] for f in frames])) for n in points},
                             "min": {str(n): min(f[str(n)] for f in frames) for n in points}})
    finally:
        env.close()
    return rows


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--task", default=None, help="the task (with --dataset: its own)")
    p.add_argument("--near", required=True, help="count points near geoms whose names contain this")
    p.add_argument("--radius", type=float, default=0.01, help="m from a geom's box (default 1 cm)")
    p.add_argument("--points", default="256,512,1024", help="comma list: the first N points of the cloud")
    p.add_argument("--scenes", type=int, default=20, help="evaluation scenes 100000, 100001, ...")
    p.add_argument("--name", default=None, help="writes bench/results/cloud_coverage_<name>.json")
    p.add_argument("--near-hands", type=float, default=0.0, help="share of the cloud drawn near the hands")
    p.add_argument("--dataset", type=Path, default=None, help="count at this dataset's recorded frames instead, "
                   "where a hand's grasp point is within --hand-within of the part")
    p.add_argument("--episodes", type=int, default=8, help="with --dataset: its first N kept episodes")
    p.add_argument("--hand-within", type=float, default=0.05, help="with --dataset: m from the part (default 5 cm)")
    a = p.parse_args()
    points = sorted(int(n) for n in a.points.split(","))
    head = commit()
    if a.dataset is None and a.task is None:
        p.error("give --task or --dataset")
    if a.dataset is not None:
        from humanoidgen.episodes.dataset import EpisodeStore

        a.task = EpisodeStore(a.dataset).meta()["task"]
        rows = coverage_at_grip(a.dataset, a.near, a.radius, points, a.episodes, a.near_hands, a.hand_within)
        if not rows:
            raise SystemExit(f"error: no recorded frame has a hand within {a.hand_within} m of '{a.near}'")
    else:
        rows = coverage(a.task, a.near, a.radius, points, list(range(100000, 100000 + a.scenes)), a.near_hands)
    summary = {str(n): {"mean": float(np.mean([r["within"][str(n)] for r in rows])),
                        "min": min(r.get("min", r["within"])[str(n)] for r in rows)} for n in points}
    where = f"{sum(r['frames'] for r in rows)} frames at the grip" if a.dataset is not None else "at reset"
    for n in points:
        print(f"{a.task}: first {n} points, within {a.radius * 100:g} cm of '{a.near}': "
              f"mean {summary[str(n)]['mean']:.1f}, min {summary[str(n)]['min']} ({len(rows)} scenes, {where})")
    out = ROOT / "results" / f"cloud_coverage_{a.name or a.task + '_' + a.near}.json"
    out.write_text(json.dumps({"commit": head, "machine": machine(), "task": a.task, "near": a.near,
                               "radius_m": a.radius, "points": points, "near_hands": a.near_hands,
                               "dataset": str(a.dataset) if a.dataset else None, "hand_within_m": a.hand_within,
                               "summary": summary, "scenes": rows}, indent=1))
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
