"""Visual randomization: what a scene looks like, drawn from a seed, changed without touching its physics.

Drawn: the table's colour and texture, the floor's (and, in a room, the walls') colours, the key and fill
lights' direction and intensity and the ambient light, a jitter of the head and world cameras within the
bounds below, and a few distractor objects on the table's far corners, outside every hand's operable range.
Distractors are purely visual (contype = conaffinity = 0): nothing can touch them, so an episode's object
trajectories are the same with and without randomization (tests/test_visual_randomization.py).

`VisualParams` is plain data; episode metadata stores it whole (`to_dict`), and `from_dict` rebuilds the
same look, so a recorded episode re-renders exactly.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from humanoidgen.scenes.room import Part

# Camera jitter bounds (uniform, per axis): eye and look-at target in metres, vertical field of view in degrees.
CAMERA_JITTER = {
    "head": (0.01, 0.02, 1.0),
    "front": (0.02, 0.03, 2.0),
    "left": (0.02, 0.03, 2.0),
    "right": (0.02, 0.03, 2.0),
}  # the wrist cameras are mounted on the hands and stay as they are
TABLE_TEXTURES = ("flat", "checker", "gradient", "cross")
LIGHT_ELEVATION_DEG = (45.0, 85.0)
KEY_DIFFUSE = (0.35, 0.85)
FILL_DIFFUSE = (0.1, 0.45)
AMBIENT = (0.2, 0.45)
# Distractors stand on the table's far corners: past x = -0.1 and |y| >= 0.52, clear of the operable ranges
# (x <= -0.19, |y| <= 0.36) and of the arms' paths to them.
DISTRACTOR_X = (-0.08, 0.14)
DISTRACTOR_ABS_Y = (0.52, 0.72)
MAX_DISTRACTORS = 4


@dataclass(frozen=True)
class CameraJitter:
    eye: tuple[float, float, float]
    target: tuple[float, float, float]
    fovy: float


@dataclass(frozen=True)
class VisualParams:
    seed: int
    table_rgba: tuple[float, float, float, float]
    table_texture: str
    table_rgb2: tuple[float, float, float]
    floor_rgb: tuple[tuple[float, float, float], tuple[float, float, float]]
    wall_rgba: tuple[float, float, float, float]  # used in rooms
    key_dir: tuple[float, float, float]
    key_diffuse: float
    fill_diffuse: float
    ambient: float
    cameras: dict[str, CameraJitter]
    distractors: tuple[Part, ...]  # tabletop-world coordinates

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> VisualParams:
        t = tuple
        return cls(seed=int(d["seed"]), table_rgba=t(d["table_rgba"]), table_texture=str(d["table_texture"]),
                   table_rgb2=t(d["table_rgb2"]), floor_rgb=t(t(c) for c in d["floor_rgb"]),
                   wall_rgba=t(d["wall_rgba"]), key_dir=t(d["key_dir"]), key_diffuse=float(d["key_diffuse"]),
                   fill_diffuse=float(d["fill_diffuse"]), ambient=float(d["ambient"]),
                   cameras={k: CameraJitter(t(v["eye"]), t(v["target"]), float(v["fovy"]))
                            for k, v in d["cameras"].items()},
                   distractors=tuple(Part(**{**p, "pos": t(p["pos"]), "size": t(p["size"]), "rgba": t(p["rgba"])})
                                     for p in d["distractors"]))


def _rgb(rng: np.random.Generator, lo: float, hi: float) -> tuple[float, float, float]:
    return tuple(round(float(v), 4) for v in rng.uniform(lo, hi, 3))


def draw_visuals(seed: int) -> VisualParams:
    """The look of episode `seed` (deterministic)."""
    rng = np.random.default_rng([seed, 0x7151])
    az = rng.uniform(0, 2 * math.pi)
    el = math.radians(rng.uniform(*LIGHT_ELEVATION_DEG))
    key_dir = (round(-math.cos(el) * math.cos(az), 4), round(-math.cos(el) * math.sin(az), 4), round(-math.sin(el), 4))
    cams = {}
    for name, (de, dt, df) in CAMERA_JITTER.items():
        cams[name] = CameraJitter(tuple(round(float(v), 5) for v in rng.uniform(-de, de, 3)),
                                  tuple(round(float(v), 5) for v in rng.uniform(-dt, dt, 3)),
                                  round(float(rng.uniform(-df, df)), 4))
    distractors = []
    for k in range(int(rng.integers(0, MAX_DISTRACTORS + 1))):
        side = 1.0 if k % 2 == 0 else -1.0
        x, y = float(rng.uniform(*DISTRACTOR_X)), side * float(rng.uniform(*DISTRACTOR_ABS_Y))
        rgba = (*_rgb(rng, 0.05, 1.0), 1.0)
        shape = ("box", "cylinder", "sphere")[int(rng.integers(3))]
        if shape == "box":
            e = tuple(round(float(v), 4) for v in rng.uniform(0.02, 0.05, 3))
            distractors.append(Part("box", (x, y, e[2]), e, rgba, yaw=float(rng.uniform(0, math.pi)), kind="distractor"))
        elif shape == "cylinder":
            r, hh = float(rng.uniform(0.02, 0.045)), float(rng.uniform(0.03, 0.1))
            distractors.append(Part("cylinder", (x, y, hh), (r, hh), rgba, kind="distractor"))
        else:
            r = float(rng.uniform(0.02, 0.05))
            distractors.append(Part("sphere", (x, y, r), (r,), rgba, kind="distractor"))
    return VisualParams(
        seed=int(seed), table_rgba=(*_rgb(rng, 0.2, 0.95), 1.0),
        table_texture=TABLE_TEXTURES[int(rng.integers(len(TABLE_TEXTURES)))], table_rgb2=_rgb(rng, 0.1, 0.95),
        floor_rgb=(_rgb(rng, 0.2, 0.8), _rgb(rng, 0.2, 0.8)), wall_rgba=(*_rgb(rng, 0.4, 0.95), 1.0),
        key_dir=key_dir, key_diffuse=round(float(rng.uniform(*KEY_DIFFUSE)), 4),
        fill_diffuse=round(float(rng.uniform(*FILL_DIFFUSE)), 4), ambient=round(float(rng.uniform(*AMBIENT)), 4),
        cameras=cams, distractors=tuple(distractors))
