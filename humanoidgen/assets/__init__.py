"""Robot model files: locate, verify and download the Unitree H1-2 description."""

from humanoidgen.assets.robot_files import (
    DEFAULT_BASE_URL,
    ROBOT_DIR_NAME,
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
