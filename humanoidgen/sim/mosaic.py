"""Pictures for people: several camera images tiled into one labelled mosaic."""

from __future__ import annotations

import numpy as np
from PIL import Image, ImageDraw

from humanoidgen.sim.cameras import Frame


def depth_to_rgb(depth: np.ndarray, near: float | None = None, far: float | None = None) -> np.ndarray:
    """Grey-scale picture of a depth image (near = bright); the far background is black."""
    finite = depth[np.isfinite(depth) & (depth < 50)]
    near = float(finite.min()) if near is None and finite.size else (near or 0.0)
    far = float(finite.max()) if far is None and finite.size else (far or 1.0)
    x = np.clip((far - depth) / max(far - near, 1e-6), 0, 1)
    x[~np.isfinite(depth) | (depth >= 50)] = 0
    return np.repeat((x * 255).astype(np.uint8)[..., None], 3, axis=2)


def labels_to_rgb(labels: np.ndarray) -> np.ndarray:
    """A distinct colour per segmentation label (-1, nothing, is black)."""
    rng = np.random.default_rng(7)
    palette = rng.integers(40, 255, size=(int(labels.max(initial=0)) + 2, 3)).astype(np.uint8)
    palette[0] = 0
    return palette[labels + 1]


def frame_image(frame: Frame, modality: str) -> np.ndarray:
    if modality == "rgb":
        return frame.rgb
    if modality == "depth":
        return depth_to_rgb(frame.depth)
    if modality == "segmentation":
        return labels_to_rgb(frame.segmentation)
    raise ValueError(f"unknown modality {modality!r}; use rgb, depth or segmentation")


def mosaic(images: dict[str, np.ndarray], columns: int = 3) -> Image.Image:
    """Tile equally sized images row by row, each with its name in the top-left corner."""
    if not images:
        raise ValueError("no images to tile")
    h, w = next(iter(images.values())).shape[:2]
    rows = -(-len(images) // columns)
    out = Image.new("RGB", (columns * w, rows * h))
    draw = ImageDraw.Draw(out)
    for i, (name, img) in enumerate(images.items()):
        x, y = (i % columns) * w, (i // columns) * h
        out.paste(Image.fromarray(img), (x, y))
        draw.rectangle([x, y, x + 8 + 7 * len(name), y + 16], fill=(0, 0, 0))
        draw.text((x + 4, y + 3), name, fill=(255, 255, 255))
    return out
