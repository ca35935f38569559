"""Drawing annotated key points (dots) and key axes (arrows) over a camera image, labelled either in a legend
(`hgen assets show`) or beside each mark (the scene picture of image prompts). One drawing for both, so a
point looks the same wherever it is shown."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from PIL import Image, ImageDraw

from humanoidgen.sim.pointcloud import intrinsics

COLORS = [(230, 25, 75), (60, 180, 75), (0, 130, 200), (245, 130, 48), (145, 30, 180), (70, 240, 240),
          (240, 50, 230), (210, 245, 60), (250, 190, 212), (0, 128, 128)]
CHAR_W, LINE_H = 6, 11  # PIL's default bitmap font: about 6 px a character, 11 px a line
LABEL_PAD = 2


@dataclass(frozen=True)
class Mark:
    """One thing to draw: a point (world, m), and with `axis` (a world direction) an arrow from it."""

    label: str
    point: np.ndarray
    axis: np.ndarray | None = None


def project(points: np.ndarray, cam_pos: np.ndarray, cam_mat: np.ndarray, K: np.ndarray) -> np.ndarray:
    """World points (N, 3) -> pixel coordinates (N, 2) of a MuJoCo camera (looks along -z, y up)."""
    pc = (np.atleast_2d(points) - cam_pos) @ cam_mat  # camera-frame coordinates
    z = -pc[:, 2]
    u = K[0, 2] + K[0, 0] * pc[:, 0] / z
    v = K[1, 2] - K[1, 1] * pc[:, 1] / z
    return np.stack([u, v], axis=1)


def draw_marks(img: Image.Image, marks: list[Mark], frame, axis_len: float, labels: str = "legend") -> Image.Image:
    """Draw `marks` onto `img` (the RGB of `frame`, a cameras.Frame). `labels`: "legend" (a colour key in the
    top-left corner) or "beside" (each label next to its dot or arrow tip, moved until it overlaps no other)."""
    if labels not in ("legend", "beside"):
        raise ValueError(f"labels must be 'legend' or 'beside', not {labels!r}")
    width, height = img.size
    K = intrinsics(width, height, frame.fovy)
    draw = ImageDraw.Draw(img)
    anchors, dots = [], []
    for i, m in enumerate(marks):
        color = COLORS[i % len(COLORS)]
        (u, v), = project(m.point, frame.cam_pos, frame.cam_mat, K)
        anchor = (u, v)
        if m.axis is not None:
            (u2, v2), = project(m.point + axis_len * np.asarray(m.axis), frame.cam_pos, frame.cam_mat, K)
            _arrow(draw, (u, v), (u2, v2), color)
            anchor = (u2, v2)  # an axis is labelled at its tip, where it is told apart from its point
        draw.ellipse([u - 4, v - 4, u + 4, v + 4], fill=color, outline=(0, 0, 0))
        anchors.append(anchor)
        dots.append((u, v))
    if labels == "legend":
        _legend(draw, marks)
    else:
        _beside(draw, marks, anchors, dots, width, height)
    return img


def _arrow(draw: ImageDraw.ImageDraw, a: tuple[float, float], b: tuple[float, float], color) -> None:
    draw.line([a, b], fill=color, width=2)
    d = np.subtract(b, a)
    n = float(np.linalg.norm(d))
    if n < 1e-6:  # an axis along the line of sight: a dot says where it is
        draw.ellipse([a[0] - 2, a[1] - 2, a[0] + 2, a[1] + 2], fill=color)
        return
    d /= n
    side = np.array([-d[1], d[0]])
    head = min(8.0, 0.5 * n)
    base = np.asarray(b) - head * d
    draw.polygon([tuple(b), tuple(base + 0.5 * head * side), tuple(base - 0.5 * head * side)], fill=color)


def _legend(draw: ImageDraw.ImageDraw, marks: list[Mark]) -> None:
    y = 4
    legend_w = 24 + CHAR_W * max((len(m.label) for m in marks), default=0)
    draw.rectangle([0, 0, legend_w, 8 + 12 * len(marks)], fill=(255, 255, 255))
    for i, m in enumerate(marks):
        draw.rectangle([4, y, 12, y + 8], fill=COLORS[i % len(COLORS)])
        draw.text((16, y - 2), m.label, fill=(0, 0, 0))
        y += 12


def _overlaps(box: tuple[float, float, float, float], taken: list[tuple[float, float, float, float]]) -> bool:
    return any(box[0] < t[2] and t[0] < box[2] and box[1] < t[3] and t[1] < box[3] for t in taken)


def label_boxes(sizes: list[tuple[int, int]], anchors: list[tuple[float, float]], width: int,
                height: int, dots: list[tuple[float, float]] = ()) -> list[tuple[float, float, float, float]]:
    """Where each label goes: the first place on rings of growing radius around its anchor (right, left,
    below, above, then the diagonals) that lies in the image and overlaps no label placed before and no dot;
    the nearest place in the image when none is free within reach. Boxes are (x0, y0, x1, y1)."""
    obstacles = [(u - 5, v - 5, u + 5, v + 5) for u, v in dots]
    taken: list[tuple[float, float, float, float]] = []
    for (w, h), (u, v) in zip(sizes, anchors):
        options = []
        for r in (6, 18, 32, 48, 66, 88, 112):
            for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (-1, 1), (1, -1), (-1, -1)):
                x0 = u + dx * r - (w if dx < 0 else 0 if dx > 0 else w / 2)
                y0 = v + dy * r - (h if dy < 0 else 0 if dy > 0 else h / 2)
                options.append((x0, y0, x0 + w, y0 + h))
        inside = [b for b in options if b[0] >= 0 and b[1] >= 0 and b[2] <= width and b[3] <= height]
        free = [b for b in inside if not _overlaps(b, taken) and not _overlaps(b, obstacles)]
        if free:
            box = free[0]
        else:  # crowded: overlap rather than leave the label out; keep it in the image
            x0 = min(max(u + 6, 0), max(width - w, 0))
            y0 = min(max(v - h / 2, 0), max(height - h, 0))
            box = (x0, y0, x0 + w, y0 + h)
        taken.append(box)
    return taken


def _beside(draw: ImageDraw.ImageDraw, marks: list[Mark], anchors: list[tuple[float, float]],
            dots: list[tuple[float, float]], width: int, height: int) -> None:
    sizes = [(CHAR_W * len(m.label) + 2 * LABEL_PAD, LINE_H + 2 * LABEL_PAD) for m in marks]
    boxes = label_boxes(sizes, anchors, width, height, dots)
    for i, (m, (u, v), box) in enumerate(zip(marks, anchors, boxes)):
        color = COLORS[i % len(COLORS)]
        # A leader line from the mark to the nearest point of its label, so a moved label stays attached.
        nx, ny = min(max(u, box[0]), box[2]), min(max(v, box[1]), box[3])
        if abs(nx - u) + abs(ny - v) > 8:
            draw.line([(u, v), (nx, ny)], fill=color, width=1)
        draw.rectangle(box, fill=(255, 255, 255), outline=color)
        draw.text((box[0] + LABEL_PAD, box[1] + LABEL_PAD - 1), m.label, fill=(0, 0, 0))
