"""`hgen tasks`, `hgen run`, `hgen collect`: the benchmark tasks, single episodes, demonstration collection."""

from __future__ import annotations

import json
import os
from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from humanoidgen.cli import fast_exit
from humanoidgen.cli.robot_option import robot_option, select_robot

console = Console()


def _fail(message: str) -> None:
    typer.secho(message, fg=typer.colors.RED, err=True)
    raise typer.Exit(1)


def tasks() -> None:
    """List the benchmark tasks with their descriptions.

    Example: hgen tasks
    """
    from humanoidgen.tasks.registry import list_tasks

    table = Table()
    table.add_column("task", no_wrap=True)
    for col in ("arms", "horizon", "objects", "plan", "description"):
        table.add_column(col)
    for spec in list_tasks():
        objs = ", ".join(sorted({o.type for o in spec.objects}))
        table.add_row(spec.name, spec.arms, spec.horizon, objs, "yes" if spec.plan else "-", spec.description)
    console.print(table)


def check_output_path(path: Path | None, option: str, kind: str = "file") -> None:
    """Fail before any work when an output path cannot be what the option writes (checked up front, so a
    long episode or collection is not lost to a typo at the end)."""
    if path is None:
        return
    if kind == "file" and path.is_dir():
        _fail(f"{option} {path} is a directory; give a file name")
    if kind == "dir" and path.exists() and not path.is_dir():
        _fail(f"{option} {path} is a file; give a folder (it is created if missing)")
    parent = path.parent if kind == "file" else path
    existing = next((p for p in (parent, *parent.parents) if p.exists()), None)
    if existing is not None and not existing.is_dir():
        _fail(f"{option} {path}: {existing} is a file, not a folder")
    if existing is not None and not os.access(existing, os.W_OK):
        _fail(f"{option} {path}: {existing} is not writable")


def run(
    task: str = typer.Argument(..., help="A task name (see `hgen tasks`) or a task YAML file."),
    seed: int = typer.Option(None, help="Randomize the scene with this seed (default: the task's default layout)."),
    script: Path = typer.Option(None, exists=True, help="A plan: a file, ours (`# step:` blocks) or the paper's "
                                "`def step(planner):` form, or a folder of step files (step0.py, step1.py, ...)."),
    video: Path = typer.Option(None, help="Write an MP4 of the episode (front camera)."),
    video_camera: str = typer.Option("front", help="Camera for --video."),
    json_out: Path = typer.Option(None, "--json", help="Write the result (steps, timings, final object poses) as JSON."),
    step_timeout: float = typer.Option(300.0, min=1.0, help="Seconds one plan step may take before it is stopped."),
    room: str = typer.Option(None, help="Run in a room: a room seed, or 'random' (a room drawn from each episode's "
                                        "seed); the task and its plan run unchanged (scenes.frames)."),
    randomize_visuals: bool = typer.Option(False, help="Randomize colours, textures, lights, camera poses and "
                                                       "distractors (drawn from the seed)."),
    model: list[str] = typer.Option(None, "--model", help="Use this model of a family: FAMILY=MODEL (a name from "
                                    "`hgen assets list`, imported or from the library, or a type_id); repeatable."),
    randomize_models: bool = typer.Option(False, "--randomize-models", help="Each episode draws its objects' models "
                                          "from their families' imported models (seeded: the same seed, the same "
                                          "models)."),
    robot: str = robot_option(),
) -> None:
    """Run one episode of a task and report success, the step log and timings.

    The plan runs in a locked-down worker process (no files, processes, sockets or secrets; time and memory
    limits); a failing step is reported with its call and reason.

    Example: hgen run blocks_stack_easy --seed 3 --video stack.mp4 --json stack.json
    Example: hgen run block_stack_single --robot g1_inspire --seed 3
    """
    os.environ.setdefault("MUJOCO_GL", "egl")
    select_robot(robot)
    if model or randomize_models:  # before the server builds the episode's scene: the task on those models
        import tempfile

        task, script = _with_models(task, model, randomize_models, Path(tempfile.mkdtemp(prefix="hgen-task-")),
                                    script)
    dressing = None
    if room is not None or randomize_visuals:
        from humanoidgen.scenes.dressing import episode_dressing

        try:
            dressing = episode_dressing(room, randomize_visuals, seed)
        except ValueError as exc:
            _fail(str(exc))
            return
    from humanoidgen.sandbox.forkserver import prestart

    # The workers' server imports, warms up and builds this episode's scene while this process checks its
    # arguments (a task it cannot load only costs the server that build: the worker says what is wrong).
    prestart(warm=("humanoidgen.episodes.episode_worker:prebuild",
                   {"task": str(Path(task).resolve()) if Path(task).suffix in (".yaml", ".yml") else task,
                    "seed": seed, "dressing": dressing}))
    from humanoidgen.assets.robot_files import AssetsError
    from humanoidgen.episodes.episode_worker import VideoSpec
    from humanoidgen.episodes.plans import PlanFormatError
    from humanoidgen.episodes.task_episode import EpisodeRequest, run_task_episode

    check_output_path(video, "--video")
    check_output_path(json_out, "--json")
    writer = None
    if video is not None:  # (imageio: only for a video)
        from humanoidgen.episodes.video import VideoWriter
        from humanoidgen.sim.cameras import CAMERA_NAMES

        if video_camera not in CAMERA_NAMES:
            _fail(f"unknown camera {video_camera!r}; cameras: {', '.join(CAMERA_NAMES)}")
        writer = VideoWriter(video, video_camera)
    req = EpisodeRequest(task, seed, str(script) if script else None, step_timeout_s=step_timeout,
                         video=VideoSpec(video_camera, writer.width, writer.height, writer.fps) if writer else None,
                         dressing=dressing)
    try:
        if writer is not None:
            writer.open()
        result, _ = run_task_episode(req, on_frame=writer.frame if writer is not None else None)
    except (KeyError, ValueError, FileNotFoundError, PlanFormatError, AssetsError, RuntimeError, OSError) as exc:
        _fail(str(exc).strip("'\"").splitlines()[0] if str(exc).strip() else type(exc).__name__)
        return
    finally:
        if writer is not None:
            writer.close()
    table = Table("#", "step", "result", "wall s", "sim s", "events")
    for s in result.steps:
        table.add_row(str(s.index), s.title, "ok" if s.ok else f"[red]{escape(s.error)}[/red]", f"{s.seconds:.2f}",
                      f"{s.sim_seconds:.1f}", escape("; ".join(s.events)))
    console.print(table)
    for c in result.checks:
        console.print(("[green]✓[/green] " if c["ok"] else "[red]✗[/red] ") + escape(f"{c['predicate']}: {c['detail']}"))
    verdict = "[green]SUCCESS[/green]" if result.success else "[red]FAILURE[/red]"
    console.print(f"{verdict}  {result.task} seed={seed}  wall {result.wall_seconds:.1f} s "
                  f"(planning {result.plan_seconds:.1f} s), simulated {result.sim_seconds:.1f} s")
    if video is not None:
        console.print(f"video: {video}")
    if json_out is not None:
        json_out.write_text(json.dumps(result.to_dict(), indent=2))
    fast_exit.allow()  # all written (the video is closed, the JSON too): no need to wait for the teardown
    raise typer.Exit(0 if result.success else 2)


