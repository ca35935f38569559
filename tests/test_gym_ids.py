"""Gym ids exist after `import humanoidgen`, whichever of it and gymnasium comes first, and the package
imports without gymnasium (issue 37 item 5)."""

import subprocess
import sys

import pytest

pytest.importorskip("gymnasium")


def _run(code: str) -> str:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    return out.stdout.strip()


@pytest.mark.parametrize("order", ["import humanoidgen, gymnasium", "import gymnasium, humanoidgen"])
def test_ids_registered_after_import_humanoidgen(order):
    code = f"""{order}
import sys
from humanoidgen.tasks.registry import task_names
ids = sorted(k for k in gymnasium.registry if k.startswith("humanoidgen/"))
assert ids == sorted(f"humanoidgen/{{t}}-v0" for t in task_names()), ids
spec = gymnasium.spec("humanoidgen/close_drawer-v0")
assert spec.kwargs == {{"task": "close_drawer"}}
# Registering stores the entry point's name only: the env module (MuJoCo, torch) is not loaded yet.
print("humanoidgen.envs.task_env" in sys.modules)
"""
    assert _run(code) == "False"


def test_hook_costs_nothing_and_leaves_once_used():
    code = """import sys
import humanoidgen
from humanoidgen.gym_ids import _GymnasiumHook
hooked = sum(isinstance(f, _GymnasiumHook) for f in sys.meta_path)
humanoidgen.gym_ids.install()  # idempotent: still one hook
again = sum(isinstance(f, _GymnasiumHook) for f in sys.meta_path)
print(hooked, again, "gymnasium" in sys.modules)
import gymnasium
print(sum(isinstance(f, _GymnasiumHook) for f in sys.meta_path))
"""
    assert _run(code).split() == ["1", "1", "False", "0"]


def test_package_imports_without_gymnasium():
    code = """import sys
sys.modules["gymnasium"] = None  # as if it were not installed
import humanoidgen
try:
    import gymnasium
except ImportError:
    print("no gymnasium")
"""
    assert _run(code) == "no gymnasium"
