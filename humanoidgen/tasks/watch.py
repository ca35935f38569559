"""What an episode's predicates over time have seen: a task may judge a process, not only where things end
(`moved_while_held`: the drawer pushed shut by the hand holding its handle, not knocked shut by a swinging arm).
Whoever steps the simulation that is judged calls `observe()` after every control step: the trusted replay
(`episodes.replay`) and the gym environment (`envs.task_env`). A plan's own simulation is never watched: its
verdict is the replay's.

    watch = Watch(spec, env)
    for action in actions:
        env.step(action)
        watch.observe()
    checks = judge(spec, env, watch)
"""

from __future__ import annotations


class Watch:
    def __init__(self, spec, env) -> None:
        self.env = env
        self._preds = [(k, p) for k, p in enumerate(spec.success) if getattr(p, "history", False)]
        self.memory = {k: p.start() for k, p in self._preds}

    def __bool__(self) -> bool:
        return bool(self._preds)

    def observe(self) -> None:
        for k, p in self._preds:
            p.observe(self.env, self.memory[k])

    def saved(self) -> dict:
        """A copy of what it has seen, to go back to with `restore` (a replay resumed from a kept state)."""
        return {k: m.copy() for k, m in self.memory.items()}

    def restore(self, saved: dict) -> None:
        self.memory = {k: m.copy() for k, m in saved.items()}
