"""Image parts of chat messages (OpenAI chat-completions `image_url` parts carrying a PNG as a data URL), and
their storage beside a recording or cache entry: the JSON keeps a reference (the PNG's sha256), the PNG goes to
a file named by it, so records stay small and readable and the picture can be opened as it was sent."""

from __future__ import annotations

import base64
import hashlib
from pathlib import Path
from typing import Any

PNG_PREFIX = "data:image/png;base64,"
REF_PREFIX = "sha256:"  # a stored image part's url: "sha256:<hex>", the PNG in <images dir>/<hex>.png
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def image_part(png: bytes) -> dict[str, Any]:
    """One image content part with `png` inline."""
    if not png.startswith(PNG_MAGIC):
        raise ValueError("image_part takes PNG bytes")
    return {"type": "image_url", "image_url": {"url": PNG_PREFIX + base64.b64encode(png).decode("ascii")}}


def with_image(text: str, png: bytes | None, caption: str = "") -> str | list[dict[str, Any]]:
    """A user message's content: `text` alone without a picture, else the text, the caption and the picture as
    parts (the text first, so its words are the same with or without the picture)."""
    if png is None:
        return text
    parts: list[dict[str, Any]] = [{"type": "text", "text": text}]
    if caption:
        parts.append({"type": "text", "text": caption})
    return parts + [image_part(png)]


def text_of(content: Any) -> str:
    """The words of a message's content: a string, or its text parts joined by blank lines."""
    if isinstance(content, list):
        return "\n\n".join(str(p.get("text", "")) for p in content if isinstance(p, dict) and p.get("type") == "text")
    return "" if content is None else str(content)


def pngs(messages: list[dict[str, Any]]) -> list[bytes]:
    """The PNGs of every inline image part of `messages`, in order."""
    out = []
    for m in messages:
        content = m.get("content")
        for p in content if isinstance(content, list) else []:
            url = p.get("image_url", {}).get("url", "") if isinstance(p, dict) else ""
            if isinstance(url, str) and url.startswith(PNG_PREFIX):
                out.append(base64.b64decode(url[len(PNG_PREFIX):]))
    return out


def has_images(messages: list[dict[str, Any]]) -> bool:
    return any(isinstance(p, dict) and p.get("type") == "image_url"
               for m in messages if isinstance(m.get("content"), list) for p in m["content"])


def sha256(png: bytes) -> str:
    return hashlib.sha256(png).hexdigest()


def stored(obj: Any, images_dir: Path) -> Any:
    """`obj` (a request, nested dicts and lists) with every inline PNG written to `images_dir/<sha256>.png` and
    its URL replaced by "sha256:<hex>"; `obj` itself is not changed. Written once per picture."""
    if isinstance(obj, dict):
        url = obj.get("url")
        if isinstance(url, str) and url.startswith(PNG_PREFIX) and len(obj) == 1:
            png = base64.b64decode(url[len(PNG_PREFIX):])
            digest = sha256(png)
            path = Path(images_dir) / f"{digest}.png"
            if not path.is_file():
                path.parent.mkdir(parents=True, exist_ok=True)
                tmp = path.with_suffix(".tmp")
                tmp.write_bytes(png)
                tmp.replace(path)  # a reader never sees half a picture
            return {"url": REF_PREFIX + digest}
        return {k: stored(v, images_dir) for k, v in obj.items()}
    if isinstance(obj, list):
        return [stored(v, images_dir) for v in obj]
    return obj


def restored(obj: Any, images_dir: Path) -> Any:
    """The inverse of `stored`: references replaced by the PNGs inline again, as they were sent."""
    if isinstance(obj, dict):
        url = obj.get("url")
        if isinstance(url, str) and url.startswith(REF_PREFIX) and len(obj) == 1:
            png = (Path(images_dir) / f"{url[len(REF_PREFIX):]}.png").read_bytes()
            return {"url": PNG_PREFIX + base64.b64encode(png).decode("ascii")}
        return {k: restored(v, images_dir) for k, v in obj.items()}
    if isinstance(obj, list):
        return [restored(v, images_dir) for v in obj]
    return obj


def images_dir_of(recording: Path) -> Path:
    """Where a recording's pictures go: `run.jsonl` -> `run.images/`."""
    recording = Path(recording)
    return recording.with_name(recording.stem + ".images")
