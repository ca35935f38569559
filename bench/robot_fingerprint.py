"""Is the robot built from its data file the robot built from code before? Fingerprint everything it makes.

Digests (SHA-256, 16 hex digits) of:
- every array of the compiled MjModel of a few tasks' scenes, names, meshes and textures included, and the
  state they settle to (`model:<task>:<field>`, `qpos:<task>`);
- the robot constants other modules import (`const:<name>`): joint names, action layout, hand points, axes,
  postures, cameras;
- one recorded episode (`episode:<key>`): the reference plan of block_stack_single, seed 3, recorded with the
  head and front cameras at 160x120 (RGB, depth, segmentation).

    python bench/robot_fingerprint.py --json /tmp/before.json
    python bench/robot_fingerprint.py --compare /tmp/before.json /tmp/after.json
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import sys
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
TASKS = ("block_stack_single", "open_drawer", "close_laptop_easy")
EPISODE = ("block_stack_single", 3)


def _h(value: object) -> str:
    import numpy as np

    if isinstance(value, np.ndarray):
        data = np.ascontiguousarray(value).tobytes() + str(value.dtype).encode() + str(value.shape).encode()
    else:
        data = repr(value).encode()
    return hashlib.sha256(data).hexdigest()[:16]


def model_digests(task: str, seed: int = 0) -> dict[str, str]:
    import numpy as np

    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    _, env = build_scene(load_task(task), seed)
    m = env.model
    out = {f"model:{task}:{n}": _h(getattr(m, n)) for n in dir(m)
           if not n.startswith("_") and isinstance(getattr(m, n, None), np.ndarray)}
    out[f"model:{task}:opt"] = _h([getattr(m.opt, n).tolist() if hasattr(getattr(m.opt, n), "tolist")
                                   else getattr(m.opt, n) for n in dir(m.opt) if not n.startswith("_")
                                   and not callable(getattr(m.opt, n))])
    out[f"qpos:{task}"] = _h(env.data.qpos.copy())
    return out


def const_digests() -> dict[str, str]:
    from humanoidgen.objects import hands
    from humanoidgen.sim import action, cameras, layout, robot

    values = {
        "layout.ARM_JOINTS": layout.ARM_JOINTS, "layout.HAND_JOINTS": layout.HAND_JOINTS,
        "layout.HAND_PREFIX": layout.HAND_PREFIX, "layout.HAND_BASE_FRAME": layout.HAND_BASE_FRAME,
        "layout.WRIST_BODY": layout.WRIST_BODY, "layout.ROBOT_BASE_POS": layout.ROBOT_BASE_POS.tolist(),
        "layout.OPERABLE_RANGE": layout.OPERABLE_RANGE, "layout.PALM_SIGN": layout.PALM_SIGN,
        "layout.HAND_DOF_NAMES": layout.HAND_DOF_NAMES,
        "layout.arm_bodies": {s: layout.arm_bodies(s) for s in layout.SIDES},
        "layout.palm": {s: (layout.palm_center_on_wrist(s).tolist(), layout.palm_normal_on_wrist(s).tolist())
                        for s in layout.SIDES},
        "action.ACTION_JOINTS": action.ACTION_JOINTS, "action.ACTION_DIM": action.ACTION_DIM,
        "action.slices": (action.ARM_SLICE, action.HAND_SLICE),
        "cameras.CAMERAS": cameras.CAMERAS, "cameras.CAMERA_NAMES": cameras.CAMERA_NAMES,
        "hands.HAND_POSTURES": hands.HAND_POSTURES,
        "hands.points": {s: {k: v.tolist() for k, v in hands.hand_points(s).items()} for s in layout.SIDES},
        "hands.axes": {s: {k: v.tolist() for k, v in hands.hand_axes(s).items()} for s in layout.SIDES},
        "hands.descriptions": (hands.HAND_POINT_DESCRIPTIONS, hands.HAND_AXIS_DESCRIPTIONS),
        "hands.wrap": [hands.wrap_point(s, 0.06, a).tolist() for s in layout.SIDES for a in (None, 0.08)],
        "robot.groups": (robot.ROBOT_COLLISION_GROUP, robot.ROBOT_VISUAL_GROUP),
    }
    return {f"const:{k}": _h(v) for k, v in values.items()}


def episode_digests() -> dict[str, str]:
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    task, seed = EPISODE
    rec = RecorderConfig(cameras=("head", "front"), width=160, height=120)
    result, arrays = run_task_episode(EpisodeRequest(task, seed, recorder=rec), render=True)
    out = {f"episode:{k}": _h(v) for k, v in sorted((arrays or {}).items()) if hasattr(v, "tobytes")}
    out["episode:success"] = str(bool(result.success))
    out["episode:events"] = _h("\n".join(result.events))
    return out


def compare(a: Path, b: Path) -> int:
    before, after = json.loads(a.read_text()), json.loads(b.read_text())
    keys = sorted(set(before) | set(after))
    diff = [k for k in keys if before.get(k) != after.get(k)]
    for k in diff:
        print(f"DIFFERS {k}: {before.get(k)} -> {after.get(k)}")
    print(f"{len(keys)} digests compared, {len(diff)} differ")
    return 1 if diff else 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", type=Path)
    ap.add_argument("--compare", nargs=2, type=Path, metavar=("BEFORE", "AFTER"))
    ap.add_argument("--no-episode", action="store_true")
    args = ap.parse_args()
    if args.compare:
        return compare(*args.compare)
    out = const_digests()
    for task in TASKS:
        out.update(model_digests(task))
    if not args.no_episode:
        out.update(episode_digests())
    text = json.dumps(out, indent=1, sort_keys=True)
    if args.json:
        args.json.write_text(text)
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
