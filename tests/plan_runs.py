"""Running a plan text through the real episode entry point (a file in tmp_path, the locked-down worker)."""

from __future__ import annotations

from pathlib import Path

from humanoidgen.episodes.result import EpisodeResult
from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode


def run_plan(tmp_path, task: str, seed: int, text: str, time_limit_s: float | None = None) -> EpisodeResult:
    """`time_limit_s`: run the task with this time limit instead of its own (a test of the plan's time budget,
    which is a multiple of it: `episodes.replay.PLAN_TIME_FACTOR`)."""
    path = tmp_path / f"{task}_{seed}.py"
    path.write_text(text)
    if time_limit_s is not None:
        import yaml

        from humanoidgen.tasks.registry import load_task

        spec = load_task(task).model_dump(mode="json", exclude_none=True)
        spec.update(time_limit_s=time_limit_s, plan=None)
        task = str(tmp_path / f"{task}.yaml")
        Path(task).write_text(yaml.safe_dump(spec))
    result, _ = run_task_episode(EpisodeRequest(task, seed=seed, plan_path=str(path)))
    return result


def task_planner(env, **kwargs):
    """The planner API on a task's scene with the task's targets (`targets=scene.targets`), as the episode
    worker makes it; a scene built without a task has none."""
    from humanoidgen.planning.planner import HumanoidMotionPlanner

    return HumanoidMotionPlanner(env, targets=getattr(env.scene, "targets", None), **kwargs)


def cube_pinch_pose(task: str = "block_stack_single", seed: int = 0, side: str = "right"):
    """A planner on the task's scene, the hand opened for a pinch, and the solved pose pinching cube 0 (the way
    several tests start): (planner, pose)."""
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    _, env = build_scene(load_task(task), seed)
    planner = task_planner(env)
    planner.hand_pre_pinch(side)
    _, pose = planner.generate_end_effector_pose(planner.generate_constraints("cube", 0, "pinch", side), side)
    return planner, pose
