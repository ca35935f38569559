"""get_openness_in_env: a plan reads how open a part is now (the fresh corpus's close_drawer plan pushed from the
openness the prompt's default layout showed, and its seeds start elsewhere)."""

from __future__ import annotations

import pytest

from humanoidgen.episodes.runner import step_namespace
from humanoidgen.objects.describe import openness
from humanoidgen.tasks.registry import load_task
from humanoidgen.tasks.scene import build_scene


@pytest.mark.parametrize("seed", [0, 1])
def test_the_plan_reads_the_drawers_openness_as_it_is(seed: int) -> None:
    _, env = build_scene(load_task("close_drawer"), seed)
    get = step_namespace(None)["get_openness_in_env"]
    now = get(env, "drawer", 0)
    assert now == pytest.approx(openness(env.model, env.data, env.scene.object("drawer", 0)), abs=1e-9)
    assert 0.3 < now < 1.0  # the task starts it open


def test_a_second_part_by_name_and_clear_errors() -> None:
    _, env = build_scene(load_task("rotate_safe_knob"), 0)
    get = step_namespace(None)["get_openness_in_env"]
    safe = env.scene.object("safe", 0)
    assert get(env, "safe", 0, part="knob") == pytest.approx(openness(env.model, env.data, safe, "knob"), abs=1e-9)
    with pytest.raises(KeyError, match="no part 'lid'; its parts: .*knob"):
        get(env, "safe", 0, part="lid")
    _, env = build_scene(load_task("block_stack_single"), 0)
    with pytest.raises(KeyError, match=r"cube\[0\] has no moving part"):
        get(env, "cube", 0)
