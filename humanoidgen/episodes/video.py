"""MP4 videos of episodes, rendered from one camera at the control rate (every `every`-th step)."""

from __future__ import annotations

from pathlib import Path

import imageio.v2 as imageio
import numpy as np

from humanoidgen.sim.cameras import CAMERA_NAMES, CameraRig


class VideoWriter:
    """An episode observer: `attach(env)`, then called after every control step; `close()` finishes the file."""

    def __init__(self, path: Path, camera: str = "front", width: int = 640, height: int = 480, fps: int = 25,
                 control_hz: float = 50.0) -> None:
        if camera not in CAMERA_NAMES:
            raise ValueError(f"unknown camera {camera!r}; cameras: {', '.join(CAMERA_NAMES)}")
        self.path, self.camera, self.width, self.height, self.fps = Path(path), camera, width, height, fps
        self.every = max(1, int(round(control_hz / fps)))
        self._env = None
        self._rig: CameraRig | None = None
        self._writer = None
        self._count = 0

    def open(self) -> None:
        """Start the file, for frames that are rendered elsewhere (`frame`), e.g. streamed by a plan worker."""
        if self._writer is None:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._writer = imageio.get_writer(str(self.path), fps=self.fps, codec="libx264", quality=7,
                                              macro_block_size=8)

    def attach(self, env) -> None:
        """Render from `env` after every control step (trusted code only: dataset replay)."""
        self._env = env
        self._rig = CameraRig(env.model, self.width, self.height, shadows=True)
        self.open()

    def frame(self, rgb: np.ndarray) -> None:
        self._writer.append_data(rgb)

    def __call__(self, _action: np.ndarray) -> None:
        if self._env is None:
            return
        self._count += 1
        if (self._count - 1) % self.every == 0:
            self.frame(self._rig.render(self._env.data, self.camera, depth=False, segmentation=False).rgb)

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()
        if self._rig is not None:
            self._rig.close()
