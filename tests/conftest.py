import os

# Offscreen rendering through EGL (Mesa's software renderer on CPU machines); must be set before mujoco loads.
os.environ.setdefault("MUJOCO_GL", "egl")

import pytest  # noqa: E402

# torch's triton, imported (by diffusers) after an EGL context exists in the process, segfaults on this Mesa
# (reproduced outside the project: create a MuJoCo GLContext, then `import diffusers.utils.torch_utils`). The
# policy commands import it before they render; the test process renders first, so import it first here.
try:
    import diffusers.utils.torch_utils  # noqa: E402, F401
except ImportError:  # the policy extra is not installed: its tests fail on their own imports
    pass

from humanoidgen.sim.scene import Scene, SceneBuilder  # noqa: E402


@pytest.fixture(scope="session")
def cube_scene() -> Scene:
    """The default scene: the robot at its table and one 4 cm cube."""
    builder = SceneBuilder()
    builder.add_cube(size=0.04, pos=(-0.30, -0.10, 0.02))
    return builder.build()


@pytest.fixture(scope="session")
def empty_scene() -> Scene:
    return SceneBuilder().build()
