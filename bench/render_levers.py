"""Cheap levers on the recording renderer (issue 14), measured on the same views and scene: the frames of a
recorded block_stack_single episode (seed 0, 10 Hz, six 320x240 cameras, recording level of detail), drawn
by the software renderer (Mesa llvmpipe through EGL) in one thread.

Each lever is timed in CPU milliseconds per six-camera RGB-D frame (render + read pixels + metric depth;
`time.process_time`, so the renderer's own threads count too; the levers are interleaved over several rounds
and the fastest round is kept, since the machine is shared) and compared with the baseline pixels: mean
absolute RGB difference in levels, the share of pixels with a channel off by more than 8 levels, the largest
depth difference and the share of depth pixels that differ at all.

The baseline is the recording renderer before these measurements: a render context made from the whole
model and the floor drawn on its 5 cm grid. Levers: MuJoCo scene flags (shadow, reflection, skybox, haze,
fog; shadows were already off), lights (shadow casting, the fill light), the context made without the
meshes nothing draws (`cameras.drawn_meshes_only`: its setup time), the floor's rendering grid (a plane's
third size), the textures' minifying filter (set through OpenGL on MuJoCo's context),
an offscreen buffer of the camera's size (MuJoCo's default scene asks 1280x960 for `hgen render`), all six
views drawn into tiles of one offscreen buffer and read back with one `mjr_readPixels` call (one flush of the
renderer instead of six), the renderer's thread count (`LP_NUM_THREADS`, in a child process each, since Mesa
reads it once), and the per-frame numpy work after the read (flip, metric depth, millimetres).

Writes bench/results/render_levers.json.

Usage: python bench/render_levers.py [--frames 31] [--rounds 3] [--json bench/results/render_levers.json]
"""

from __future__ import annotations

import argparse
import copy
import json
import os
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402

from humanoidgen.episodes.render_replay import pose_data  # noqa: E402
from humanoidgen.sim.cameras import CAMERA_NAMES, CameraRig  # noqa: E402
from humanoidgen.sim.meshes import FLOOR_GRID_M  # noqa: E402

RESULTS = Path(__file__).parent / "results"
FLAG = mujoco.mjtRndFlag


def episode_job(task: str = "block_stack_single", seed: int = 0):
    """The ImageJob of a recorded episode (physics only, as collect hands it to the writer)."""
    from humanoidgen.episodes.image_job import PENDING_IMAGES
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    rec = RecorderConfig(every=5, cameras=CAMERA_NAMES, point_cloud=True)
    result, arrays = run_task_episode(EpisodeRequest(task, seed=seed, recorder=rec), render=False)
    if not result.success:
        raise SystemExit(f"{task} seed {seed} failed: cannot measure on it")
    return arrays[PENDING_IMAGES]


