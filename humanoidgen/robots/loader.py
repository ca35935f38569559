"""Reading robot and hand files into a `Robot`: validated, cross-checked between the two files, with what code
needs derived once (joint names per side, the action layout, the hand's points and axes per side).

A robot is a folder `robots/<name>/` holding `robot.yaml`; the hand it names is `hands/<type>.yaml` beside the
robot's folder, else the packaged `robots/hands/<type>.yaml`. Loads are cached per path; reading the default robot costs a YAML read and a
validation, once per process. Every error is one line that names the file and the field.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import cache, cached_property
from pathlib import Path

import numpy as np
import yaml
from pydantic import ValidationError

from humanoidgen.robots.schema import SIDE_NAMES, HandFile, RobotFile
from humanoidgen.robots.workspace import WorkspaceMap

ROBOTS_DIR = Path(__file__).parent
HANDS_DIR_NAME = "hands"
ROBOT_FILE = "robot.yaml"
DEFAULT_ROBOT = "h1_2_inspire"
# The process's robot when set (a name, folder or robot.yaml): `--robot` sets it before the simulation's modules
# are imported, so that their derived names (`sim.layout`) and the plan worker (it inherits the environment)
# are that robot's.
ENV_ROBOT = "HGEN_ROBOT"
_Loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class RobotFileError(ValueError):
    """A robot or hand file that cannot be read, does not fit the schema, or does not fit its model."""


def _details(exc: ValidationError) -> str:
    parts = []
    for err in exc.errors():
        msg = err["msg"].removeprefix("Value error, ")
        loc = ".".join(str(x) for x in err["loc"])
        parts.append(f"{loc}: {msg}" if loc else msg)
    return "; ".join(parts)


def _read(path: Path, schema: type) -> object:
    try:
        raw = yaml.load(path.read_text(), Loader=_Loader)
    except OSError as exc:
        raise RobotFileError(f"{path}: cannot read: {exc.strerror or exc}") from None
    except yaml.YAMLError as exc:
        raise RobotFileError(f"{path}: not valid YAML: {' '.join(str(exc).split())}") from None
    try:
        return schema.model_validate(raw)
    except ValidationError as exc:
        raise RobotFileError(f"{path}: {_details(exc)}") from None


@dataclass(frozen=True)
class Hand:
    """A validated hand file, and its annotations per side."""

    data: HandFile
    path: Path

    @property
    def stems(self) -> tuple[str, ...]:
        return tuple(j.stem for j in self.data.joints)

    @property
    def dof_names(self) -> tuple[str, ...]:
        return tuple(j.dof for j in self.data.joints)

    def palm_sign(self, side: str) -> float:
        return self.data.frame.palm_sign[side]  # type: ignore[index]

    def _mirror(self, v: tuple[float, float, float], side: str) -> np.ndarray:
        # Given for the right hand; the left's y is mirrored. A y of 0 stays as written (no -0.0).
        x, y, z = v
        return np.array([x, self.palm_sign(side) * y if y else y, z])

    def points(self, side: str) -> dict[str, np.ndarray]:
        return {p.name.format(side=side): self._mirror(p.position, side) for p in self.data.points}

    def axes(self, side: str) -> dict[str, np.ndarray]:
        return {a.name.format(side=side): self._mirror(a.direction, side) for a in self.data.axes}

    @property
    def point_descriptions(self) -> dict[str, str]:
        return {p.name: p.description for p in self.data.points}

    @property
    def axis_descriptions(self) -> dict[str, str]:
        return {a.name: a.description for a in self.data.axes}

    @property
    def postures(self) -> dict[str, tuple[float, ...]]:
        return {k: tuple(v) for k, v in self.data.postures.items()}


@dataclass(frozen=True)
class Robot:
    """A validated robot file with its hand; names per side, in the order the action uses them."""

    data: RobotFile
    hand: Hand
    path: Path  # the robot.yaml
    arm_joints: dict[str, tuple[str, ...]] = field(init=False)
    arm_links: dict[str, tuple[str, ...]] = field(init=False)
    hand_prefix: dict[str, str] = field(init=False)
    hand_joints: dict[str, tuple[str, ...]] = field(init=False)

    def __post_init__(self) -> None:
        arms, hands = self.data.arms, self.data.hands
        prefix = {s: getattr(hands, s).prefix for s in SIDE_NAMES}
        object.__setattr__(self, "arm_joints", {s: tuple(j.joint for j in arms[s]) for s in SIDE_NAMES})
        object.__setattr__(self, "arm_links", {s: tuple(j.link for j in arms[s]) for s in SIDE_NAMES})
        object.__setattr__(self, "hand_prefix", prefix)
        object.__setattr__(self, "hand_joints",
                           {s: tuple(f"{prefix[s]}_{stem}" for stem in self.hand.stems) for s in SIDE_NAMES})

    @property
    def name(self) -> str:
        return self.data.name

    @cached_property
    def workspace(self) -> WorkspaceMap:
        """How positions of the reference workspace map to this robot's (`robots.workspace`)."""
        return WorkspaceMap.of(self.data.workspace)

    @property
    def folder(self) -> Path:
        return self.path.parent

    @property
    def sums_path(self) -> Path:
        return self.folder / self.data.model.checksums

    @property
    def hand_source(self) -> "Robot | None":
        """The robot whose model carries this robot's hands (`hands.source`), or None: its model's own."""
        src = self.data.hands.source
        return None if src is None else load_robot(src.robot)

    def robots_needed(self) -> tuple["Robot", ...]:
        """The robots whose model files building this one reads: the hands' source first, then itself."""
        src = self.hand_source
        return (self,) if src is None else (*src.robots_needed(), self)

    # ------------------------------------------------------------------ the hands' mounts

    def hand_mount(self, side: str) -> str:
        return getattr(self.data.hands, side).mount

    def hand_frame(self, side: str) -> str:
        return getattr(self.data.hands, side).frame

    def hand_link(self, side: str, stem: str) -> str:
        """A hand link's (or joint's) name in the model: "<prefix>_<stem>"."""
        return f"{self.hand_prefix[side]}_{stem}"

    def is_hand_name(self, name: str, side: str | None = None) -> bool:
        """Whether a joint or body name belongs to a hand (`side`'s, or either)."""
        sides = SIDE_NAMES if side is None else (side,)
        return name.startswith(tuple(f"{self.hand_prefix[s]}_" for s in sides))

    # ------------------------------------------------------------------ the action

    @cached_property
    def action_joints(self) -> tuple[str, ...]:
        """What each action entry drives: the arms (left, right), then the hands (left, right)."""
        return (*(j for s in SIDE_NAMES for j in self.arm_joints[s]),
                *(j for s in SIDE_NAMES for j in self.hand_joints[s]))

    @cached_property
    def arm_slices(self) -> dict[str, slice]:
        n = len(self.arm_joints["left"])
        return {s: slice(i * n, (i + 1) * n) for i, s in enumerate(SIDE_NAMES)}

    @cached_property
    def hand_slices(self) -> dict[str, slice]:
        start, n = 2 * len(self.arm_joints["left"]), len(self.hand.stems)
        return {s: slice(start + i * n, start + (i + 1) * n) for i, s in enumerate(SIDE_NAMES)}

    # ------------------------------------------------------------------ every name the files give

    def model_names(self) -> dict[str, list[str]]:
        """The joint and body names this robot's files use in the model, by what they are (for `check`)."""
        d, joints, bodies = self.data, [], []
        for s in SIDE_NAMES:
            joints += [*self.arm_joints[s], *self.hand_joints[s]]
            bodies += [*self.arm_links[s], self.hand_mount(s)]
            bodies += [self.hand_link(s, link) for links in self.hand.data.fingers.values() for link in links]
        bodies += [d.stand.root_body, *d.stand.feet, *d.torso_bodies, *d.no_collision.subtrees,
                   *d.no_collision.bodies, *(c.body for c in d.cameras if c.body is not None)]
        return {"joints": joints + list(d.weld), "bodies": bodies}


