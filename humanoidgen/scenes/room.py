"""Procedural rooms: floor, walls, the work surface's place and height, cabinets, shelves and clutter, drawn
from a seed (the same seed gives the same room).

A room is pure data in its own coordinates (room world: the floor's corner at the origin, walls along x and
y, z up from the floor). `o_prime` is the paper's frame O' on the work surface's near edge (see
`scenes.frames`); the task's table top becomes that surface, so the surface's extent is the tabletop table's.
Nothing of the room may enter the task's keep-out box (`KEEP_OUT`, tabletop-world coordinates): the table,
the robot, its arms' reach and the three world cameras all lie inside it, so furniture and clutter are
never in the way of the arms and never between a camera and the workspace (they sit behind the cameras).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from humanoidgen.robots import default_robot
from humanoidgen.scenes.frames import Rigid, apply_point, frame, o_to_o_prime

# The robot's root body stands this far above its feet (the robot file's `stand.feet_below_base`: 1.03 m for the
# H1-2's pelvis); at the tabletop table the root body is level with the table top, so that table is that high.
PELVIS_HEIGHT = default_robot().data.stand.feet_below_base
DEFAULT_SURFACE_HEIGHT = PELVIS_HEIGHT
# Work-surface heights a room may have. The robot's height is fixed, so a surface dz higher than the
# tabletop table puts the base dz lower relative to the task (and the arms reach it from dz lower).
# Measured with the reference plans (scripts/room_height_sweep.py): at 1.06 m block_handover's pinch-lift slips
# (1/3); below 1.015 m (the robot 1.5+ cm higher over the task) the left fingertip cannot push handover_and_storage's
# drawer shut (room bench seeds 1012 and 1015: fails at 1.0015 and 1.01 m, passes at 1.015, 1.02, 1.03 m).
SURFACE_HEIGHT_RANGE = (1.015, 1.035)

# Tabletop-world box (x0, x1, y0, y1) nothing of the room enters: table (x -0.62..0.20, y +-0.8), the robot
# (base at x -0.85, its back and elbows to about -1.3), the front camera (x 0.55) and the side cameras (y +-1.05).
KEEP_OUT = (-1.45, 0.70, -1.22, 1.22)
WALL_THICKNESS = 0.08


@dataclass(frozen=True)
class Part:
    """One static visual shape in room coordinates: a box (half sizes), a cylinder (radius, half height) or a
    sphere (radius); `pos` is its centre, `yaw` its turn about z."""

    shape: str
    pos: tuple[float, float, float]
    size: tuple[float, ...]
    rgba: tuple[float, float, float, float]
    yaw: float = 0.0
    kind: str = "clutter"  # wall, cabinet, shelf, clutter, surface


@dataclass(frozen=True)
class Room:
    seed: int
    size: tuple[float, float, float]  # x, y extent and wall height (m)
    surface_height: float  # work surface top above the floor (m)
    o_prime: tuple[float, float, float]  # O' origin in room coordinates (z = surface_height)
    yaw: float  # O' x axis turned from the room's x axis (rad)
    style: str  # "wall": the surface's far side faces a wall; "island": free standing
    floor_rgb: tuple[tuple[float, float, float], tuple[float, float, float]]
    wall_rgba: tuple[float, float, float, float]
    surface_rgba: tuple[float, float, float, float]
    base_rgba: tuple[float, float, float, float]  # the cabinet under the work surface
    parts: tuple[Part, ...] = field(default_factory=tuple)

    @property
    def transform(self) -> Rigid:
        """T_{O -> O'}: tabletop world -> room world."""
        return o_to_o_prime(frame(np.array(self.o_prime), self.yaw))

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> Room:
        parts = tuple(Part(**{**p, "pos": tuple(p["pos"]), "size": tuple(p["size"]), "rgba": tuple(p["rgba"])})
                      for p in d["parts"])
        return cls(**{**d, "size": tuple(d["size"]), "o_prime": tuple(d["o_prime"]),
                      "floor_rgb": tuple(tuple(c) for c in d["floor_rgb"]), "wall_rgba": tuple(d["wall_rgba"]),
                      "surface_rgba": tuple(d["surface_rgba"]), "base_rgba": tuple(d["base_rgba"]), "parts": parts})


def keep_out_in_room(T: Rigid) -> tuple[float, float, float, float]:
    """The keep-out box in room coordinates (axis aligned: O' turns by multiples of 90 degrees)."""
    x0, x1, y0, y1 = KEEP_OUT
    corners = apply_point(T, np.array([[x0, y0, 0], [x1, y0, 0], [x1, y1, 0], [x0, y1, 0]], float))
    return corners[:, 0].min(), corners[:, 0].max(), corners[:, 1].min(), corners[:, 1].max()


def _overlaps(a: tuple[float, float, float, float], b: tuple[float, float, float, float]) -> bool:
    return a[0] < b[1] and b[0] < a[1] and a[2] < b[3] and b[2] < a[3]


def footprint(p: Part) -> tuple[float, float, float, float]:
    """The part's xy bounding box in room coordinates."""
    if p.shape == "box":
        c, s = abs(math.cos(p.yaw)), abs(math.sin(p.yaw))
        hx, hy = c * p.size[0] + s * p.size[1], s * p.size[0] + c * p.size[1]
    else:
        hx = hy = p.size[0]
    return p.pos[0] - hx, p.pos[0] + hx, p.pos[1] - hy, p.pos[1] + hy


def _colour(rng: np.random.Generator, lo: float = 0.25, hi: float = 0.9) -> tuple[float, float, float, float]:
    return (*(round(float(v), 4) for v in rng.uniform(lo, hi, 3)), 1.0)


def generate_room(seed: int) -> Room:
    """The room of `seed`: deterministic, and every part clear of the task's keep-out box."""
    rng = np.random.default_rng([seed, 0x5C0E])
    size_x, size_y = float(rng.uniform(4.0, 7.0)), float(rng.uniform(3.8, 6.5))
    wall_h = float(rng.uniform(2.5, 3.1))
    h = float(rng.uniform(*SURFACE_HEIGHT_RANGE))
    yaw = float(rng.integers(4)) * math.pi / 2
    style = "wall" if rng.random() < 0.6 else "island"
    # Place O' so that the keep-out box fits inside the walls; a "wall" room pushes it against the wall the
    # robot faces.
    probe = frame(np.zeros(3), yaw)
    x0, x1, y0, y1 = keep_out_in_room(o_to_o_prime(probe))
    margin = 0.05
    lo = np.array([margin - x0, margin - y0])
    hi = np.array([size_x - margin - x1, size_y - margin - y1])
    if np.any(hi < lo):  # the room is too small for this turn: widen it
        grow = np.maximum(lo - hi, 0) + 0.2
        size_x, size_y = size_x + grow[0], size_y + grow[1]
        hi = hi + grow
    xy = rng.uniform(lo, hi)
    if style == "wall":
        facing = np.round([math.cos(yaw), math.sin(yaw)]).astype(int)
        axis = int(np.argmax(np.abs(facing)))
        xy[axis] = hi[axis] if facing[axis] > 0 else lo[axis]
    room = dict(seed=int(seed), size=(round(size_x, 4), round(size_y, 4), round(wall_h, 4)), surface_height=round(h, 4),
                o_prime=(round(float(xy[0]), 4), round(float(xy[1]), 4), round(h, 4)), yaw=yaw, style=style)
    T = o_to_o_prime(frame(np.array(room["o_prime"]), yaw))
    keep = keep_out_in_room(T)
    wall_rgba = _colour(rng, 0.55, 0.95)
    parts = list(_walls(size_x, size_y, wall_h, wall_rgba))
    parts += _furniture(rng, size_x, size_y, wall_h, keep)
    return Room(**room, floor_rgb=(_colour(rng, 0.3, 0.75)[:3], _colour(rng, 0.3, 0.75)[:3]), wall_rgba=wall_rgba,
                surface_rgba=_colour(rng, 0.35, 0.9), base_rgba=_colour(rng, 0.2, 0.8), parts=tuple(parts))


def _walls(sx: float, sy: float, h: float, rgba) -> list[Part]:
    t = WALL_THICKNESS / 2
    return [Part("box", (sx / 2, -t, h / 2), (sx / 2 + 2 * t, t, h / 2), rgba, kind="wall"),
            Part("box", (sx / 2, sy + t, h / 2), (sx / 2 + 2 * t, t, h / 2), rgba, kind="wall"),
            Part("box", (-t, sy / 2, h / 2), (t, sy / 2, h / 2), rgba, kind="wall"),
            Part("box", (sx + t, sy / 2, h / 2), (t, sy / 2, h / 2), rgba, kind="wall")]


def _along_wall(rng, sx: float, sy: float, depth: float, width: float) -> tuple[float, float, float]:
    """A centre (x, y) and yaw for something `width` wide and `depth` deep standing against a random wall."""
    wall = int(rng.integers(4))
    if wall in (0, 1):  # walls along x, at y = 0 and y = sy
        x = float(rng.uniform(width / 2, max(width / 2, sx - width / 2)))
        return x, depth / 2 if wall == 0 else sy - depth / 2, 0.0
    y = float(rng.uniform(width / 2, max(width / 2, sy - width / 2)))
    return depth / 2 if wall == 2 else sx - depth / 2, y, math.pi / 2


def _furniture(rng, sx: float, sy: float, wall_h: float, keep) -> list[Part]:
    out: list[Part] = []
    taken: list[tuple[float, float, float, float]] = [keep]

    def place(parts: list[Part]) -> bool:
        boxes = [footprint(p) for p in parts]
        if any(_overlaps(b, t) for b in boxes for t in taken):
            return False
        taken.extend(boxes)
        out.extend(parts)
        return True

    for _ in range(int(rng.integers(2, 5))):  # base cabinets, some with wall cabinets above
        w, d, ch = float(rng.uniform(0.6, 2.4)), 0.6, float(rng.uniform(0.85, 0.95))
        x, y, yaw = _along_wall(rng, sx, sy, d, w)
        hw, hd = (w / 2, d / 2) if yaw == 0 else (d / 2, w / 2)
        body, top = _colour(rng, 0.2, 0.85), _colour(rng, 0.3, 0.95)
        group = [Part("box", (x, y, ch / 2 - 0.02), (hw, hd, ch / 2 - 0.02), body, kind="cabinet"),
                 Part("box", (x, y, ch - 0.02), (hw + 0.01, hd + 0.01, 0.02), top, kind="cabinet")]
        for k in range(int(rng.integers(0, 4))):  # things on the counter
            px = x + float(rng.uniform(-0.8, 0.8)) * (hw - 0.08)
            py = y + float(rng.uniform(-0.8, 0.8)) * (hd - 0.08)
            r, hh = float(rng.uniform(0.03, 0.07)), float(rng.uniform(0.04, 0.15))
            group.append(Part("cylinder" if k % 2 else "box", (px, py, ch + hh), (r, hh) if k % 2 else (r, r, hh),
                              _colour(rng, 0.1, 1.0), kind="clutter"))
        if rng.random() < 0.5:
            uh, ud = float(rng.uniform(0.6, 0.8)), 0.35
            ux, uy = x, y  # against the same wall as the cabinet below
            if yaw == 0:
                uy = ud / 2 if y < sy / 2 else sy - ud / 2
            else:
                ux = ud / 2 if x < sx / 2 else sx - ud / 2
            ext = (hw, ud / 2, uh / 2) if yaw == 0 else (ud / 2, hd, uh / 2)
            group.append(Part("box", (ux, uy, min(wall_h - 0.3, 1.5 + uh / 2)), ext, body, kind="cabinet"))
        place(group)
    for _ in range(int(rng.integers(1, 3))):  # shelves: two sides, boards, a back
        w, d, sh = float(rng.uniform(0.7, 1.3)), 0.35, float(rng.uniform(1.6, min(2.3, wall_h - 0.1)))
        x, y, yaw = _along_wall(rng, sx, sy, d, w)
        wood = _colour(rng, 0.3, 0.8)
        local = [((0.0, 0.0, sh / 2), (w / 2, d / 2, sh / 2), "back")]
        group = []
        c, s = math.cos(yaw), math.sin(yaw)
        boards = int(rng.integers(3, 6))
        for i in range(boards + 1):
            local.append(((0.0, 0.0, 0.02 + i * (sh - 0.04) / boards), (w / 2, d / 2, 0.015), "board"))
        for (lx, ly, lz), ext, what in local:
            if what == "back":  # one thin slab standing for the back and sides
                ext = (w / 2, 0.015, sh / 2)
            group.append(Part("box", (x + c * lx - s * ly, y + s * lx + c * ly, lz), ext, wood, yaw=yaw, kind="shelf"))
        for i in range(boards):  # books and boxes on the boards
            z = 0.035 + i * (sh - 0.04) / boards
            for _ in range(int(rng.integers(0, 4))):
                u, bh = float(rng.uniform(-0.4, 0.4)) * w, float(rng.uniform(0.06, 0.14))
                group.append(Part("box", (x + c * u, y + s * u, z + bh), (0.04, 0.1, bh), _colour(rng, 0.1, 0.95),
                                  yaw=yaw, kind="clutter"))
        place(group)
    for _ in range(int(rng.integers(3, 8))):  # floor clutter: boxes, bins, plants
        x, y = float(rng.uniform(0.3, sx - 0.3)), float(rng.uniform(0.3, sy - 0.3))
        kind = int(rng.integers(3))
        if kind == 0:
            e = tuple(float(v) for v in rng.uniform(0.1, 0.3, 3))
            group = [Part("box", (x, y, e[2]), e, _colour(rng), yaw=float(rng.uniform(0, math.pi)))]
        elif kind == 1:
            r, hh = float(rng.uniform(0.1, 0.2)), float(rng.uniform(0.15, 0.35))
            group = [Part("cylinder", (x, y, hh), (r, hh), _colour(rng))]
        else:
            r, hh = float(rng.uniform(0.1, 0.18)), float(rng.uniform(0.12, 0.22))
            green = (round(float(rng.uniform(0.1, 0.3)), 4), round(float(rng.uniform(0.45, 0.75)), 4), 0.2, 1.0)
            group = [Part("cylinder", (x, y, hh), (r, hh), _colour(rng, 0.3, 0.7)),
                     Part("sphere", (x, y, 2 * hh + r * 1.3), (r * 1.6,), green)]
        place(group)
    return out


def room_seed_for(room: str | int | None, episode_seed: int | None) -> int | None:
    """`--room`: None (tabletop), a seed, or "random": each episode its own room, drawn from its seed."""
    if room is None:
        return None
    if isinstance(room, int):
        return room
    if str(room).strip().lower() == "random":
        return int(np.random.default_rng([0 if episode_seed is None else episode_seed, 0x200A]).integers(1 << 31))
    try:
        return int(room)
    except ValueError:
        raise ValueError(f"--room takes a seed (an integer) or 'random', not {room!r}") from None
