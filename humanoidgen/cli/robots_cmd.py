"""`hgen robots ...`: the robots as data (list, show, check): docs/guides/robots.md."""

from __future__ import annotations

from pathlib import Path

import typer

app = typer.Typer(
    help=(
        "Robots as data: each is a folder under humanoidgen/robots/ holding robot.yaml (model files and their "
        "sha256, arms, hand and its mount, cameras, stand, welds, gains) and naming a hand file "
        "(robots/hands/<hand>.yaml: joints, couplings, key points and axes, postures).\n\n"
        "Example: hgen robots check humanoidgen/robots/h1_2_inspire"
    ),
    no_args_is_help=True,
)


def _fail(message: str) -> None:
    typer.secho(message, fg=typer.colors.RED, err=True)
    raise typer.Exit(code=1)


@app.command("list")
def list_() -> None:
    """The packaged robots (* marks the default one)."""
    from humanoidgen.robots import DEFAULT_ROBOT, RobotFileError, load_robot, robot_names

    for name in robot_names():
        try:
            r = load_robot(name)
        except RobotFileError as exc:
            typer.echo(f"  {name}  (invalid: {exc})")
            continue
        mark = "*" if name == DEFAULT_ROBOT else " "
        typer.echo(f"{mark} {name}  {len(r.action_joints)}-D action, hand {r.hand.data.name}: {r.data.description}")


@app.command()
def show(robot: str = typer.Argument("h1_2_inspire", help="A robot's name, folder or robot.yaml.")) -> None:
    """What a robot file says, as code reads it: the action layout, hands, cameras, where it stands."""
    from humanoidgen.robots import RobotFileError, load_robot

    try:
        r = load_robot(robot)
    except RobotFileError as exc:
        _fail(str(exc))
        return
    d = r.data
    typer.echo(f"{d.name} ({r.path}): {d.description}")
    m = d.model
    typer.echo(f"model: <assets>/{m.folder}/{m.mjcf} (urdf {m.urdf}), sums {m.checksums}, {m.source.license}")
    typer.echo(f"source: {m.source.url.format(commit=m.source.commit)}")
    typer.echo(f"stands: {d.stand.root_body} at {list(d.stand.base_pos)}, feet {d.stand.feet_below_base} m below")
    typer.echo(f"action ({len(r.action_joints)}):")
    for part, slices in (("arm", r.arm_slices), ("hand", r.hand_slices)):
        for side, sl in slices.items():
            typer.echo(f"  {sl.start:>2}-{sl.stop - 1:<2} {side} {part}: {', '.join(r.action_joints[sl])}")
    typer.echo(f"hand: {r.hand.data.name} ({r.hand.path}), postures {', '.join(r.hand.postures)}")
    for side in ("left", "right"):
        typer.echo(f"  {side}: on {r.hand_mount(side)}, frame {r.hand_frame(side)}")
    typer.echo(f"points: {', '.join(p.name for p in r.hand.data.points)}")
    typer.echo(f"axes: {', '.join(a.name for a in r.hand.data.axes)}")
    cams = [f"{c.name} on {c.body or 'the world'}" for c in d.cameras]
    typer.echo(f"cameras: {', '.join(cams)}")
    off = d.no_collision.subtrees + d.no_collision.bodies
    typer.echo(f"welded: {len(d.weld)} joints; no collisions: {', '.join(off)}")


@app.command()
def check(
    path: Path = typer.Argument(..., help="A robot folder or its robot.yaml (or a packaged robot's name)."),
    assets: Path | None = typer.Option(None, "--assets", help="Assets root holding the model files (default: "
                                       "where `hgen assets where` finds them; none found: the files alone)."),
    checksums: bool = typer.Option(True, "--checksums/--no-checksums", help="Check every model file's sha256."),
) -> None:
    """Validate a robot file and its hand file; with the model files, check every name they give, that every
    model joint is an arm, hand or welded joint, the couplings, and every file's sha256. Exit 1 on a problem,
    each printed as one line naming the file and the field."""
    from humanoidgen.robots.check import check as run_check

    root = assets
    if root is None:
        from humanoidgen.assets.robot_files import AssetsError, resolve_assets_root

        try:
            root = resolve_assets_root()
        except AssetsError:
            typer.echo("model files not found: checking the robot and hand files alone")
    problems = run_check(path, root, checksums=checksums)
    for line in problems:
        typer.secho(line, fg=typer.colors.RED, err=True)
    if problems:
        raise typer.Exit(code=1)
    typer.echo(f"{path}: ok" + (f" (model files in {root})" if root is not None else ""))