def _cross_check(robot: RobotFile, hand: HandFile, path: Path, hand_path: Path) -> None:
    if robot.hands.hand_base != hand.frame.hand_base:
        raise RobotFileError(f"{path}: hands.hand_base: {hand.name}'s annotations ({hand_path.name}) assume the "
                             f"hand base at {hand.frame.hand_base.model_dump()} on its mount")
    if robot.home.hands not in hand.postures:
        raise RobotFileError(f"{path}: home.hands: {robot.home.hands!r} is not a posture of {hand_path.name} "
                             f"({', '.join(hand.postures)})")
    if hand.followers == "urdf_mimic" and robot.model.urdf is None and robot.hands.source is None:
        raise RobotFileError(f"{path}: model.urdf: {hand.name}'s followers are coupled by the URDF's <mimic> tags "
                             f"({hand_path.name}): name the URDF")
    if not (path.parent / robot.model.checksums).is_file():
        raise RobotFileError(f"{path}: model.checksums: no file {robot.model.checksums} beside it")


def robot_file_path(name_or_path: str | Path) -> Path:
    """A robot's name (a folder under robots/), its folder or its robot.yaml -> the robot.yaml."""
    p = Path(name_or_path)
    if p.suffix in (".yaml", ".yml"):
        return p
    if p.is_dir():
        return p / ROBOT_FILE
    return ROBOTS_DIR / str(name_or_path) / ROBOT_FILE


