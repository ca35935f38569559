"""Robots as data: one folder per robot (`robots/<name>/robot.yaml`, README.md, CHANGELOG.md, the model files'
checksums) and the hands they carry (`robots/hands/<hand>.yaml`). docs/guides/robots.md describes the files.

The names below come from `robots.loader` on first use, so that importing `robots.checksums` (the CLI does, for
every command) does not import pydantic."""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from humanoidgen.robots.loader import (
        DEFAULT_ROBOT,
        Hand,
        Robot,
        RobotFileError,
        default_robot,
        load_robot,
        robot_names,
    )

__all__ = ["DEFAULT_ROBOT", "Hand", "Robot", "RobotFileError", "default_robot", "load_robot", "robot_names"]


def __getattr__(name: str):
    if name in __all__:
        return getattr(importlib.import_module("humanoidgen.robots.loader"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