class LeverRig(CameraRig):
    """CameraRig with the levers: scene flags switched off, lights changed, tiled drawing."""

    def __init__(self, model, flags_off=(), tiled=False, tex_filter=None, upload_hidden=True, **kw):
        from humanoidgen.sim import cameras

        trim = cameras.drawn_meshes_only
        if upload_hidden:  # as before: the context made from the whole model, hidden meshes too
            cameras.drawn_meshes_only = lambda m, opt: m
        try:
            super().__init__(model, 320, 240, **kw)
        finally:
            cameras.drawn_meshes_only = trim
        if tex_filter is not None:
            from OpenGL import GL

            self._gl.make_current()
            for t in range(model.ntex):
                if model.tex_type[t] == mujoco.mjtTexture.mjTEXTURE_2D:
                    GL.glBindTexture(GL.GL_TEXTURE_2D, self._con.texture[t])
                    GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_MIN_FILTER, getattr(GL, tex_filter))
        self.flags_off, self.tiled = tuple(flags_off), tiled
        if tiled:
            n = len(CAMERA_NAMES)
            self.cols = min(n, model.vis.global_.offwidth // self.width)
            rows = -(-n // self.cols)
            self._big = mujoco.MjrRect(0, 0, self.cols * self.width, rows * self.height)
            self._brgb = np.empty((rows * self.height, self.cols * self.width, 3), np.uint8)
            self._bdepth = np.empty((rows * self.height, self.cols * self.width), np.float32)

    def frame(self, data):
        """[(rgb, metric depth)] of the six cameras."""
        if not self.tiled and not self.flags_off:
            return [(f.rgb, f.depth) for f in (self.render(data, c, segmentation=False) for c in CAMERA_NAMES)]
        self._gl.make_current()
        out, rects = [], []
        for i, c in enumerate(CAMERA_NAMES):
            self._cam.fixedcamid = self.model.camera(c).id
            mujoco.mjv_updateScene(self.model, data, self._opt, self._pert, self._cam,
                                   mujoco.mjtCatBit.mjCAT_ALL.value, self._scn)
            self._scn.flags[FLAG.mjRND_SHADOW] = self.shadows
            for f in self.flags_off:
                self._scn.flags[f] = False
            if self.tiled:
                rect = mujoco.MjrRect((i % self.cols) * self.width, (i // self.cols) * self.height,
                                      self.width, self.height)
                mujoco.mjr_render(rect, self._scn, self._con)
                rects.append(rect)
            else:
                mujoco.mjr_render(self._rect, self._scn, self._con)
                mujoco.mjr_readPixels(self._rgb, self._depth, self._rect, self._con)
                out.append((np.flipud(self._rgb).copy(), np.flipud(self._metric_depth(self._depth)).copy()))
        if self.tiled:
            mujoco.mjr_readPixels(self._brgb, self._bdepth, self._big, self._con)
            for r in rects:
                sl = (slice(r.bottom, r.bottom + r.height), slice(r.left, r.left + r.width))
                out.append((np.flipud(self._brgb[sl]).copy(), np.flipud(self._metric_depth(self._bdepth[sl])).copy()))
        return out


def model_variant(base: mujoco.MjModel, name: str) -> mujoco.MjModel:
    """A copy of `base` (the recording model as it was: floor grid 5 cm) with the lever's change."""
    m = copy.copy(base)
    floor = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "floor")
    m.geom_size[floor, 2] = FLOOR_GRID_M
    if name == "offscreen 320x240":
        m.vis.global_.offwidth, m.vis.global_.offheight = 320, 240
    elif name == "no shadow-casting lights":
        m.light_castshadow[:] = 0
    elif name == "fill light off":
        m.light_active[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_LIGHT, "fill")] = 0
    elif name == "shadow map 1x1":
        m.vis.quality.shadowsize = 1
    elif name.startswith("floor grid"):
        m.geom_size[floor, 2] = float(name.split()[2])
    return m


NOW = {"upload_hidden": False}  # what CameraRig does now
LEVERS = {
    # name: (model variant, rig keywords)
    "baseline": ("", {}),
    "skybox off": ("", {"flags_off": (FLAG.mjRND_SKYBOX,)}),
    "reflection off": ("", {"flags_off": (FLAG.mjRND_REFLECTION,)}),
    "haze off": ("", {"flags_off": (FLAG.mjRND_HAZE,)}),
    "fog off": ("", {"flags_off": (FLAG.mjRND_FOG,)}),
    "skybox, reflection, haze, fog off": ("", {"flags_off": (FLAG.mjRND_SKYBOX, FLAG.mjRND_REFLECTION,
                                                             FLAG.mjRND_HAZE, FLAG.mjRND_FOG)}),
    "no shadow-casting lights": ("no shadow-casting lights", {}),
    "fill light off": ("fill light off", {}),
    "shadow map 1x1": ("shadow map 1x1", {}),
    "offscreen 320x240": ("offscreen 320x240", {}),
    "six views tiled, one read": ("", {"tiled": True}),
    "hidden meshes not uploaded": ("", NOW),
    "floor grid 0.1 m": ("floor grid 0.1 m", {}),
    "floor grid 0.2 m": ("floor grid 0.2 m", {}),
    "floor grid 0.5 m": ("floor grid 0.5 m", {}),
    "texture min filter bilinear, nearest mipmap": ("", {"tex_filter": "GL_LINEAR_MIPMAP_NEAREST"}),
    "texture min filter nearest mipmap, nearest texel": ("", {"tex_filter": "GL_NEAREST_MIPMAP_NEAREST"}),
    "recording now: floor grid 0.2 m, hidden meshes not uploaded": ("floor grid 0.2 m", NOW),
    "floor grid 0.2 m, hidden meshes, bilinear nearest mipmap": ("floor grid 0.2 m",
                                                                 {**NOW, "tex_filter": "GL_LINEAR_MIPMAP_NEAREST"}),
}


def measure(job, frames: int, rounds: int, only: list[str] | None) -> dict:
    model = job.model()
    qs = job.configurations[np.linspace(0, job.frames - 1, frames).round().astype(int)]
    names = [n for n in LEVERS if only is None or n in only]
    rigs, models, setup = {}, {}, {}
    for name in names:
        variant, kw = LEVERS[name]
        models[name] = model_variant(model, variant)
        setup[name] = np.inf
        for _ in range(3):  # the context's setup: the fastest of three
            t0 = time.process_time()
            rig = LeverRig(models[name], **kw)
            setup[name] = min(setup[name], time.process_time() - t0)
            if name in rigs:
                rig.close()
            else:
                rigs[name] = rig
    datas = {name: mujoco.MjData(models[name]) for name in names}
    cpu = {name: [] for name in names}
    wall = {name: [] for name in names}
    images = {}
    rng = np.random.default_rng(0)
    for _ in range(rounds):
        for name in rng.permutation(names):  # a new order each round: no lever always runs first
            rig, data = rigs[name], datas[name]
            rig._gl.make_current()
            pose_data(rig.model, data, qs[0])
            rig.frame(data)  # warm
            out = []
            c0, w0 = time.process_time(), time.perf_counter()
            for q in qs:
                pose_data(rig.model, data, q)
                out.append(rig.frame(data))
            cpu[name].append((time.process_time() - c0) / len(qs))
            wall[name].append((time.perf_counter() - w0) / len(qs))
            images[name] = out
    post = _postprocess_cost(images[names[0]], rigs[names[0]])
    for rig in rigs.values():
        rig.close()
    rows = {}
    ref = images.get("baseline")
    for name in names:
        row = {"cpu_ms_per_frame": round(1000 * min(cpu[name]), 2),
               "wall_ms_per_frame": round(1000 * min(wall[name]), 2),
               "context_setup_cpu_s": round(setup[name], 3)}
        if ref is not None:
            row.update(_pixel_change(ref, images[name]))
        rows[name] = row
    return {"rows": rows, "postprocess": post}


def _pixel_change(ref, other) -> dict:
    rgb_a = np.stack([v[0] for f in ref for v in f]).astype(np.int16)
    rgb_b = np.stack([v[0] for f in other for v in f]).astype(np.int16)
    d_a = np.stack([v[1] for f in ref for v in f])
    d_b = np.stack([v[1] for f in other for v in f])
    diff = np.abs(rgb_a - rgb_b)
    finite = np.isfinite(d_a) & np.isfinite(d_b) & (d_a < 50) & (d_b < 50)
    return {"rgb_identical": bool((diff == 0).all()),
            "rgb_mean_abs_levels": round(float(diff.mean()), 3),
            "rgb_pixels_over_8_levels_pct": round(100 * float((diff.max(axis=-1) > 8).mean()), 3),
            "depth_identical": bool(np.array_equal(d_a, d_b)),
            "depth_pixels_changed_pct": round(100 * float((d_a != d_b).mean()), 3),
            "depth_max_abs_m_on_surfaces": round(float(np.abs(d_a - d_b)[finite].max(initial=0.0)), 6)}


def _postprocess_cost(frames, rig: CameraRig) -> dict:
    """Per six-camera frame: flip + copy of RGB, metric depth (float64 then float32), uint16 millimetres."""
    from humanoidgen.episodes.depth_units import encode_depth

    rgb = np.flipud(frames[0][0][0]).copy()
    z = np.random.default_rng(0).uniform(0.9, 1.0, (240, 320)).astype(np.float32)
    n = 200
    t0 = time.process_time()
    for _ in range(n):
        np.flipud(rgb).copy()
    t1 = time.process_time()
    for _ in range(n):
        np.flipud(rig._metric_depth(z)).copy()
    t2 = time.process_time()
    d = rig._metric_depth(z)
    for _ in range(n):
        encode_depth(d)
    t3 = time.process_time()
    k = len(CAMERA_NAMES) * 1000 / n
    return {"flip_rgb_ms": round((t1 - t0) * k, 2), "metric_depth_ms": round((t2 - t1) * k, 2),
            "encode_mm_ms": round((t3 - t2) * k, 2)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--frames", type=int, default=31)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--lp-threads", default="0,1,2", help="LP_NUM_THREADS values measured in child processes")
    ap.add_argument("--json", type=Path, default=RESULTS / "render_levers.json")
    ap.add_argument("--child", default=None, help=argparse.SUPPRESS)
    ap.add_argument("--job", type=Path, default=None, help="a pickled ImageJob (default: record one now)")
    args = ap.parse_args()
    import pickle

    if args.child is not None:
        job = pickle.loads(args.job.read_bytes())
        out = measure(job, args.frames, args.rounds, args.child.split("|"))
        print(json.dumps(out))
        return
    job = episode_job()
    job_path = Path(os.environ.get("TMPDIR", "/tmp")) / f"hgen-render-levers-{os.getpid()}.pkl"
    job_path.write_bytes(pickle.dumps(job))
    try:
        load0 = os.getloadavg()[0]
        res = measure(job, args.frames, args.rounds, None)
        threads = {}
        for lp in [s for s in args.lp_threads.split(",") if s]:
            env = dict(os.environ, LP_NUM_THREADS=lp)
            cmd = [sys.executable, __file__, "--child", "baseline|six views tiled, one read", "--job", str(job_path),
                   "--frames", str(args.frames), "--rounds", str(args.rounds)]
            child = json.loads(subprocess.run(cmd, env=env, check=True, capture_output=True,
                                              text=True).stdout.strip().splitlines()[-1])
            threads[f"LP_NUM_THREADS={lp}"] = {k: {kk: v[kk] for kk in ("cpu_ms_per_frame", "wall_ms_per_frame")}
                                               for k, v in child["rows"].items()}
    finally:
        job_path.unlink(missing_ok=True)
    out = {"machine": f"{os.cpu_count()} CPUs, shared; load average {load0:.2f} at the start, "
                      f"{os.getloadavg()[0]:.2f} at the end",
           "episode": f"block_stack_single seed 0, 10 Hz: {job.frames} frames, {args.frames} of them drawn per "
                      f"lever and round, {args.rounds} rounds, fastest kept",
           "renderer_threads_default": os.environ.get("LP_NUM_THREADS", "Mesa's default (one per CPU)"),
           "levers": res["rows"], "postprocess_ms_per_six_cameras": res["postprocess"],
           "llvmpipe_threads": threads}
    text = json.dumps(out, indent=2) + "\n"
    print(text)
    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(text)


if __name__ == "__main__":
    main()
