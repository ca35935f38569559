"""MuJoCo's binary mesh file (`.msh`, the format MuJoCo read before it read OBJ): four int32 counts (vertices,
normals, texture coordinates, faces), then the vertices (float32 x, y, z), the normals, the texture coordinates
and the faces (int32 triples). MyoSuite ships its YCB gelatin box only in it; robosuite ships each object in it too."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

from humanoidgen.objects.imported.formats import ImportError_, SourceLink, SourceModel

_HEADER = 16  # four int32


def read_msh(path: Path) -> trimesh.Trimesh:
    """The file's triangles; a file whose size is not what its counts say, or that has no faces (MuJoCo then
    takes the vertices' convex hull, which is not the object's shape), is refused in one line."""
    data = Path(path).read_bytes()
    if len(data) < _HEADER:
        raise ImportError_(f"{path}: not a MuJoCo .msh file (shorter than its 16-byte header)")
    nv, nn, nt, nf = (int(x) for x in np.frombuffer(data[:_HEADER], dtype="<i4"))
    want = _HEADER + 12 * nv + 12 * nn + 8 * nt + 12 * nf
    if min(nv, nn, nt, nf) < 0 or len(data) != want:
        raise ImportError_(f"{path}: not a MuJoCo .msh file (its counts {nv}, {nn}, {nt}, {nf} want {want} bytes, "
                           f"it has {len(data)})")
    if nv < 3 or nf < 1:
        raise ImportError_(f"{path}: the file holds no mesh with faces ({nv} vertices, {nf} faces)")
    vertices = np.frombuffer(data, dtype="<f4", count=3 * nv, offset=_HEADER).reshape(-1, 3).astype(float)
    start = _HEADER + 12 * nv + 12 * nn + 8 * nt
    faces = np.frombuffer(data, dtype="<i4", count=3 * nf, offset=start).reshape(-1, 3).astype(np.int64)
    if faces.min() < 0 or faces.max() >= nv:
        raise ImportError_(f"{path}: a face names a vertex the file does not have")
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    if nt == nv:  # one texture coordinate per vertex: kept for an image given with --texture
        uv = np.frombuffer(data, dtype="<f4", count=2 * nt, offset=_HEADER + 12 * nv + 12 * nn).reshape(-1, 2)
        # MuJoCo keeps them as it samples images, v from the top; trimesh's (OBJ's) v runs from the bottom
        mesh.visual = trimesh.visual.TextureVisuals(uv=np.column_stack([uv[:, 0], 1.0 - uv[:, 1]]).astype(float))
    return mesh


def write_msh(mesh: trimesh.Trimesh, path: Path, uv: np.ndarray | None = None) -> None:
    """The mesh as a .msh file (vertices, faces and, given, texture coordinates in trimesh's convention): for
    tests, and to hand a mesh to MuJoCo as it is."""
    v = np.asarray(mesh.vertices, dtype="<f4")
    f = np.asarray(mesh.faces, dtype="<i4")
    t = b"" if uv is None else np.column_stack([uv[:, 0], 1.0 - uv[:, 1]]).astype("<f4").tobytes()
    counts = np.array([len(v), 0, 0 if uv is None else len(uv), len(f)], dtype="<i4")
    Path(path).write_bytes(counts.tobytes() + v.tobytes() + t + f.tobytes())


@dataclass(frozen=True)
class MshFormat:
    name: str = "MuJoCo msh"
    suffixes: tuple[str, ...] = (".msh",)

    def load(self, path: Path) -> SourceModel:
        return SourceModel([SourceLink("base", read_msh(path))])
