"""`hgen assets ...`: the robot model files (fetch, where) and the object library (list, show, import)."""

from __future__ import annotations

from pathlib import Path

import typer

from humanoidgen.assets import robot_files as rf

app = typer.Typer(
    help=(
        "Download and locate the Unitree H1-2 robot model (URDF, MJCF, meshes; Apache-2.0).\n\n"
        "The files are not part of the package: `hgen assets fetch` downloads them once "
        "(about 49 MB) and checks each against the sha256 sums shipped with humanoidgen. "
        f"Lookup order: ${rf.ENV_ASSETS}, then the user cache (${rf.ENV_CACHE}, "
        "$XDG_CACHE_HOME/humanoidgen/assets or ~/.cache/humanoidgen/assets), then "
        "../shared/assets beside a source checkout.\n\n"
        "Example: hgen assets fetch && hgen assets where"
    ),
    no_args_is_help=True,
)


def _fail(message: str) -> None:
    # Red message, exit 1, no traceback: these errors are the user's to act on, not bugs.
    typer.secho(message, fg=typer.colors.RED, err=True)
    raise typer.Exit(code=1)


@app.command()
def fetch(
    dest: Path | None = typer.Option(
        None,
        "--dest",
        help="Assets root to fill (the files go to DEST/h1_2/). Default: the user cache.",
        file_okay=False,
    ),
    base_url: str | None = typer.Option(
        None,
        "--base-url",
        help=(
            "Address of a folder serving the h1_2 files (a mirror, or file:///path/h1_2). "
            "Default: the robot file's model.source (Unitree's GitHub repository at a pinned commit; "
            "`hgen robots show`)."
        ),
        show_default=False,
    ),
    progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar."),
    objects: bool = typer.Option(False, "--objects", help="Also fetch the object library: real meshes from pip "
                                 "and Debian packages, checked against their sha256 and imported (docs/guides/objects.md)."),
    include_noncommercial: bool = typer.Option(
        False, "--include-noncommercial",
        help="Also fetch library models whose licence forbids commercial use (the 26 HOPE meshes, CC BY-NC-SA "
             "4.0); by default only permissively licensed ones (MIT, zlib, CC-BY) are fetched."),
    only: str | None = typer.Option(None, "--only", help="Library models or families to fetch, comma-separated."),
    robot: str | None = typer.Option(None, "--robot", help="The robot whose model files to fetch (`hgen robots "
                                     "list`; with the robot whose hands it carries). Default: $HGEN_ROBOT, else "
                                     "h1_2_inspire.", show_default=False),
) -> None:
    """Download the robot files and verify every one against its sha256.

    Files already present and correct are skipped, so re-running resumes an interrupted
    download. A file with a wrong hash is discarded and the command fails.

    Example: hgen assets fetch --dest ./assets --base-url http://mirror.local/h1_2
    Example: hgen assets fetch --robot g1_inspire  (the G1 out of the mjlab 1.6.0 wheel from PyPI; --base-url
    ./mjlab-1.6.0-py3-none-any.whl takes it from a wheel already downloaded)
    """
    from humanoidgen.robots import RobotFileError, default_robot, load_robot

    try:
        chosen = default_robot() if robot is None else load_robot(robot)
        root = rf.fetch(dest, base_url=base_url, progress=progress, robot=chosen)
        reports = [(r, rf.verify(root / r.data.model.folder, rf.parse_sums(r.sums_path.read_text("utf-8"))))
                   for r in chosen.robots_needed()]
    except (rf.AssetsError, RobotFileError, OSError, ValueError) as exc:
        _fail(f"hgen assets fetch failed: {exc}")
        return
    for r, report in reports:
        folder = root / r.data.model.folder
        if not report.is_complete:  # defensive: fetch verified each file as it arrived
            _fail(f"files under {folder} changed during the fetch; run it again.")
        typer.echo(f"Robot files of {r.name} are in {folder}: all {report.total} verified (sha256).")
    if objects:
        from humanoidgen.objects.imported.fetch import FetchError_, fetch_library

        try:
            lib = fetch_library(root, rf.cache_dir().parent / "wheels", include_noncommercial=include_noncommercial,
                                only=set(only.split(",")) if only else None, log=typer.echo)
        except FetchError_ as exc:
            _fail(f"hgen assets fetch --objects failed: {exc}")
            return
        typer.echo(f"Object library in {lib.folder}: {len(lib.imported)} imported, {len(lib.kept)} already there"
                   + (f", {len(lib.failed)} failed" if lib.failed else ""))
        for source, n in lib.skipped.items():
            typer.echo(f"Not fetched: {n} models from {source}, a licence that forbids commercial use; "
                       "--include-noncommercial fetches them.")
        if lib.failed:
            _fail("\n".join(lib.failed))
    if dest is not None and root.resolve() != rf.cache_dir().resolve():
        typer.echo(f"To use them, set {rf.ENV_ASSETS}={root.resolve()}")


