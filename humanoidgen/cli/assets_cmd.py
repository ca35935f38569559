"""`hgen assets ...`: download and locate the Unitree H1-2 robot model files."""

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
    base_url: str = typer.Option(
        rf.DEFAULT_BASE_URL,
        "--base-url",
        help=(
            "Address of a folder serving the h1_2 files (a mirror, or file:///path/h1_2). "
            f"Default: Unitree's GitHub repository at commit {rf.UPSTREAM_COMMIT[:7]}."
        ),
        show_default=False,
    ),
    progress: bool = typer.Option(True, "--progress/--no-progress", help="Show a progress bar."),
) -> None:
    """Download the robot files and verify every one against its sha256.

    Files already present and correct are skipped, so re-running resumes an interrupted
    download. A file with a wrong hash is discarded and the command fails.

    Example: hgen assets fetch --dest ./assets --base-url http://mirror.local/h1_2
    """
    try:
        root = rf.fetch(dest, base_url=base_url, progress=progress)
        report = rf.verify(root / rf.ROBOT_DIR_NAME)
    except (rf.AssetsError, OSError, ValueError) as exc:
        _fail(f"hgen assets fetch failed: {exc}")
        return
    if not report.is_complete:  # defensive: fetch verified each file as it arrived
        _fail(f"files under {root / rf.ROBOT_DIR_NAME} changed during the fetch; run it again.")
    typer.echo(f"Robot files are in {root / rf.ROBOT_DIR_NAME}")
    typer.echo(f"All {report.total} files verified (sha256).")
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
