"""Robot model files: locate, verify and download the Unitree H1-2 description."""

from humanoidgen.assets import robot_files as _robot_files
from humanoidgen.assets.robot_files import (
    AssetsError,
    AssetsNotFoundError,
    ChecksumError,
    FetchError,
    VerifyReport,
    cache_dir,
    expected_sums,
    fetch,
    resolve_assets_root,
    robot_mjcf_path,
    verify,
)

__all__ = [
    "DEFAULT_BASE_URL",
    "ROBOT_DIR_NAME",
    "AssetsError",
    "AssetsNotFoundError",
    "ChecksumError",
    "FetchError",
    "VerifyReport",
    "cache_dir",
    "expected_sums",
    "fetch",
    "resolve_assets_root",
    "robot_mjcf_path",
    "verify",
]


def __getattr__(name: str):
    # DEFAULT_BASE_URL, ROBOT_DIR_NAME: read from the robot file on first use (robot_files.__getattr__).
    if name in ("DEFAULT_BASE_URL", "ROBOT_DIR_NAME"):
        return getattr(_robot_files, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
