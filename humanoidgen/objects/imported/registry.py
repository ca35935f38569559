"""The registry of model file formats, the one place a format is registered: each is one module behind the
`formats.ModelFormat` protocol (mesh_files.py: OBJ, STL, PLY, glTF/GLB; msh_file.py: MuJoCo's binary .msh;
urdf.py; mjcf.py)."""

from __future__ import annotations

from pathlib import Path

from humanoidgen.objects.imported.formats import ImportError_, ModelFormat
from humanoidgen.objects.imported.mesh_files import MESH_FORMATS
from humanoidgen.objects.imported.mjcf import MjcfFormat
from humanoidgen.objects.imported.msh_file import MshFormat
from humanoidgen.objects.imported.urdf import UrdfFormat


def formats() -> list[ModelFormat]:
    """Every format, in the order they are tried (the registry)."""
    return [*MESH_FORMATS, MshFormat(), UrdfFormat(), MjcfFormat()]


def format_for(path: Path) -> ModelFormat:
    suffix = Path(path).suffix.lower()
    for fmt in formats():
        if suffix in fmt.suffixes:
            return fmt
    known = ", ".join(s for f in formats() for s in f.suffixes)
    raise ImportError_(f"{path}: unknown file type {suffix or '(none)'!r}; known: {known}")