def _with_models(task: str, model: list[str] | None, randomize: bool, folder: Path,
                 script: Path | None) -> tuple[str, Path | None]:
    """The task file with --model / --randomize-models applied, and the plan to run (the task's own)."""
    from humanoidgen.tasks.models import ModelChoiceError, task_with_models

    try:
        derived, plan = task_with_models(task, list(model or []), randomize, folder)
    except (ModelChoiceError, KeyError, ValueError, FileNotFoundError) as exc:
        _fail(str(exc).strip("'\""))
    return derived, script if script is not None or plan is None else plan


def collect(
    task: str = typer.Argument(..., help="A task name or task YAML."),
    n: int = typer.Option(..., "-n", min=1, help="How many successful episodes to keep."),
    out: Path = typer.Option(..., "--out", help="Dataset folder (episodes are written one by one)."),
    workers: int = typer.Option(None, min=1, help="Worker processes (default 1); the dataset is the same for any "
                                                 "number. With --ray local: the Ray CPUs (default: all); with a "
                                                 "cluster: at most this many attempts at once."),
    seed: int = typer.Option(0, help="First seed; attempts use seed, seed+1, ..."),
    resume: bool = typer.Option(False, help="Continue an interrupted collection in --out."),
    ray_address: str = typer.Option(None, "--ray", help="Run the attempts as Ray tasks: 'local', 'auto' or "
                                                        "'ray://host:port' (see the README's cluster recipe)."),
    ray_results: str = typer.Option("auto", help="With --ray, how kept episodes reach --out: 'object-store', "
                                                 "'shared-folder' (written by the task) or 'auto' (the folder "
                                                 "when recording images or point clouds)."),
    ray_gpus: float = typer.Option(0.0, min=0.0, help="With --ray, GPUs per attempt (rendering)."),
    cameras: str = typer.Option("all", help="Cameras to record: 'all', 'none' or a comma list (head,front,...)."),
    width: int = typer.Option(320, help="Image width."),
    height: int = typer.Option(240, help="Image height."),
    every: int = typer.Option(5, min=1, help="Record every n-th control step (50 Hz control; 5 -> 10 Hz)."),
    point_cloud: bool = typer.Option(True, help="Record the fused 1024-point cloud."),
    cloud_near_hands: float = typer.Option(0.0, help="Share of the cloud's points drawn near the hands, in [0, 1) "
                                                     "(0: the workspace sampled evenly; docs: guides/policies.md)."),
    visual_faces: int = typer.Option(None, help="Faces per robot visual mesh in the images (default: chosen for "
                                                "the resolution, 375 at 320x240; 1500: the full detail of "
                                                "`hgen render`)."),
    script: Path = typer.Option(None, exists=True, help="A plan file or folder instead of the reference plan."),
    room: str = typer.Option(None, help="Run in a room: a room seed, or 'random' (a room drawn from each episode's "
                                        "seed); the task and its plan run unchanged (scenes.frames)."),
    randomize_visuals: bool = typer.Option(False, help="Randomize each attempt's look (colours, textures, lights, "
                                                       "camera jitter, distractors), drawn from its seed and stored "
                                                       "in its index record so it re-renders exactly."),
    model: list[str] = typer.Option(None, "--model", help="Use this model of a family: FAMILY=MODEL (a name from "
                                    "`hgen assets list`, imported or from the library, or a type_id); repeatable."),
    randomize_models: bool = typer.Option(False, "--randomize-models", help="Each episode draws its objects' models "
                                          "from their families' imported models (seeded: the same seed, the same "
                                          "models)."),
    robot: str = robot_option(),
) -> None:
    """Collect N successful randomized demonstrations of a task.

    Each attempt runs in its own locked-down plan worker; this process writes the dataset.

    Example: hgen collect blocks_stack_easy -n 50 --out data/stack --workers 2
    """
    os.environ.setdefault("MUJOCO_GL", "egl")
    select_robot(robot)  # before the workers' server starts: they inherit it
    if ray_address is None:
        from humanoidgen.sandbox.forkserver import prestart

        prestart()  # the workers' server warms up while this process imports and checks its arguments
    from tqdm import tqdm

    from humanoidgen.episodes.collect import collect as run_collect
    from humanoidgen.episodes.dataset import DatasetError
    from humanoidgen.episodes.recorder import RecorderConfig
    from humanoidgen.sim.cameras import CAMERA_NAMES

    cams = CAMERA_NAMES if cameras == "all" else () if cameras == "none" else tuple(c.strip() for c in cameras.split(","))
    try:
        rec = RecorderConfig(every=every, cameras=cams, width=width, height=height, point_cloud=point_cloud,
                             visual_faces=visual_faces, point_cloud_near_hands=cloud_near_hands)
    except ValueError as exc:
        _fail(str(exc))
        return
    check_output_path(out, "--out", kind="dir")
    if model or randomize_models:  # kept beside the dataset: with the seeds it says which model each episode had
        task, script = _with_models(task, model, randomize_models, out.resolve().parent / f".{out.name}.task",
                                    script)
    from humanoidgen.episodes.task_episode import load_spec

    try:
        load_spec(task)  # a bad task fails before the progress bar is drawn
    except (KeyError, ValueError, FileNotFoundError) as exc:
        _fail(str(exc).strip("'\""))
        return
    from humanoidgen.episodes.ray_session import RaySetupError, check_address

    from humanoidgen.scenes.room import room_seed_for

    try:
        room_seed_for(room, 0)  # a bad --room fails before any work
    except ValueError as exc:
        _fail(str(exc))
        return
    if ray_address is not None:
        try:
            check_address(ray_address)
        except RaySetupError as exc:
            _fail(str(exc))
            return
    bar = tqdm(total=n, unit="episode", desc=f"collect {task}")

    def progress(kept: int, tried: int, nodes=None) -> None:
        bar.n = kept
        per_node = f"; {nodes.text()}" if nodes is not None else ""
        bar.set_postfix_str(f"kept {kept}/tried {tried} ({100 * kept / max(tried, 1):.0f}% success){per_node}")
        bar.refresh()

    try:
        if ray_address is None:
            stats = run_collect(task, n, out, workers=workers or 1, seed=seed, resume=resume, recorder=rec,
                                plan_path=str(script) if script else None, progress=progress, room=room,
                                randomize_visuals=randomize_visuals)
        else:
            from humanoidgen.episodes.ray_collect import ray_collect

            stats = ray_collect(task, n, out, ray_address, workers=workers, seed=seed, resume=resume, recorder=rec,
                                plan_path=str(script) if script else None, progress=progress,
                                transport=ray_results, gpus_per_task=ray_gpus, room=room,
                                randomize_visuals=randomize_visuals)
    except RaySetupError as exc:
        bar.close()
        _fail(str(exc))
        return
    except KeyboardInterrupt:
        bar.close()
        _fail(f"interrupted; what was kept is in {out}. Continue with: hgen collect {task} -n {n} --out {out} --resume")
        return
    except (DatasetError, KeyError, ValueError, FileNotFoundError) as exc:
        bar.close()
        _fail(str(exc).strip("'\""))
        return
    bar.close()
    typer.echo(f"kept {stats.kept} of {stats.tried} attempts ({100 * stats.success_rate:.0f}% success) "
               f"in {stats.wall_seconds:.0f} s -> {out}")
    if stats.kept < n:
        _fail(f"stopped after {stats.tried} attempts with only {stats.kept} successes; see {out}/index.jsonl")