@cache
def _load(path: Path) -> Robot:
    data = _read(path, RobotFile)
    assert isinstance(data, RobotFile)
    # The hand file beside the robot's folder, else the packaged one (hands are shared between robots).
    beside = path.parent.parent / HANDS_DIR_NAME / f"{data.hands.type}.yaml"
    hand_path = beside if beside.is_file() else ROBOTS_DIR / HANDS_DIR_NAME / f"{data.hands.type}.yaml"
    if not hand_path.is_file():
        raise RobotFileError(f"{path}: hands.type: no hand file {beside} nor {hand_path}")
    hand = _read(hand_path, HandFile)
    assert isinstance(hand, HandFile)
    _cross_check(data, hand, path, hand_path)
    if data.hands.source is not None:
        _check_hand_source(data, path)
    return Robot(data=data, hand=Hand(hand, hand_path), path=path)


def _check_hand_source(data: RobotFile, path: Path) -> None:
    """The robot the hands come from carries the same hand, with the same names, at the same pose on its mount."""
    name = data.hands.source.robot  # type: ignore[union-attr]
    try:
        src = load_robot(name).data.hands
    except RobotFileError as exc:
        raise RobotFileError(f"{path}: hands.source.robot: {exc}") from None
    if src.type != data.hands.type or src.hand_base != data.hands.hand_base:
        raise RobotFileError(f"{path}: hands.source.robot: {name} carries {src.type!r} hands at "
                             f"{src.hand_base.model_dump()}, not this file's")
    for side in SIDE_NAMES:
        if getattr(src, side).prefix != getattr(data.hands, side).prefix:
            raise RobotFileError(f"{path}: hands.{side}.prefix: {name}'s {side} hand is "
                                 f"{getattr(src, side).prefix!r}")


def load_robot(name_or_path: str | Path = DEFAULT_ROBOT, cached: bool = True) -> Robot:
    """The robot named (or at this path), validated; cached unless `cached=False` (a check reads the files as
    they are now)."""
    path = robot_file_path(name_or_path).resolve()
    return _load(path) if cached else _load.__wrapped__(path)


def default_robot() -> Robot:
    """The process's robot: `$HGEN_ROBOT` when set, else the default one."""
    return load_robot(os.environ.get(ENV_ROBOT) or DEFAULT_ROBOT)


def robot_names() -> list[str]:
    """The robots packaged under robots/."""
    return sorted(p.parent.name for p in ROBOTS_DIR.glob(f"*/{ROBOT_FILE}"))
