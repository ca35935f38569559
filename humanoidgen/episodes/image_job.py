"""The images of a kept attempt, rendered outside its plan worker.

The plan worker records an attempt's physics and, for a kept attempt, hands back the configurations the
frames are drawn from (`HumanoidEnv.kinematics_qpos`, a few kB per frame) instead of the frames (over a
hundred kB per camera and frame): sending those through the worker's pipe cost more than rendering them,
and held them all in memory twice on each side (a 50 Hz handover_and_storage episode is 4.3 GB of frames).
The caller renders them here, from the same scene built again at the recording's level of detail, and
`EpisodeStore` writes them frame by frame as they come (`write_episode`), so an episode of any length
renders in bounded memory, and `collect` renders one attempt while the plan worker runs the next.

Rendering here trusts nothing of the worker's but numbers: configurations are checked for shape and
finiteness, and a hostile plan can only spoil its own episode's pictures, as it could before.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from humanoidgen.episodes.recorder import RecorderConfig

# The key under which arrays of a kept attempt carry its ImageJob until they are written (`write_episode`).
PENDING_IMAGES = "pending_images"


@dataclass(frozen=True)
class ImageJob:
    """What a kept attempt's images are drawn from (picklable: it travels with Ray results)."""

    task: str  # a task name or a path to a task YAML, as in EpisodeRequest
    seed: int | None
    dressing: dict | None
    recorder: RecorderConfig
    configurations: np.ndarray  # (T, nq) float64
    # The simulated model's stat.extent and stat.center: the clipping planes (so depth) are the simulator's.
    model_stat: np.ndarray  # (4,) float64

    def __post_init__(self) -> None:
        q, stat = self.configurations, self.model_stat
        if not (isinstance(q, np.ndarray) and q.dtype == np.float64 and q.ndim == 2 and len(q)
                and np.isfinite(q).all()):
            raise ValueError("configurations must be a finite (T, nq) float64 array with T >= 1")
        if not (isinstance(stat, np.ndarray) and stat.shape == (4,) and np.isfinite(stat).all() and stat[0] > 0):
            raise ValueError("model_stat must be a finite (4,) array: extent > 0 and centre")

    @property
    def frames(self) -> int:
        return len(self.configurations)

    def layout(self) -> dict[str, tuple[tuple[int, ...], np.dtype]]:
        """Shape of one frame and dtype of each array the images add, in writing order."""
        from humanoidgen.episodes.render_replay import frame_layout

        r = self.recorder
        return frame_layout(r.cameras, r.width, r.height, r.depth, r.point_cloud, r.num_points)

    def model(self):
        """The task's scene for this seed, built again (not settled: only poses are replayed) with the
        recording's visual meshes, and given the simulated model's clipping planes."""
        from humanoidgen.scenes.dressing import SceneDressing
        from humanoidgen.sim.meshes import visual_detail
        from humanoidgen.tasks.registry import load_task
        from humanoidgen.tasks.scene import build_layout

        spec = load_task(self.task)
        with visual_detail(self.recorder.faces):
            scene, _ = build_layout(spec.sample_layout(self.seed), settle_s=0.0, aliases=spec.aliases(),
                                    dressing=SceneDressing.from_dict(self.dressing) if self.dressing else None)
        model = scene.model
        if model.nq != self.configurations.shape[1]:
            raise RuntimeError(f"the scene rebuilt for rendering has nq={model.nq}, the recording "
                               f"{self.configurations.shape[1]}")
        model.stat.extent = self.model_stat[0]
        model.stat.center[:] = self.model_stat[1:]
        return model

    def iter_frames(self, threads: int | None = None) -> Iterator[tuple[int, dict[str, np.ndarray]]]:
        """(t, arrays of frame t) in time order (`render_replay.iter_frames`)."""
        from humanoidgen.episodes.render_replay import iter_frames

        return iter_frames(*self._render_args(), threads=threads, cloud_floor=self.recorder.point_cloud_floor,
                           near_hands=self.recorder.point_cloud_near_hands)

    def render_arrays(self, threads: int | None = None) -> dict[str, np.ndarray]:
        """All images at once, in memory (for callers that want the arrays, not a file)."""
        from humanoidgen.episodes.render_replay import render_recording

        return render_recording(*self._render_args(), threads=threads, cloud_floor=self.recorder.point_cloud_floor,
                                near_hands=self.recorder.point_cloud_near_hands)

    def _render_args(self) -> tuple:
        r = self.recorder
        return (self.model(), self.configurations, r.cameras, r.width, r.height, r.depth,
                r.point_cloud_cameras if r.point_cloud else (), r.num_points)


def warm_up(task: str, recorder: RecorderConfig, seed: int | None = 0) -> None:
    """Pay the collecting process's one-off rendering costs now, while the first attempt plans in its worker:
    the first build of the task's scene at the recording detail (MuJoCo compiles the robot's meshes once per
    process, about 2.4 s of the first build's 2.7; later builds take 0.3 s) and the loading of the compiled
    point-cloud and still-layer code (about 0.7 s). Nothing is kept but those caches; any failure is left to
    the real render."""
    try:
        from humanoidgen.sim.fps import warm_up as warm_fps
        from humanoidgen.sim.meshes import visual_detail
        from humanoidgen.sim.still_layer import warm_up as warm_layers
        from humanoidgen.tasks.registry import load_task
        from humanoidgen.tasks.scene import build_layout

        spec = load_task(task)
        with visual_detail(recorder.faces):
            build_layout(spec.sample_layout(seed), settle_s=0.0, aliases=spec.aliases())
        warm_layers()
        if recorder.point_cloud:
            from humanoidgen.sim.pointcloud import PointCloudConfig, fuse_point_cloud

            warm_fps()
            fuse_point_cloud([(np.ones((4, 4), np.float32), 45.0, np.zeros(3), np.eye(3), None)],
                             PointCloudConfig(num_points=4, crop_lo=(-9.0,) * 3, crop_hi=(9.0,) * 3))
    except Exception:  # noqa: BLE001 - a cache left cold only costs time
        pass


def model_stat(model) -> np.ndarray:
    """What `ImageJob.model_stat` holds for the simulated `model`."""
    return np.array([model.stat.extent, *model.stat.center], np.float64)
