"""`hgen assets import`: a model file in, a model folder out (model_file.py), atomically: everything is
written into a hidden folder beside the target and renamed into place only when all of it is there, so a
failed import leaves nothing behind."""

from __future__ import annotations

import hashlib
import shutil
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import trimesh
import yaml

from humanoidgen.objects.imported import model_file as mf
from humanoidgen.objects.imported.collision import coarse, convex_parts
from humanoidgen.objects.imported.formats import ImportError_, SourceModel
from humanoidgen.objects.imported.registry import format_for
from humanoidgen.objects.imported.sizing import family_size_range, fit_note
from humanoidgen.objects.imported.geometry import UpAxis, Units, check_mesh, fit_factor, to_metres, up_rotation
from humanoidgen.objects.imported.transfer import LOW_CONFIDENCE, TransferResult, transfer


MAX_TEXTURE = 1024


@dataclass(frozen=True)
class ImportRequest:
    path: Path
    family: str
    name: str | None = None
    units: Units = Units()
    up: UpAxis | None = None  # None: the format's convention (z; y for glTF)
    mass: float | None = None
    density: float | None = None
    out: Path | None = None
    description: str | None = None
    allow_open: bool = False
    force: bool = False
    type_id: int | None = None
    preview: bool = True  # render preview.png (hgen assets show's picture) into the folder
    package: str | None = None  # for the library: where the file came from, and under what licence
    licence: str | None = None
    sha256: str | None = None  # the library's digest of the files (default: the file's own sha256)
    fit_family: bool = False  # scale the model into its family's size range (sizing.py)
    # an image for a mesh whose file has texture coordinates but names no image (MuJoCo's .msh names none: the
    # MJCF that uses it does)
    texture: Path | None = None


@dataclass
class ImportReport:
    folder: Path
    model: mf.ImportedModel
    transfer: TransferResult | None
    warnings: list[str]


def import_model(req: ImportRequest) -> ImportReport:
    """Import `req.path` as a model of `req.family`; raises ImportError_ (one line) for anything unusable."""
    from humanoidgen.objects import library

    path = Path(req.path)
    if not path.is_file():
        raise ImportError_(f"{path}: no such file")
    fams = library.families()
    if req.family not in fams:
        raise ImportError_(f"unknown family {req.family!r}; known: {', '.join(sorted(fams))}")
    fmt = format_for(path)
    name = req.name or path.stem.replace(" ", "_")
    root = mf.models_root(req.out)
    target = root / req.family / name
    if target.exists() and not req.force:
        raise ImportError_(f"{target} already exists: pass --force to replace it, or --name another")
    src = fmt.load(path)
    if req.texture is not None:
        src.texture = _given_texture(src, Path(req.texture), path)
    if req.fit_family:
        req = replace(req, units=replace(req.units, fit=family_size_range(req.family)))
    articulated = fams[req.family].articulated
    if src.articulated != articulated:
        want = "an articulated model (URDF/MJCF with a joint)" if articulated else "a rigid mesh"
        raise ImportError_(f"{path}: family {req.family} needs {want}; the file has "
                           f"{'joints' if src.articulated else 'no joint'}")
    type_id = req.type_id if req.type_id is not None else _type_id(req.family, name, root)
    made = [d for d in (root, root / req.family) if not d.exists()]
    tmp = Path(tempfile.mkdtemp(prefix=f".{name}.", suffix=".importing", dir=_mkdir(root / req.family)))
    try:
        if articulated:
            from humanoidgen.objects.imported.parts import import_articulated

            info, ann, tr, arrays, warnings = import_articulated(src, req, name, type_id, path)
        else:
            info, ann, tr, arrays, warnings = _import_rigid(src, req, name, type_id, path, tmp)
        np.savez_compressed(tmp / mf.MESH_FILE, **arrays)
        mf.save_model_file(info, tmp)
        (tmp / mf.ANNOTATION_FILE).write_text(yaml.safe_dump(ann.model_dump(mode="json"), sort_keys=False))
        if tr is not None:
            _write_transfer(tr, tmp, warnings)
        if req.preview:
            _preview(tmp, warnings)
        tmp.chmod(0o755)
        _commit(tmp, target)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        for d in reversed(made):  # the folders this import made, now empty again
            if d.is_dir() and not any(d.iterdir()):
                d.rmdir()
        raise
    return ImportReport(target, mf.read_model(target), tr, warnings)


