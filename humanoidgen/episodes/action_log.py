"""The robot's commands as the plan worker hands them back: every control step's 26-D action (float64, as
the simulator was given it) with the configuration the worker's simulation reached after it.

The worker's simulation is not trusted (plan code shares its process), so nothing here is a result: the
parent re-simulates the actions from the task's scene (`episodes.replay`) and judges that simulation. The
configurations only let it say where the two parted, when a plan changed its simulation by other means
than the robot's commands.

Inside an episode's worker the log streams itself to the parent in chunks while the plan runs, so the
parent replays one chunk while the worker plans the next; the tree search and script generation keep the
whole log since the scene was reset and send it with each judgement (`packed`/`unpack` give it a compact,
JSON-safe form for the search tree's snapshots).
"""

from __future__ import annotations

import base64
import zlib
from collections.abc import Callable

import numpy as np

from humanoidgen.sim.action import ACTION_DIM, validate_action

CHUNK = 50  # control steps per streamed chunk: one second at 50 Hz, about 40 kB with the configurations
STREAM_KEY = "replay"  # stream payloads {"replay": {"actions": (k, 26), "qpos": (k, nq)}}


class ActionLog:
    """A planner `on_step` hook: keeps each action and the configuration after it; `send(chunk)` (if given)
    receives them in chunks of CHUNK as they accumulate and at `flush()`."""

    def __init__(self, data, send: Callable[[dict], None] | None = None) -> None:
        self.data = data  # the worker's MjData
        self.send = send
        self.actions: list[np.ndarray] = []
        self.qpos: list[np.ndarray] = []
        self._sent = 0

    def __call__(self, action: np.ndarray) -> None:
        # Checked as it comes (shape (26,), finite numbers): plan code can call the hook itself, and an odd
        # command (a 27-long array, a column, a string) is refused here with its reason, in the plan's step,
        # instead of breaking the log's next chunk with a message about stacking arrays.
        self.actions.append(validate_action(action).copy())
        self.qpos.append(self.data.qpos.copy())
        if self.send is not None and len(self.actions) - self._sent >= CHUNK:
            self.flush()

    def __len__(self) -> int:
        return len(self.actions)

    def flush(self) -> None:
        """Send what has not been sent yet."""
        if self.send is None or self._sent >= len(self.actions):
            return
        chunk = {"actions": np.stack(self.actions[self._sent:]), "qpos": np.stack(self.qpos[self._sent:])}
        self._sent = len(self.actions)
        self.send({STREAM_KEY: chunk})

    def truncate(self, n: int) -> None:
        """Forget everything after the first `n` steps (a restored snapshot)."""
        del self.actions[n:], self.qpos[n:]
        self._sent = min(self._sent, n)

    def array(self) -> np.ndarray:
        return np.stack(self.actions) if self.actions else np.zeros((0, ACTION_DIM))


def packed(actions: np.ndarray) -> str:
    """(T, 26) float64 actions as a short JSON-safe string (exact: the bytes, compressed)."""
    return base64.b64encode(zlib.compress(np.ascontiguousarray(actions, np.float64).tobytes(), 6)).decode()


def unpack(text: object, max_steps: int) -> np.ndarray:
    """The inverse of `packed`, for text anyone may have written; raises ValueError."""
    if not isinstance(text, str):
        raise ValueError("the action log is not a string")
    try:
        raw = zlib.decompressobj().decompress(base64.b64decode(text, validate=True), max_steps * ACTION_DIM * 8 + 1)
    except (ValueError, zlib.error) as exc:
        raise ValueError(f"the action log is not readable ({exc})") from None
    if len(raw) % (ACTION_DIM * 8) or len(raw) > max_steps * ACTION_DIM * 8:
        raise ValueError(f"the action log is not a whole number of actions, or longer than {max_steps} steps")
    return np.frombuffer(raw, np.float64).reshape(-1, ACTION_DIM).copy()
