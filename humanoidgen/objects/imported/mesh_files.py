"""Rigid mesh files read with trimesh: OBJ, STL, PLY, glTF/GLB (with the texture where the file has one)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

from humanoidgen.objects.imported.formats import ImportError_, SourceLink, SourceModel


@dataclass(frozen=True)
class TrimeshFormat:
    name: str
    suffixes: tuple[str, ...]
    file_type: str
    default_up: str = "z"  # glTF is y-up by its specification

    def load(self, path: Path) -> SourceModel:
        try:
            loaded = trimesh.load(str(path), file_type=Path(path).suffix.lower().lstrip(".") or self.file_type,
                                    process=False)
        except Exception as exc:  # trimesh raises many types for a corrupt file
            raise ImportError_(f"{path}: not a readable {self.name} file ({type(exc).__name__}: "
                               f"{' '.join(str(exc).split())[:120]})") from None
        mesh, texture = _one_mesh(loaded, path)
        return SourceModel([SourceLink("base", mesh)], texture=texture, default_up=self.default_up)


def _one_mesh(loaded, path: Path) -> tuple[trimesh.Trimesh, object | None]:
    """A scene's geometry flattened into one mesh; a texture is kept only where there is exactly one."""
    if isinstance(loaded, trimesh.Scene):
        geoms = [g for g in loaded.dump() if isinstance(g, trimesh.Trimesh)]
        if not geoms:
            raise ImportError_(f"{path}: the file holds no mesh with faces")
        texture = _texture(geoms[0]) if len(geoms) == 1 else None
        mesh = geoms[0] if len(geoms) == 1 else trimesh.util.concatenate(geoms)
        return mesh, texture
    if not isinstance(loaded, trimesh.Trimesh):
        raise ImportError_(f"{path}: the file holds no mesh with faces (a {type(loaded).__name__})")
    return loaded, _texture(loaded)


def _texture(mesh: trimesh.Trimesh):
    vis = mesh.visual
    if isinstance(vis, trimesh.visual.TextureVisuals) and vis.uv is not None and len(vis.uv) == len(mesh.vertices):
        image = getattr(vis.material, "image", None) or getattr(vis.material, "baseColorTexture", None)
        if image is not None and np.isfinite(vis.uv).all():
            return image
    return None


MESH_FORMATS = [
    TrimeshFormat("OBJ", (".obj",), "obj"),
    TrimeshFormat("STL", (".stl",), "stl"),
    TrimeshFormat("PLY", (".ply",), "ply"),
    TrimeshFormat("glTF", (".glb", ".gltf"), "glb", default_up="y"),
]
