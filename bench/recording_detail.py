"""The recording level of detail: full-detail robot visual meshes (`hgen render`) next to the lighter ones
recordings use, their pixel difference and render time, on the robot at its table with one cube (six cameras,
320x240, the arms at their initial posture and at two other postures).

Writes bench/results/recording_detail.png (head, front and right-wrist views: full | recording | 4x the
difference) and bench/results/recording_detail.json.

Usage: python bench/recording_detail.py [--width 320 --height 240]
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402

from humanoidgen.episodes.recorder import matching_render_model  # noqa: E402
from humanoidgen.episodes.render_replay import pose_data  # noqa: E402
from humanoidgen.sim.action import ARM_SLICE  # noqa: E402
from humanoidgen.sim.cameras import CAMERA_NAMES, CameraRig  # noqa: E402
from humanoidgen.sim.env import HumanoidEnv  # noqa: E402
from humanoidgen.sim.meshes import DEFAULT_MAX_FACES, recording_faces, visual_detail  # noqa: E402
from humanoidgen.sim.mosaic import mosaic  # noqa: E402
from humanoidgen.sim.scene import SceneBuilder  # noqa: E402

RESULTS = Path(__file__).parent / "results"
SHOWN = ("head", "front", "right_wrist")


def scene_model(faces: int) -> mujoco.MjModel:
    with visual_detail(faces):
        builder = SceneBuilder()
        builder.add_cube()
        return builder.build().model


def postures(env: HumanoidEnv) -> list[np.ndarray]:
    """Configurations: the arms at rest, then reaching forward and in."""
    out = []
    for offset in (0.0, 0.25, -0.2):
        a = env.init_action()
        a[ARM_SLICE["left"]] += offset * np.array([-1.0, 0.5, 0.3, 0.6, 0.2, -0.3, 0.1])
        a[ARM_SLICE["right"]] += offset * np.array([-1.0, -0.5, -0.3, 0.6, -0.2, 0.3, -0.1])
        for _ in range(25):
            env.step(a)
        out.append(env.kinematics_qpos())
    return out


def render(model: mujoco.MjModel, configurations: list[np.ndarray], width: int, height: int):
    data = mujoco.MjData(model)
    frames = []
    with CameraRig(model, width, height) as rig:
        pose_data(model, data, configurations[0])
        rig.render_all(data, segmentation=False)  # warm-up
        t0 = time.perf_counter()
        for q in configurations:
            pose_data(model, data, q)
            frames.append(rig.render_all(data, segmentation=False))
        seconds = (time.perf_counter() - t0) / (len(configurations) * len(CAMERA_NAMES))
    return frames, seconds


def robot_triangles(model: mujoco.MjModel) -> int:
    from humanoidgen.sim.robot import ROBOT_VISUAL_GROUP

    return sum(int(model.mesh_facenum[model.geom_dataid[g]]) for g in range(model.ngeom)
               if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH and model.geom_group[g] == ROBOT_VISUAL_GROUP)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    args = ap.parse_args()
    full = scene_model(DEFAULT_MAX_FACES)
    builder = SceneBuilder()
    builder.add_cube()
    env = HumanoidEnv(builder.build())
    configurations = postures(env)
    ref, ref_s = render(full, configurations, args.width, args.height)
    rows = [{"faces_per_mesh": DEFAULT_MAX_FACES, "robot_triangles": robot_triangles(full),
             "ms_per_image": round(1e3 * ref_s, 2)}]
    chosen = recording_faces(args.width, args.height)
    shown = None
    for faces in sorted({750, chosen, 200}, reverse=True):
        model = matching_render_model(full, scene_model(faces))
        frames, seconds = render(model, configurations, args.width, args.height)
        rgb = np.stack([np.abs(f[c].rgb.astype(int) - r[c].rgb).max(-1) for f, r in zip(frames, ref)
                        for c in CAMERA_NAMES])
        depth = np.stack([np.abs(f[c].depth - r[c].depth) for f, r in zip(frames, ref) for c in CAMERA_NAMES])
        rows.append({"faces_per_mesh": faces, "robot_triangles": robot_triangles(model),
                     "ms_per_image": round(1e3 * seconds, 2), "rgb_mean_abs_levels": round(float(rgb.mean()), 3),
                     "rgb_pixels_over_8_levels_pct": round(100 * float((rgb > 8).mean()), 2),
                     "depth_pixels_over_1cm_pct": round(100 * float((depth > 0.01).mean()), 2),
                     "recording_default": faces == chosen})
        if faces == chosen:
            shown = frames
    for r in rows:
        print(r)
    images = {}
    for c in SHOWN:
        a, b = ref[1][c].rgb, shown[1][c].rgb
        images[f"{c}: full ({DEFAULT_MAX_FACES} faces/mesh)"] = a
        images[f"{c}: recording ({chosen})"] = b
        diff = np.clip(4 * np.abs(a.astype(int) - b).max(-1), 0, 255).astype(np.uint8)
        images[f"{c}: 4x difference"] = np.repeat(diff[..., None], 3, axis=2)
    RESULTS.mkdir(exist_ok=True)
    mosaic(images, columns=3).save(RESULTS / "recording_detail.png")
    (RESULTS / "recording_detail.json").write_text(json.dumps(
        {"resolution": [args.width, args.height], "cameras": list(CAMERA_NAMES), "postures": len(configurations),
         "levels": rows}, indent=2) + "\n")
    print(f"wrote {RESULTS / 'recording_detail.png'} and .json")


if __name__ == "__main__":
    main()
