"""`hgen`: the humanoidgen command line."""

from __future__ import annotations

import os
from pathlib import Path

import typer

from humanoidgen.cli import (
    assets_cmd,
    dataset_cmd,
    episodes_cmd,
    fast_exit,
    generate_cmd,
    policy_cmd,
    robots_cmd,
    sandbox_cmd,
)
from humanoidgen.cli.robot_option import robot_option, select_robot


class _Program(typer.Typer):
    """The `hgen` program: a command that has written everything (`fast_exit.allow`) ends its process without
    the interpreter's teardown. Only calling the app as a program comes here (the `hgen` script,
    `python -m humanoidgen.cli.main`); typer's test runner invokes the commands without it."""

    def __call__(self, *args, **kwargs):
        try:
            return super().__call__(*args, **kwargs)
        except SystemExit as exc:
            if fast_exit.allowed():
                fast_exit.exit_now(exc.code)
            raise


app = _Program(
    help=(
        "humanoidgen: bimanual dexterous manipulation for the Unitree H1-2 with Inspire hands.\n\n"
        "Start with `hgen assets fetch` (downloads the robot model once), then `hgen render --out scene.png` "
        "to see the robot at its table from all six cameras."
    ),
    no_args_is_help=True,
    pretty_exceptions_show_locals=False,
)
app.add_typer(assets_cmd.app, name="assets")
app.add_typer(robots_cmd.app, name="robots")
app.command()(episodes_cmd.tasks)
app.command()(episodes_cmd.run)
app.command()(episodes_cmd.collect)
app.command()(episodes_cmd.bench)
app.add_typer(dataset_cmd.app, name="dataset")
app.add_typer(generate_cmd.app, name="generate")
app.add_typer(sandbox_cmd.app, name="sandbox")
app.add_typer(policy_cmd.app, name="policy")


@app.command()
def render(
    out: Path = typer.Option(Path("scene.png"), "--out", "-o", help="PNG file to write."),
    width: int = typer.Option(320, min=16, max=1280, help="Width of each camera image (pixels)."),
    height: int = typer.Option(240, min=16, max=960, help="Height of each camera image (pixels)."),
    modality: str = typer.Option("rgb", help="What to show: rgb, depth or segmentation."),
    settle: float = typer.Option(0.5, min=0.0, help="Seconds to simulate before rendering, so objects come to rest."),
    room: int = typer.Option(None, help="Put the table in room SEED (scenes.room), the robot at its work surface."),
    visuals: int = typer.Option(None, help="Randomize the look with this seed (scenes.visuals)."),
    robot: str = robot_option(),
) -> None:
    """Render the default scene (the robot at its table with one cube) from all six cameras as one mosaic.

    Cameras: head (first person, D435-like), left_wrist, right_wrist, front, left, right.

    Example: hgen render --out scene.png --width 640 --height 480 --modality depth
    Example: hgen render --room 7 --out room7.png
    Example: hgen render --robot g1_inspire --out g1.png
    """
    os.environ.setdefault("MUJOCO_GL", "egl")
    select_robot(robot)
    from humanoidgen.assets.robot_files import AssetsError
    from humanoidgen.sim.cameras import CAMERA_NAMES, CameraRig
    from humanoidgen.sim.env import HumanoidEnv
    from humanoidgen.sim.mosaic import frame_image, mosaic
    from humanoidgen.sim.scene import SceneBuilder

    if modality not in ("rgb", "depth", "segmentation"):
        raise typer.BadParameter("use rgb, depth or segmentation", param_hint="--modality")
    from humanoidgen.scenes.dressing import SceneDressing

    dressing = SceneDressing.from_seeds(room, visuals)
    try:
        builder = SceneBuilder(msaa_samples=4, surface_height=dressing.surface_height, dressing=dressing)
    except AssetsError as exc:
        typer.secho(str(exc), fg=typer.colors.RED, err=True)
        raise typer.Exit(1) from None
    builder.add_cube()
    scene = builder.build()
    env = HumanoidEnv(scene)
    for _ in range(int(settle * env.control_hz)):
        env.step(env.init_action())
    with CameraRig(scene.model, width=width, height=height, geom_labels=scene.geom_labels, shadows=True) as rig:
        frames = rig.render_all(env.data)
    images = {name: frame_image(frames[name], modality) for name in CAMERA_NAMES}
    out.parent.mkdir(parents=True, exist_ok=True)
    mosaic(images).save(out)
    where = f", room {room} ({dressing.room.style}, surface {dressing.room.surface_height:.3f} m)" if room is not None else ""
    typer.echo(f"wrote {out} ({len(images)} cameras, {width}x{height} each, {modality}{where})")


if __name__ == "__main__":
    app()
