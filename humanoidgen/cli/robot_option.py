"""`--robot NAME` of the commands that build scenes: the process's robot (`robots.loader.ENV_ROBOT`).

The simulation's modules derive their names from the process's robot when they are first imported, so the
option sets `$HGEN_ROBOT` before any of them is imported (commands import them lazily); the plan worker and
every other child process inherit it."""

from __future__ import annotations

import os
import sys

import typer

HELP = ("The robot: a packaged robot's name (`hgen robots list`), a robot folder or its robot.yaml. "
        "Default: $HGEN_ROBOT, else h1_2_inspire.")


def robot_option() -> typer.models.OptionInfo:
    return typer.Option(None, "--robot", help=HELP, show_default=False)


def select_robot(name: str | None) -> None:
    """Make `name` the process's robot (None: leave it as it is); a bad robot file: its one-line error, exit 1."""
    if name is None:
        return
    from humanoidgen.robots.loader import ENV_ROBOT, RobotFileError, load_robot

    try:
        robot = load_robot(name)
    except RobotFileError as exc:
        typer.secho(str(exc), fg=typer.colors.RED, err=True)
        raise typer.Exit(1) from None
    layout = sys.modules.get("humanoidgen.sim.layout")
    if layout is not None and layout.ROBOT.path != robot.path:
        # Only reachable from code that imported the simulation before the command ran (tests, notebooks).
        typer.secho(f"--robot {name}: this process already built {layout.ROBOT.name}; run a new process",
                    fg=typer.colors.RED, err=True)
        raise typer.Exit(1)
    os.environ[ENV_ROBOT] = str(robot.path)