@app.command()
def where() -> None:
    """Show which assets folder is used and whether every file in it is intact.

    Exits with code 1 when no folder is found or a file is missing or altered.

    Example: HGEN_ASSETS=/data/assets hgen assets where
    """
    try:
        root = rf.resolve_assets_root()
    except rf.AssetsNotFoundError as exc:
        _fail(str(exc))
        return
    robot_dir = root / rf.ROBOT_DIR_NAME
    report = rf.verify(robot_dir)
    typer.echo(f"Assets root: {root}")
    typer.echo(f"Robot MJCF:  {robot_dir / rf.ROBOT_MJCF_NAME}")
    if report.is_complete:
        typer.echo(f"Complete: all {report.total} files verified (sha256).")
        return
    lines = [f"Incomplete: {len(report.ok)} of {report.total} files verified."]
    lines += [f"  missing:    {name}" for name in report.missing]
    lines += [f"  mismatched: {name}" for name in report.mismatched]
    lines.append(f"Run `hgen assets fetch --dest {root}` to repair it.")
    _fail("\n".join(lines))


@app.command("list")
def list_assets() -> None:
    """List the object library: families, models (type_id) and their annotations.

    Example: hgen assets list
    """
    from humanoidgen.objects import library

    for name, fam in sorted(library.families().items()):
        kind = "articulated" if fam.articulated else "static" if getattr(fam, "static", False) else "rigid"
        typer.secho(f"{name} ({kind})", bold=True)
        for m in fam.models():
            ann = fam.annotations(m.type_id)
            typer.echo(f"  type_id {m.type_id}: {m.description}")
            typer.echo(f"    points: {', '.join(p.name for p in ann.points)}")
            typer.echo(f"    axes: {', '.join(a.name for a in ann.axes)}")
            ops = sorted({f"{o.operation}@{o.point}" for o in ann.operations})
            fns = sorted({f"{f.function}@{f.point}" for f in ann.functions})
            typer.echo(f"    operations: {', '.join(ops) or '-'}; functions: {', '.join(fns) or '-'}")
    from humanoidgen.objects.hands import hand_axes, hand_points

    typer.secho("hands: left_hand, right_hand", bold=True)
    for side in ("left", "right"):
        typer.echo(f"  {side} points: {', '.join(hand_points(side))}")
        typer.echo(f"  {side} axes: {', '.join(hand_axes(side))}")


@app.command()
def show(
    name: str = typer.Argument(..., help="An object type (see `hgen assets list`), or left_hand / right_hand."),
    type_id: int = typer.Option(0, "--type-id", help="Which model of the family."),
    model: str | None = typer.Option(None, "--model", help="A model by name (an imported one) or type_id."),
    out: Path = typer.Option(Path("asset.png"), "--out", "-o", help="PNG file to write."),
) -> None:
    """Render an asset with its annotated key points and axes drawn on it.

    Articulated objects are shown at openness 0.3 and 1. Hands show grasp, pinch and press points and axes.

    Example: hgen assets show drawer --out drawer.png
    """
    import os

    os.environ.setdefault("MUJOCO_GL", "egl")
    from humanoidgen.objects.show import show_hand, show_object

    try:
        if name in ("left_hand", "right_hand"):
            img = show_hand(name.split("_")[0])
        else:
            if model is not None:
                from humanoidgen.objects.library import model_named

                type_id = model_named(name, model).type_id
            img = show_object(name, type_id)
    except (KeyError, ValueError, rf.AssetsError) as exc:
        _fail(str(exc).strip("'\""))
        return
    out.parent.mkdir(parents=True, exist_ok=True)
    img.save(out)
    typer.echo(f"wrote {out}")


