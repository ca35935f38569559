"""What a task environment observes and how fast it acts, named as the dataset records it.

`TaskEnvConfig.from_recorder` builds the config a dataset was recorded with (its meta.json `recorder` entry or
the zarr export's `recorder` attribute), so a policy sees in the environment exactly what it saw in training:
the same cameras at the same size, the same fused point cloud, one action per `every` control steps."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

from humanoidgen.sim.cameras import CAMERA_NAMES
from humanoidgen.sim.env import DEFAULT_CONTROL_HZ, MAX_CONTROL_HZ
from humanoidgen.sim.cloud_floor import CLOUD_FLOOR, TABLE_CLOUD_FLOOR, check_near_hands

# Seeds at or above this are never used by collection's defaults (seeds 0, 1, 2, ... count up from --seed 0),
# so an evaluation never meets a scene a policy was trained on unless asked to.
EVAL_SEED_BASE = 100_000


@dataclass(frozen=True)
class TaskEnvConfig:
    every: int = 5  # control steps per action (the recorder's `every`; 50 Hz control, 5 -> 10 Hz actions)
    control_hz: float = DEFAULT_CONTROL_HZ
    cameras: tuple[str, ...] = ("head",)  # cameras whose rgb (and depth) are observed
    width: int = 320
    height: int = 240
    depth: bool = False
    point_cloud: bool = True
    point_cloud_cameras: tuple[str, ...] = ("head", "front", "left", "right")
    num_points: int = 1024
    point_cloud_floor: float = CLOUD_FLOOR  # m above the table top; the recorder's (`RecorderConfig`)
    point_cloud_near_hands: float = 0.0  # share of the points drawn near the hands (`sim.cloud_focus`)
    visual_faces: int | None = None  # robot visual mesh detail in pictures; None: the recording's for the size
    max_steps: int | None = None  # actions per episode; None: the task's time limit at this rate
    render_camera: str = "front"
    render_width: int = 640
    render_height: int = 480
    # Each reset dresses its scene from the seed, on RoboTwin 2.0's axes: a room around the table (walls,
    # furniture, clutter: the background) whose work surface sets the table's height under the robot, table and
    # floor colours and textures, lights, camera poses jittered within `scenes.visuals.CAMERA_JITTER`, and
    # distractors on the table's far corners (as `hgen collect --room random --randomize-visuals` records).
    randomize: bool = False
    extra: dict[str, Any] = field(default_factory=dict, compare=False)  # ignored recorder fields

    def __post_init__(self) -> None:
        if self.every < 1:
            raise ValueError(f"every must be >= 1, got {self.every}")
        if not 0 < self.control_hz <= MAX_CONTROL_HZ:
            raise ValueError(f"control_hz must be in (0, {MAX_CONTROL_HZ}], got {self.control_hz}")
        for name in (*self.cameras, *self.point_cloud_cameras, self.render_camera):
            if name not in CAMERA_NAMES:
                raise ValueError(f"unknown camera {name!r}; cameras: {', '.join(CAMERA_NAMES)}")
        if min(self.width, self.height, self.render_width, self.render_height) < 16:
            raise ValueError("image sizes must be at least 16 pixels")
        if self.num_points < 1:
            raise ValueError(f"num_points must be >= 1, got {self.num_points}")
        check_near_hands(self.point_cloud_near_hands)
        if self.max_steps is not None and self.max_steps < 1:
            raise ValueError(f"max_steps must be >= 1, got {self.max_steps}")

    @classmethod
    def from_recorder(cls, recorder: dict, control_hz: float = DEFAULT_CONTROL_HZ, **overrides: Any) -> TaskEnvConfig:
        """The config matching a dataset's recorder settings (a dict, as meta.json stores them)."""
        known = {f.name for f in fields(cls)}
        kw: dict[str, Any] = {k: (tuple(v) if isinstance(v, list) else v) for k, v in recorder.items() if k in known}
        kw["control_hz"] = control_hz
        if "visual_faces" not in recorder:  # recorded before the recording level of detail: at full detail
            from humanoidgen.sim.meshes import DEFAULT_MAX_FACES

            kw["visual_faces"] = DEFAULT_MAX_FACES
        if "point_cloud_floor" not in recorder:  # recorded before the floor was a setting: clouds with the table
            kw["point_cloud_floor"] = TABLE_CLOUD_FLOOR
        kw["extra"] = {k: v for k, v in recorder.items() if k not in known}
        kw.update(overrides)
        return cls(**kw)

    @property
    def action_hz(self) -> float:
        return self.control_hz / self.every