def _given_texture(src: SourceModel, image: Path, path: Path):
    """The image given for a rigid mesh with texture coordinates, opened (PIL)."""
    from PIL import Image

    mesh = src.links[0].mesh
    uv = getattr(mesh.visual, "uv", None)
    if src.articulated or uv is None or len(uv) != len(mesh.vertices):
        raise ImportError_(f"{path}: --texture needs a rigid mesh with a texture coordinate per vertex; "
                           "this file has none")
    try:
        return Image.open(image)
    except (OSError, ValueError) as exc:
        raise ImportError_(f"{image}: not a readable image ({type(exc).__name__})") from None


def _preview(folder: Path, warnings: list[str]) -> None:
    import os

    os.environ.setdefault("MUJOCO_GL", "egl")
    from humanoidgen.objects.show import show_imported

    try:
        show_imported(mf.read_model(folder)).save(folder / mf.PREVIEW_FILE)
    except Exception as exc:  # no renderer here: the model is still usable
        warnings.append(f"no picture ({type(exc).__name__}: {' '.join(str(exc).split())[:100]})")


def _type_id(family: str, name: str, root: Path) -> int:
    """A re-import keeps its type_id; a new model takes the next free one, here and in the search path."""
    here = {}
    for f in sorted((root / family).glob(f"*/{mf.MODEL_FILE}")):
        try:
            here[f.parent.name] = mf.read_model(f.parent).info.type_id
        except (mf.ModelFolderError, ValueError):
            continue
    if name in here:
        return here[name]
    for m in mf.imported_models(family):
        if m.info.name == name:
            return m.info.type_id
    return mf.next_type_id(family, set(here.values()))


def _mkdir(p: Path) -> Path:
    p.mkdir(parents=True, exist_ok=True)
    return p


def _commit(tmp: Path, target: Path) -> None:
    old = None
    if target.exists():
        old = target.with_name(f".{target.name}.replaced")
        shutil.rmtree(old, ignore_errors=True)
        target.rename(old)
    tmp.rename(target)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def upright_mesh(mesh: trimesh.Trimesh, req: ImportRequest, default_up: str, where: str) -> tuple[trimesh.Trimesh,
                                                                                                   float, str]:
    """The mesh in metres with its up axis on +z (the scale and the up axis used), in the size range of
    `req.units.fit` if there is one."""
    check_mesh(mesh, where, req.allow_open)
    up = req.up or default_up
    factor = to_metres(mesh, req.units, where)
    factor *= fit_factor(float(np.max(mesh.extents)) * factor, req.units.fit)
    out = trimesh.Trimesh(np.asarray(mesh.vertices, float) * factor @ up_rotation(up).T, mesh.faces,
                          visual=mesh.visual, process=False)
    return out, factor, up



