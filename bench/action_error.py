"""How closely a trained policy reproduces its own demonstrations' actions, in radians: teacher-forced (each sampled
frame's recorded observations in, the predicted actions to execute against the recorded ones), per joint, beside
the range each joint's recorded targets span, and in metres where the moving hands land at the predicted targets
(`hand_misses`); and, with --closed-loop N, the policy run in the first N scenes it was trained on (the
collection's seeds 0..N-1), not the evaluation's unseen ones.

A policy fits its data in [-1, 1]: the actions are normalized over their range, so the same fit misses by more
radians where the targets span more. A grip tolerates a few hundredths of a radian (bench/replay_tolerance.py).
Measured on close_drawer against open_box_easy (docs/results/policies.md).

    python bench/action_error.py RUN/checkpoints/epoch_0040.pt DATA.zarr --frames 150 --name close_drawer
    python bench/action_error.py RUN/checkpoints/epoch_0040.pt DATA.zarr --closed-loop 20 --name close_drawer

Writes bench/results/action_error_<name>.json.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from provenance import commit, machine  # noqa: E402

ROOT = Path(__file__).resolve().parent
MOVING_RAD = 1e-3  # a joint whose recorded targets span less than this is one the task does not move


def sample_frames(episode_ends: np.ndarray, n_obs: int, n_act: int, frames: int, seed: int = 0) -> list[int]:
    """`frames` frames drawn over all episodes, each with n_obs - 1 frames before it and n_act from it on inside
    its episode."""
    rng = np.random.default_rng(seed)
    starts = np.r_[0, episode_ends[:-1]]
    out = []
    while len(out) < frames:
        e = int(rng.integers(len(episode_ends)))
        lo, hi = starts[e] + n_obs - 1, episode_ends[e] - n_act
        if hi > lo:
            out.append(int(rng.integers(lo, hi + 1)))
    return out


def predicted(model, arrays: dict[str, np.ndarray], t: int) -> np.ndarray:
    """The actions the policy would execute at frame t, from the recorded observations up to it (noise seeded by t:
    every measure below sees the same predictions)."""
    import torch

    cfg = model.cfg
    obs_idx = list(range(t - cfg.n_obs_steps + 1, t + 1))
    obs = {k: torch.as_tensor(np.asarray(arrays[k][obs_idx])[None], dtype=torch.float32)
           for k in model.obs_keys if k in arrays}
    return model.predict_action(obs, generator=torch.Generator().manual_seed(t))["action"][0].numpy()


def teacher_forced(model, arrays: dict[str, np.ndarray], frames: list[int]) -> np.ndarray:
    """(frames, action_dim) the largest |predicted - recorded| over the executed actions of each frame (rad)."""
    errors = []
    for t in frames:
        pred = predicted(model, arrays, t)
        errors.append(np.abs(pred - np.asarray(arrays["action"][t: t + len(pred)])).max(axis=0))
    return np.asarray(errors)


class HandFrames:
    """Where each hand's frame is at given arm joint targets: the planner's forward kinematics
    (`planning.kinematics.Kinematics`, a scratch copy of a task's model: any of its scenes, the arms and their base
    are the same in every one)."""

    def __init__(self, model) -> None:
        from humanoidgen.planning.kinematics import Kinematics
        from humanoidgen.sim.action import ARM_SLICE

        self.kin, self.arm_slice = Kinematics(model), ARM_SLICE

    @classmethod
    def for_task(cls, task: str) -> HandFrames:
        from humanoidgen.tasks.registry import load_task
        from humanoidgen.tasks.scene import build_scene

        return cls(build_scene(load_task(task), None, settle_s=0.0)[1].model)

    def positions(self, actions: np.ndarray) -> np.ndarray:
        """(T, action_dim) joint targets -> (T, 2, 3): the left and right hands' positions at them."""
        sides = ("left", "right")
        out = np.empty((len(actions), 2, 3))
        for t, row in enumerate(np.asarray(actions, np.float64)):
            for side in sides:
                self.kin.set_arm(side, row[self.arm_slice[side]])
            self.kin.forward()
            out[t] = [self.kin.ee_pose(side)[0] for side in sides]
        return out


