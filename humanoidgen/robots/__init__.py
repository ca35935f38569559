"""Robots as data: one folder per robot (`robots/<name>/robot.yaml`, README.md, CHANGELOG.md, the model files'
checksums) and the hands they carry (`robots/hands/<hand>.yaml`). docs/guides/robots.md describes the files."""

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
