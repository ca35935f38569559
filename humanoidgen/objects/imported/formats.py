"""What a model file is read into: a `SourceModel` of links, each a mesh in the file's own units and frame, joined
by joints; and the small protocol a format implements (registered in registry.py)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal, Protocol

import numpy as np
import trimesh


class ImportError_(ValueError):
    """A file that cannot be imported: the message is one line that says what is wrong and what to do."""


@dataclass(frozen=True)
class SourceJoint:
    """The joint that moves a link relative to its parent: at `origin` (parent frame) along `axis`."""

    name: str
    kind: Literal["slide", "hinge"]
    axis: tuple[float, float, float]
    lower: float
    upper: float


@dataclass
class SourceLink:
    """One rigid part: its mesh in the link frame, the link frame's pose in its parent's (4x4) and its joint."""

    name: str
    mesh: trimesh.Trimesh
    parent: str | None = None
    origin: np.ndarray = field(default_factory=lambda: np.eye(4))
    joint: SourceJoint | None = None


@dataclass
class SourceModel:
    """A file's content: links in tree order (the first is the root). A rigid mesh is one link."""

    links: list[SourceLink]
    texture: object | None = None  # a PIL image, for a single textured mesh
    default_up: str = "z"

    @property
    def articulated(self) -> bool:
        return any(link.joint is not None for link in self.links)


class ModelFormat(Protocol):
    """A file format: its name, the file suffixes it reads and how it reads one."""

    name: str
    suffixes: tuple[str, ...]

    def load(self, path: Path) -> SourceModel: ...