def hand_misses(model, arrays: dict[str, np.ndarray], frames: list[int], hands) -> dict:
    """How far (m) each moving hand lands, at the predicted joint targets, from where the recorded targets put it:
    the largest miss over the executed actions of each frame, median and 90th percentile over frames. The same
    predictions as `teacher_forced` (the same noise). `hands.positions(actions) -> (T, 2, 3)` (`HandFrames`)."""
    misses = []
    for t in frames:
        joints = predicted(model, arrays, t)
        want = hands.positions(np.asarray(arrays["action"][t: t + len(joints)]))
        misses.append(np.linalg.norm(hands.positions(joints) - want, axis=-1).max(axis=0))
    span = np.ptp(hands.positions(np.asarray(arrays["action"])), axis=0).max(axis=-1)
    m = np.asarray(misses)
    return {h: {"median_m": round(float(np.median(m[:, i])), 4), "p90_m": round(float(np.percentile(m[:, i], 90)), 4)}
            for i, h in enumerate(("left", "right")) if span[i] > 1e-3}


def summary(errors: np.ndarray, actions: np.ndarray) -> dict:
    """Per moving joint: its recorded span and the mean teacher-forced error; and their medians."""
    span = actions.max(axis=0) - actions.min(axis=0)
    moving = np.where(span > MOVING_RAD)[0]
    mean = errors.mean(axis=0)
    return {"joints": [int(j) for j in moving], "span_rad": [round(float(span[j]), 4) for j in moving],
            "mean_error_rad": [round(float(mean[j]), 4) for j in moving],
            "error_per_span": [round(float(mean[j] / span[j]), 4) for j in moving],
            "median_error_rad": round(float(np.median(mean[moving])), 4),
            "frames": int(len(errors))}


def closed_loop(checkpoint: Path, task: str, scenes: int) -> dict:
    """The policy in the scenes of collection seeds 0..scenes-1 (the demonstrations' own, where every attempt
    was kept); the task's predicates judge each."""
    from humanoidgen.policies import rollout
    from humanoidgen.policies.eval import evaluate

    base = rollout.EVAL_SEED_BASE
    rollout.EVAL_SEED_BASE = 0  # evaluation numbers its episodes from this scene seed on
    try:
        report = evaluate(checkpoint.parent.parent, task, scenes, (0,), checkpoints=[checkpoint], device="cpu",
                          baselines=False, progress=True)
    finally:
        rollout.EVAL_SEED_BASE = base
    return {"scenes": scenes, "success": int(sum(o.success for o in report.outcomes)),
            "episodes": [{"scene_seed": o.scene_seed, "success": o.success, "final": o.final} for o in report.outcomes]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("checkpoint", type=Path)
    ap.add_argument("data", type=Path, help="the zarr export the checkpoint was trained on")
    ap.add_argument("--frames", type=int, default=150)
    ap.add_argument("--closed-loop", type=int, default=0, help="also run the policy in this many demonstrated scenes")
    ap.add_argument("--name", required=True)
    args = ap.parse_args()
    import torch

    from humanoidgen.policies import checkpoint as ck
    from humanoidgen.policies.data import read_demos
    from humanoidgen.policies.train import policy_inputs

    torch.set_num_threads(1)
    model, meta = ck.load_policy(args.checkpoint)
    cfg = model.cfg
    demos = read_demos(args.data, model.obs_keys, cfg.train.episodes)
    # as training feeds them: clouds cut to the policy's points, pictures resized
    arrays = {k: v.numpy() for k, v in policy_inputs(model, demos).items()}
    t0 = time.perf_counter()
    frames = sample_frames(demos.episode_ends, cfg.n_obs_steps, cfg.n_action_steps, args.frames)
    result = {"checkpoint": str(args.checkpoint), "data": str(args.data), "task": meta.get("task"),
              "action_frame": getattr(cfg, "action_frame", "absolute"),
              "teacher_forced": summary(teacher_forced(model, arrays, frames), np.asarray(arrays["action"]))}
    if meta.get("task"):  # where the hands land, on the task's model
        result["teacher_forced"]["hand_miss"] = hand_misses(model, arrays, frames, HandFrames.for_task(meta["task"]))
    if args.closed_loop:
        result["closed_loop"] = closed_loop(args.checkpoint, meta["task"], args.closed_loop)
    result["settings"] = {"commit": commit(), "machine": machine(), "seconds": round(time.perf_counter() - t0, 1)}
    out = ROOT / "results" / f"action_error_{args.name}.json"
    out.write_text(json.dumps(result, indent=1))
    tf = result["teacher_forced"]
    hands = "".join(f"; the {hand} hand {v['median_m'] * 100:.2f} cm off (median)" for hand, v in
                    tf.get("hand_miss", {}).items())
    loop = f"; closed loop {result['closed_loop']['success']}/{args.closed_loop}" if args.closed_loop else ""
    print(f"{args.name}: median error {tf['median_error_rad']} rad over {len(tf['joints'])} moving joints "
          f"(spans {tf['span_rad']}){hands}{loop} -> {out}")


if __name__ == "__main__":
    main()
