"""Gym ids `humanoidgen/<task>-v0` registered as soon as both `humanoidgen` and `gymnasium` are imported.

gymnasium 1.x loads no plugin entry points, so the ids must be registered by our own import. Importing
gymnasium from `humanoidgen/__init__` would cost every `hgen` command its import time and make the package
need gymnasium; instead a one-shot import hook registers the ids right after gymnasium itself is first
imported (or at once when it already is). Registration stores only the entry point's name: the env module,
MuJoCo and torch load on the first `gymnasium.make`.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys

ENTRY_POINT = "humanoidgen.envs.task_env:HumanoidTaskEnv"


def env_id(task: str) -> str:
    return f"humanoidgen/{task}-v0"


def register_all() -> list[str]:
    """Register every built-in task with gymnasium (registering an id again is a no-op)."""
    import gymnasium as gym

    from humanoidgen.tasks.registry import task_names

    ids = []
    for name in task_names():
        if env_id(name) not in gym.registry:
            gym.register(env_id(name), entry_point=ENTRY_POINT, kwargs={"task": name}, disable_env_checker=False)
        ids.append(env_id(name))
    return ids


class _AfterLoad(importlib.abc.Loader):
    """Runs gymnasium's own loader, then registers our ids in the freshly loaded module."""

    def __init__(self, loader: importlib.abc.Loader) -> None:
        self._loader = loader

    def create_module(self, spec):  # noqa: ANN001 - the import system's signature
        return self._loader.create_module(spec)

    def exec_module(self, module) -> None:  # noqa: ANN001
        self._loader.exec_module(module)
        register_all()


class _GymnasiumHook(importlib.abc.MetaPathFinder):
    """Finds nothing itself: it wraps the loader of the real `gymnasium` once and then leaves sys.meta_path."""

    def find_spec(self, name, path, target=None):  # noqa: ANN001
        if name != "gymnasium":
            return None
        remove_hook()
        spec = importlib.machinery.PathFinder.find_spec(name, path)
        if spec is None or spec.loader is None:
            return None  # not installed: the import fails as it would have without us
        spec.loader = _AfterLoad(spec.loader)
        return spec


def remove_hook() -> None:
    sys.meta_path[:] = [f for f in sys.meta_path if not isinstance(f, _GymnasiumHook)]


def install() -> None:
    """Register now if gymnasium is loaded, else as soon as it is; without gymnasium, nothing happens."""
    if sys.modules.get("gymnasium") is not None:
        register_all()
    elif not any(isinstance(f, _GymnasiumHook) for f in sys.meta_path):
        sys.meta_path.insert(0, _GymnasiumHook())
