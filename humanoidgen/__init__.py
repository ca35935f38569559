"""humanoidgen: bimanual dexterous manipulation tasks and demonstrations for the Unitree H1-2."""

import os

# MuJoCo picks its OpenGL backend when it is first imported. Recorded images are rendered by the process
# that collects (`episodes.image_job`), usually without a display: headless EGL unless the user chose.
os.environ.setdefault("MUJOCO_GL", "egl")

__version__ = "0.1.0"

# `gymnasium.make("humanoidgen/<task>-v0")` works after `import humanoidgen`, without importing gymnasium here.
from humanoidgen import gym_ids as _gym_ids  # noqa: E402

_gym_ids.install()