def _import_rigid(src: SourceModel, req: ImportRequest, name: str, type_id: int, path: Path, tmp: Path):
    from humanoidgen.objects.rigid import RIGID_FAMILIES

    where = str(path)
    mesh, factor, up = upright_mesh(src.links[0].mesh, req, src.default_up, where)
    fitted = factor / to_metres(src.links[0].mesh, req.units, where) if req.units.fit is not None else None
    description = req.description or f"{name.replace('_', ' ')} (imported {path.name})"
    tr = transfer(mesh, req.family, type_id, description)
    mesh.apply_transform(tr.transform)
    parts = convex_parts(coarse(mesh))
    template = RIGID_FAMILIES[req.family]._model(0).params
    mass = _mass(mesh, parts, req)
    arrays = {"base_v": np.asarray(mesh.vertices, np.float32), "base_f": np.asarray(mesh.faces, np.int32)}
    textured = src.texture is not None
    if textured:
        arrays["base_uv"] = np.asarray(mesh.visual.uv, np.float32)
        image = src.texture.convert("RGB")
        image.thumbnail((MAX_TEXTURE, MAX_TEXTURE))
        image.save(tmp / "texture.png")
    for k, p in enumerate(parts):
        arrays[f"base_c{k}_v"], arrays[f"base_c{k}_f"] = (np.asarray(p.vertices, np.float32),
                                                          np.asarray(p.faces, np.int32))
    info = mf.ImportedModelFile(
        import_rules=mf.IMPORT_RULES,
        family=req.family, name=name, type_id=type_id, description=description,
        source=mf.SourceInfo(file=path.name, sha256=req.sha256 or _sha256(path),
                             format=path.suffix.lower().lstrip("."),
                             package=req.package, licence=req.licence),
        scale=factor, fitted=fitted, up=up, material=template["material"],
        rgba=_rgba(mesh, template["rgba"], textured),
        links=[mf.LinkFile(name="base", mass=mass, collision_parts=len(parts), textured=textured)])
    warnings = [f"{p.name}: confidence {p.confidence:.2f} ({p.rule}); check it, and fix it in "
                f"{mf.OVERRIDE_FILE} if needed" for p in tr.low()] + tr.notes \
        + fit_note(fitted or 1.0, req.family, req.units.fit)
    if 2 * len(tr.low()) >= len(tr.points) - 1:
        warnings.append(f"most points are unsure: is the object upright? --up names the file's up axis "
                        f"(used: {up}; the default is z, y for glTF)")
    return info, tr.annotations, tr, arrays, warnings


def _mass(mesh: trimesh.Trimesh, parts, req: ImportRequest) -> float:
    """--mass, else --density times the solid's volume, else the template's mass in proportion to the box."""
    from humanoidgen.objects.rigid import RIGID_FAMILIES

    if req.mass is not None:
        if req.mass <= 0:
            raise ImportError_(f"--mass must be positive, got {req.mass}")
        return float(req.mass)
    if req.density is not None:
        vol = float(mesh.volume) if mesh.is_watertight and mesh.volume > 0 else sum(p.volume for p in parts)
        return float(max(req.density * vol, 1e-3))
    fam = RIGID_FAMILIES[req.family]
    geo = fam.geometry(0)
    box = float(np.prod(geo.bmax - geo.bmin))
    return float(np.clip(fam._model(0).params["mass"] * np.prod(mesh.extents) / box, 0.02, 3.0))


def _rgba(mesh: trimesh.Trimesh, fallback, textured: bool) -> tuple[float, float, float, float]:
    if textured:
        return (1.0, 1.0, 1.0, 1.0)
    vis = mesh.visual
    try:
        if isinstance(vis, trimesh.visual.ColorVisuals) and vis.defined:
            c = np.asarray(vis.face_colors, float).mean(0) / 255.0
            return tuple(round(float(x), 3) for x in c)
        if isinstance(vis, trimesh.visual.TextureVisuals):
            c = np.asarray(vis.material.main_color, float) / 255.0
            return tuple(round(float(x), 3) for x in c)
    except (AttributeError, ValueError):
        pass
    return tuple(float(x) for x in fallback)


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _write_transfer(tr: TransferResult, folder: Path, warnings: list[str]) -> None:
    data = {"seconds": round(tr.seconds, 3), "icp_rms_m": round(tr.icp_rms, 5), "yaw_rad": round(tr.yaw, 4),
            "low_confidence_below": LOW_CONFIDENCE, "notes": tr.notes,
            "points": [{"name": p.name, "confidence": p.confidence, "rule": p.rule} for p in tr.points]}
    (folder / mf.TRANSFER_FILE).write_text(yaml.safe_dump(data, sort_keys=False))
    low = tr.low()
    if low:
        lines = ["# Points whose transfer was unsure: check each in preview.png and fix its position (object frame,",
                 "# metres). These values replace the transferred ones when the model is loaded.", "points:"]
        lines += [f"  {p.name}: [{p.position[0]:.4f}, {p.position[1]:.4f}, {p.position[2]:.4f}]"
                  f"  # confidence {p.confidence:.2f}" for p in low]
        (folder / mf.OVERRIDE_FILE).write_text("\n".join(lines) + "\n")