@app.command("import")
def import_model(
    path: Path = typer.Argument(..., help="A mesh (OBJ, STL, PLY, GLB/glTF, MuJoCo .msh) or an articulated model "
                                          "(URDF, MJCF)."),
    family: str = typer.Option(..., "--family", help="The family it is a model of (see `hgen assets list`)."),
    name: str | None = typer.Option(None, "--name", help="The model's name (default: the file's name)."),
    scale: float | None = typer.Option(None, "--scale", help="Multiply the file's coordinates (0.001: mm)."),
    size: float | None = typer.Option(None, "--size", help="Scale to this largest extent (m)."),
    fit_family: bool = typer.Option(False, "--fit-family", help="Then scale it into the size range of the "
                                    "family's own models (largest extent), the sizes its tasks were written for."),
    up: str | None = typer.Option(None, "--up", help="The file's up axis: x, y, z, -x, -y, -z "
                                                     "(default z; y for glTF)."),
    mass: float | None = typer.Option(None, "--mass", help="Mass (kg)."),
    density: float | None = typer.Option(None, "--density", help="Density (kg/m^3) of the solid."),
    out: Path | None = typer.Option(None, "--out", help="Models folder (default: the first of $HGEN_FAMILIES_PATH)."),
    allow_open: bool = typer.Option(False, "--allow-open", help="Accept a mesh that is not watertight."),
    force: bool = typer.Option(False, "--force", help="Replace a model of that name."),
    preview: bool = typer.Option(True, "--preview/--no-preview", help="Write preview.png beside the model."),
    texture: Path | None = typer.Option(None, "--texture", help="An image for a mesh whose file has texture "
                                        "coordinates but names no image (a MuJoCo .msh: its MJCF names it)."),
) -> None:
    """Import a model file: a model folder with collision parts and annotations transferred from the family.

    Writes OUT/FAMILY/NAME/ atomically (a failed import leaves nothing). Points whose transfer is unsure are
    listed and written to annotations.override.yaml beside the model for a manual fix.

    Example: hgen assets import mug.obj --family cup --name my_mug --out ~/hgen_models
    """
    from humanoidgen.objects.imported.formats import ImportError_
    from humanoidgen.objects.imported.geometry import Units
    from humanoidgen.objects.imported.importer import ImportRequest
    from humanoidgen.objects.imported.importer import import_model as run_import
    from humanoidgen.objects.imported.model_file import ModelFolderError

    if up is not None and up not in ("x", "y", "z", "-x", "-y", "-z"):
        _fail(f"--up must be one of x, y, z, -x, -y, -z, got {up!r}")
    if scale is not None and size is not None:
        _fail("give --scale or --size, not both")
    if (scale is not None and scale <= 0) or (size is not None and size <= 0):
        _fail("--scale and --size must be positive")
    req = ImportRequest(path=path, family=family, name=name, units=Units(scale, size), up=up, mass=mass,
                        density=density, out=out, allow_open=allow_open, force=force, preview=preview,
                        fit_family=fit_family, texture=texture)
    try:
        report = run_import(req)
    except (ImportError_, ModelFolderError, rf.AssetsError) as exc:
        _fail(f"hgen assets import: {exc}")
        return
    info = report.model.info
    typer.echo(f"imported {info.family} model {info.name!r} (type_id {info.type_id}) into {report.folder}")
    typer.echo(f"  {len(info.links)} link(s), {sum(l.collision_parts for l in info.links)} collision parts, "
               f"mass {sum(l.mass for l in info.links):.3f} kg, scale {info.scale:g}, up {info.up}")
    if report.transfer is not None:
        typer.echo(f"  annotations transferred in {report.transfer.seconds:.2f} s; confidence per point:")
        for p in report.transfer.points:
            typer.echo(f"    {p.name:<14} {p.confidence:.2f}  ({p.rule})")
    for w in report.warnings:
        typer.secho(f"  warning: {w}", fg=typer.colors.YELLOW, err=True)
    typer.echo(f"  use it: --model {info.family}={info.name}  (or type_id {info.type_id}); "
               f"picture: {report.folder / 'preview.png'}")
