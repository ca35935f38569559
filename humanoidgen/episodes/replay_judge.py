"""Judging many action logs from one scene: script generation and the tree search keep one plan worker per
scene and ask for a verdict after each attempt or branch. Each verdict replays the worker's whole log since
the scene was reset (`episodes.replay`), here, outside the plan's process.

Branches of a tree share their beginnings, so a replay resumes from the furthest state already simulated for
a prefix of the new log (states are kept by the digest of the actions that led to them): a search replays
each control step about once, not once per judgement.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from dataclasses import dataclass

import mujoco
import numpy as np

from humanoidgen.episodes.action_log import unpack
from humanoidgen.episodes.replay import Replay, ReplayVerdict
from humanoidgen.sandbox.outcome import plain

STATE = mujoco.mjtState.mjSTATE_INTEGRATION
CACHED_STATES = 64


@dataclass(frozen=True)
class _Resume:
    state: np.ndarray
    steps: int
    held: int
    last: np.ndarray | None
    seen: dict  # the replay's watch (tasks.watch): what its predicates over time saw up to here


def _digest(actions: np.ndarray) -> bytes:
    return hashlib.blake2b(np.ascontiguousarray(actions).tobytes(), digest_size=16).digest()


class ReplayJudge:
    """The task's scene for one seed, built once here; `judge(reply)` replays a worker's log on it."""

    def __init__(self, spec, seed: int | None) -> None:
        self.replay = Replay.build(spec, seed)
        self._states: OrderedDict[tuple[int, bytes], _Resume] = OrderedDict()
        self._keep(np.zeros((0, 26)))

    def judge(self, reply: object) -> tuple[ReplayVerdict, dict]:
        """The verdict on the log in `reply` (the worker's judgement: "actions" packed, its final "qpos" and
        "fingerprint"), and the scene's status as a prompt shows it."""
        from humanoidgen.objects.describe import describe_scene

        replay = self.replay
        reply = reply if isinstance(reply, dict) else {}
        try:
            actions = unpack(reply.get("actions"), replay.max_steps + 1)
        except ValueError as exc:
            return ReplayVerdict([], {}, 0.0, 0, f"the plan worker sent no usable log of its commands ({exc})"), {}
        self._resume(actions)
        replay.feed(actions[replay.steps:])
        verdict = replay.finish(reply.get("qpos"), reply.get("fingerprint"))
        if verdict.problem is None and replay.steps == len(actions):
            self._keep(actions)
        status = describe_scene(replay.env, as_json=False)["status"]
        return verdict, {"status": status}

    def _resume(self, actions: np.ndarray) -> None:
        """Put the replay at the furthest kept state that a prefix of `actions` leads to."""
        best: _Resume | None = None
        for (n, digest), resume in self._states.items():
            if n <= len(actions) and (best is None or n > best.steps) and _digest(actions[:n]) == digest:
                best = resume
        assert best is not None  # the empty prefix is always kept
        r, env = self.replay, self.replay.env
        mujoco.mj_setState(env.model, env.data, best.state, STATE)
        mujoco.mj_forward(env.model, env.data)
        r.steps, r._held, r._last, r.problem = best.steps, best.held, best.last, None
        r.watch.restore(best.seen)

    def _keep(self, actions: np.ndarray) -> None:
        r, env = self.replay, self.replay.env
        state = np.empty(mujoco.mj_stateSize(env.model, STATE))
        mujoco.mj_getState(env.model, env.data, state, STATE)
        key = (len(actions), _digest(actions))
        self._states[key] = _Resume(state, r.steps, r._held, None if r._last is None else r._last.copy(),
                                    r.watch.saved())
        self._states.move_to_end(key)
        while len(self._states) > CACHED_STATES:
            oldest = next(iter(self._states))
            if oldest[0] == 0:  # the scene's start stays
                self._states.move_to_end(oldest)
                continue
            self._states.popitem(last=False)

    def report(self, reply: object) -> dict:
        """`judge` as the generation prompts and the search tree read it: {"checks" (the replay's, with a
        failed "replay" check when rejected), "events" (the worker's log, for feedback only), "status"}."""
        verdict, extra = self.judge(reply)
        raw = reply.get("events") if isinstance(reply, dict) else None
        events = [plain(str(e), 500, newlines=False) for e in raw[:2000]] if isinstance(raw, list) else []
        return {"checks": verdict.all_checks(), "events": events + verdict.events, "status": extra.get("status", [])}