def bench(
    tasks_opt: str = typer.Option(None, "--tasks", help="Comma list of tasks (default: every task with a reference plan)."),
    episodes: int = typer.Option(10, min=1, help="Randomized episodes per task."),
    seed: int = typer.Option(1000, help="First seed (held-out from collection's default seeds)."),
    workers: int = typer.Option(1, min=1, help="Worker processes (with --ray local: Ray CPUs)."),
    ray_address: str = typer.Option(None, "--ray", help="Run the episodes as Ray tasks: 'local', 'auto' or "
                                                        "'ray://host:port'."),
    json_out: Path = typer.Option(None, "--json", help="Write the report as JSON."),
    plot_out: Path = typer.Option(None, "--plot", help="Write a bar chart (PNG) of success per task."),
    room: str = typer.Option(None, help="Run in a room: a room seed, or 'random' (a room drawn from each episode's "
                                        "seed); the task and its plan run unchanged (scenes.frames)."),
    randomize_visuals: bool = typer.Option(False, help="Randomize each episode's look (colours, textures, lights, "
                                                       "camera jitter, distractors), drawn from its seed and stored "
                                                       "in its record of the --json report."),
    model: list[str] = typer.Option(None, "--model", help="Use this model of a family: FAMILY=MODEL or "
                                    "FAMILY[K]=MODEL (its K-th object); every task must have that family. "
                                    "Repeatable."),
    randomize_models: bool = typer.Option(False, "--randomize-models", help="Each episode draws its objects' models "
                                          "from their families' imported models (seeded); each record of the "
                                          "--json report names them."),
    robot: str = robot_option(),
) -> None:
    """Run each task's reference plan on randomized seeds and report success rate and time per episode.

    Example: hgen bench --tasks block_stack_single,open_drawer --episodes 20 --plot bench.png
    Example: hgen bench --robot g1_inspire --tasks block_stack_single --episodes 5
    """
    os.environ.setdefault("MUJOCO_GL", "egl")
    select_robot(robot)
    from humanoidgen.episodes.bench import plot, run_bench
    from humanoidgen.tasks.registry import list_tasks, load_task

    try:
        specs = [load_task(t.strip()) for t in tasks_opt.split(",")] if tasks_opt else \
            [s for s in list_tasks() if s.plan is not None]
    except (KeyError, ValueError, FileNotFoundError) as exc:
        _fail(str(exc).strip("'\""))
        return
    from humanoidgen.episodes.ray_session import RaySetupError
    from humanoidgen.tasks.models import ModelChoiceError

    try:
        reports = run_bench(specs, episodes, seed=seed, workers=workers,
                            progress=lambda t, k, n: console.print(f"{t}: {k}/{n}"), ray_address=ray_address,
                            room=room, randomize_visuals=randomize_visuals, models=list(model or []),
                            randomize_models=randomize_models)
    except RaySetupError as exc:
        _fail(str(exc))
        return
    except ModelChoiceError as exc:
        _fail(str(exc))
        return
    table = Table("task", "arms", "horizon", "success", "s / successful episode", "planning s", "main failure")
    for r in reports:
        reasons = [f.split(": ", 1)[-1] for f in r.failures]  # without the "seed N: " prefix
        common = max(set(reasons), key=reasons.count) if reasons else ""
        seeds = ", ".join(f.split(":", 1)[0].removeprefix("seed ") for f in r.failures[:5])
        table.add_row(r.task, r.arms, r.horizon, f"{100 * r.success_rate:.0f}%", f"{r.mean_wall_s:.1f}",
                      f"{r.mean_plan_s:.1f}", f"{common[:80]} (seeds {seeds}{', ...' if len(r.failures) > 5 else ''})"
                      if r.failures else "")
    console.print(table)
    if json_out is not None:
        json_out.write_text(json.dumps([r.to_dict() for r in reports], indent=2))
    if plot_out is not None:
        plot(reports, plot_out)
        console.print(f"plot: {plot_out}")
