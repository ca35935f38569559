"""An episode's replay in its plan worker's twin (`sandbox.twin`): the process forked from the worker right
after the worker's set-up got the task's scene (built there, or by the fork server before it forked anyone:
`episode_worker.prebuild`), before the worker locked itself down and before any plan code ran.

The twin holds the very scene the plan got (the same memory image, so the same model and start to the last
bit) in an address space the plan cannot reach, and the scene is built once for both. The parent forwards
the worker's chunks of commands to it as they arrive (`TwinReplay.feed`), the twin simulates them while the
worker plans the next ones, on a core of its own, and at the end sends back the verdict and the recording
(`episodes.replay`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from humanoidgen.episodes.recorder import RecorderConfig
from humanoidgen.episodes.replay import OverTime, Replay, ReplayVerdict, step_budget

POST_TIMEOUT_S = 120.0  # the twin reads all the time: a full pipe this long means it is gone
VERDICT_TIMEOUT_S = 300.0  # the rest of the replay, the final rest and the judging
MAX_VERDICT_BYTES = 1 << 30  # the twin is trusted; this only bounds a broken one


def twin_main(spec, env, recorder: RecorderConfig | None) -> Callable:
    """What `EpisodeSetup` returns under `sandbox.twin.TWIN`: the twin's loop over the parent's messages,
    ("feed", {"actions", "qpos"}) and then ("finish", (claimed_qpos, claimed_fingerprint, settle))."""

    def main(receive: Callable[[], Any], send: Callable[[Any], None]) -> None:
        replay = Replay(spec, env, recorder)
        while (message := receive()) is not None:
            kind, payload = message
            if kind == "feed":
                try:
                    replay.feed(payload.get("actions"), payload.get("qpos"))
                except Exception as exc:  # noqa: BLE001 - numbers from the plan's process broke the replay
                    replay.problem = replay.problem or f"the replay failed: {type(exc).__name__}: {exc}"
            elif kind == "finish":
                send(_to_wire(replay.finish(*payload)))
                return

    return main


def _to_wire(v: ReplayVerdict) -> dict:
    return {"checks": v.checks, "objects": v.objects, "sim_seconds": v.sim_seconds, "steps": v.steps,
            "problem": v.problem, "events": v.events, "arrays": v.arrays, "configurations": v.configurations,
            "model_stat": v.model_stat}


def _from_wire(d: Any) -> ReplayVerdict:
    if not isinstance(d, dict):
        raise TypeError("the replay process sent no verdict")
    return ReplayVerdict(list(d["checks"]), dict(d["objects"]), float(d["sim_seconds"]), int(d["steps"]),
                         d["problem"], d["arrays"], d["configurations"], d["model_stat"], list(d["events"]))


class TwinReplay:
    """The parent's side of an episode's replay: counts the commands against the plan's time budget
    (`replay.step_budget`) and passes them on to the twin; `finish` gets the verdict."""

    def __init__(self, channel, spec, control_hz: float) -> None:
        self.channel = channel  # sandbox.twin.TwinChannel
        self.max_steps = step_budget(spec, control_hz)
        self.fed = 0
        self.malformed = False  # a chunk that was not (k, 26) commands with their (k, nq) configurations

    def feed(self, payload: Any) -> None:
        """A chunk the worker streamed ({"actions": (k, 26), "qpos": (k, nq)}, k >= 1); raises OverTime past the
        plan's time budget. A chunk of any other form is not passed on: the episode is rejected at `finish`."""
        actions = payload.get("actions") if isinstance(payload, dict) else None
        qpos = payload.get("qpos") if isinstance(payload, dict) else None
        if not (isinstance(actions, np.ndarray) and actions.ndim == 2 and len(actions) >= 1
                and isinstance(qpos, np.ndarray) and qpos.ndim == 2 and len(qpos) == len(actions)):
            self.malformed = True
        self.fed += len(actions) if isinstance(actions, np.ndarray) and actions.ndim == 2 else 0
        self.fed += 1 if self.malformed else 0  # an empty or broken chunk still costs a step: floods end
        if self.fed > self.max_steps:
            raise OverTime()
        if not self.malformed:
            self.channel.post(("feed", {"actions": actions, "qpos": qpos}), POST_TIMEOUT_S)

    def finish(self, claimed_qpos: Any = None, claimed_fingerprint: Any = None, settle: bool = True
               ) -> ReplayVerdict:
        self.channel.post(("finish", (claimed_qpos, claimed_fingerprint, settle)), POST_TIMEOUT_S)
        verdict = _from_wire(self.channel.receive(VERDICT_TIMEOUT_S, MAX_VERDICT_BYTES))
        if self.malformed and verdict.problem is None:
            verdict.problem = "the plan worker sent malformed actions; nothing it did is kept"
        return verdict
