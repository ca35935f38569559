"""A robot's workspace map: positions written for the reference workspace, placed for this robot.

Task specs and reference plans are written once, in the reference workspace (the H1-2's, where they were tuned).
Positions in them that are about the arms' reach rather than about an object (a spec target's mid-air hand-over
`pos`, the spot a plan hands a block over at, the height a plan lifts it to) are mapped per robot with its
robot file's `workspace` (docs/guides/robots.md):

    p' = p + offset + per_height * (p.z - table top)

so the same spec and the same plan put a hand-over where each robot's arms meet comfortably. Positions relative to
objects (`relative_to`, offsets from a key point) are not mapped: they follow the objects. The reference robot's
map is the identity and gives its positions back unchanged, bit for bit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from humanoidgen.robots.schema import Workspace

TABLE_TOP_Z = 0.0  # the world's convention (sim.layout): every robot's table top is z = 0


@dataclass(frozen=True)
class WorkspaceMap:
    """`Workspace` as a function of positions."""

    offset: np.ndarray
    per_height: np.ndarray

    @classmethod
    def of(cls, ws: Workspace) -> WorkspaceMap:
        return cls(np.array(ws.offset, float), np.array(ws.per_height, float))

    @property
    def identity(self) -> bool:
        return not (self.offset.any() or self.per_height.any())

    def point(self, p) -> np.ndarray:
        """A position (3,) or positions (..., 3) of the reference workspace -> this robot's (a new array)."""
        q = np.array(p, dtype=float)
        if q.shape[-1:] != (3,):
            raise ValueError(f"a workspace position has x, y and z, got shape {q.shape}")
        if self.identity:  # the reference robot: exactly what was given
            return q
        return q + self.offset + self.per_height * (q[..., 2:3] - TABLE_TOP_Z)
