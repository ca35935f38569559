"""`hgen dataset ...`: look at, export and replay collected demonstrations."""

from __future__ import annotations

import os
from pathlib import Path

import typer
from rich.console import Console
from rich.table import Table

app = typer.Typer(help="Inspect, export and replay datasets written by `hgen collect`.\n\n"
                       "Example: hgen dataset info data/stack", no_args_is_help=True)
console = Console()


def _fail(message: str) -> None:
    typer.secho(message, fg=typer.colors.RED, err=True)
    raise typer.Exit(1)


def _store(path: Path):
    """The dataset at `path` (its meta.json readable), or one red line and exit 1; skipped index lines are
    warned about (yellow), since what they held is not shown or exported."""
    from humanoidgen.episodes.dataset import DatasetError, EpisodeStore

    store = EpisodeStore(path)
    try:
        store.meta()
    except DatasetError as exc:
        _fail(str(exc))
    for problem in store.index_problems():
        typer.secho(f"warning: {problem}", fg=typer.colors.YELLOW, err=True)
    return store


@app.command()
def info(path: Path = typer.Argument(..., help="A dataset folder.")) -> None:
    """Summarize a dataset: task, episodes kept and tried, lengths, what was recorded.

    Example: hgen dataset info data/stack
    """
    store = _store(path)
    meta, attempts, kept = store.meta(), store.attempts(), store.kept()
    bad = store.corrupt()
    lengths = [k["length"] for k in kept if k["episode"] not in bad and isinstance(k.get("length"), int)]
    console.print(f"[bold]{meta['task']}[/bold]: {len(kept)} episodes kept of {len(attempts)} attempts "
                  f"({100 * len(kept) / max(len(attempts), 1):.0f}% success)")
    if lengths:
        every, hz = meta.get("recorder", {}).get("every", "?"), meta.get("control_hz")
        console.print(f"frames per episode: min {min(lengths)}, mean {sum(lengths) / len(lengths):.0f}, max {max(lengths)} "
                      f"(every {every} control steps at {hz if hz is None else f'{hz:.0f}'} Hz)")
        good = next(k["episode"] for k in kept if k["episode"] not in bad)
        table = Table("array", f"shape (episode {good})", "dtype")
        for name, arr in store.load(good).items():
            table.add_row(name, str(arr.shape), str(arr.dtype))
        console.print(table)
    failed = [a for a in attempts if not a["success"]]
    for a in failed[:5]:
        console.print(f"  seed {a['seed']} failed: {str(a.get('error', ''))[:150]}")
    if bad:
        seeds = {k["episode"]: k["seed"] for k in kept}
        for i, why in sorted(bad.items()):
            typer.secho(f"damaged: {store.episode_path(i)} (episode {i}, seed {seeds[i]}): {why}",
                        fg=typer.colors.RED, err=True)
        _fail(f"{len(bad)} of {len(kept)} episode files are damaged; continue the collection with "
              f"`hgen collect {meta.get('task_source', meta['task'])} -n N --out {path} --resume` to replace them")


@app.command()
def export(
    path: Path = typer.Argument(..., help="A dataset folder."),
    zarr_out: Path | None = typer.Option(None, "--zarr", help="Write the Diffusion Policy / DP3 zarr layout here."),
    lerobot_out: Path | None = typer.Option(None, "--lerobot",
                                            help="Write a LeRobot dataset (format v3.0, parquet + mp4) here."),
    camera: str = typer.Option("head", help="Camera whose images go to data/img and data/depth (zarr)."),
    lerobot_cameras: str | None = typer.Option(None, "--lerobot-cameras",
                                               help="Comma-separated cameras to export as LeRobot videos "
                                                    "(default: all recorded)."),
) -> None:
    """Export to the zarr layout DP and DP3 train from (data/{state, action, point_cloud, img, depth},
    meta/episode_ends) and/or to a LeRobot dataset that `lerobot`'s LeRobotDataset loads.

    Example: hgen dataset export data/stack --zarr data/stack.zarr --lerobot data/stack_lerobot
    """
    from humanoidgen.episodes.dataset import DatasetError, export_zarr

    if zarr_out is None and lerobot_out is None:
        typer.secho("give --zarr DIR, --lerobot DIR or both", fg=typer.colors.RED, err=True)
        raise typer.Exit(2)
    store = _store(path)
    try:
        if zarr_out is not None:
            shapes = export_zarr(store, zarr_out, image_camera=camera)
            for name, shape in shapes.items():
                console.print(f"{name}: {shape}")
            console.print(f"wrote {zarr_out}")
        if lerobot_out is not None:
            from humanoidgen.episodes.lerobot_export import export_lerobot

            cams = [c.strip() for c in lerobot_cameras.split(",") if c.strip()] if lerobot_cameras else None
            info = export_lerobot(store, lerobot_out, cameras=cams)
            console.print(f"wrote {lerobot_out} (LeRobot {info['codebase_version']}: {info['total_episodes']} "
                          f"episodes, {info['total_frames']} frames at {info['fps']} fps; features "
                          f"{', '.join(k for k in info['features'] if '.' in k or k == 'action')})")
    except DatasetError as exc:
        _fail(str(exc))
    except KeyError as exc:  # a readable episode file or meta.json without an entry the export needs
        _fail(f"{path}: an episode or meta.json lacks {exc}, which the export needs")


@app.command()
def replay(
    path: Path = typer.Argument(..., help="A dataset folder."),
    episode: int = typer.Option(0, help="Episode index."),
    video: Path = typer.Option(..., help="MP4 file to write."),
    camera: str = typer.Option("front", help="Camera to render from."),
) -> None:
    """Render a recorded episode again from its recorded simulator states.

    Example: hgen dataset replay data/stack --episode 3 --video ep3.mp4 --camera head
    """
    os.environ.setdefault("MUJOCO_GL", "egl")
    import mujoco

    from humanoidgen.episodes.dataset import DatasetError
    from humanoidgen.episodes.task_episode import load_spec
    from humanoidgen.episodes.video import VideoWriter
    from humanoidgen.tasks.scene import build_scene

    store = _store(path)
    meta = store.meta()
    seeds = {a["episode"]: a["seed"] for a in store.kept()}
    if episode not in seeds:
        _fail(f"episode {episode} is not in {store.index_path} (kept episodes: "
              f"{', '.join(map(str, sorted(seeds))) or 'none'})")
    try:
        frames = store.load(episode)
        if "qpos" not in frames:
            raise DatasetError(f"{store.episode_path(episode)} has no qpos array to replay")
        fps = float(meta["control_hz"]) / int(meta["recorder"]["every"])
    except DatasetError as exc:
        _fail(str(exc))
    except (KeyError, TypeError, ValueError, ZeroDivisionError) as exc:
        _fail(f"{store.meta_path} lacks the control rate or recorder settings ({type(exc).__name__}: {exc})")
    try:
        _, env = build_scene(load_spec(meta.get("task_source", meta["task"])), seeds[episode])
    except (KeyError, ValueError, FileNotFoundError) as exc:
        _fail(str(exc).strip("'\""))
    writer = VideoWriter(video, camera, fps=int(round(fps)), control_hz=fps)
    writer.attach(env)
    try:
        for qpos in frames["qpos"]:
            env.data.qpos[:] = qpos
            mujoco.mj_forward(env.model, env.data)
            writer(None)
    finally:
        writer.close()
    console.print(f"wrote {video} ({len(frames['qpos'])} frames at {fps:.0f} fps)")


@app.command()
def perturb(
    path: Path = typer.Argument(..., help="A dataset folder (hgen collect --out)."),
    out: Path = typer.Option(..., help="Where to write the perturbed dataset (a new folder)."),
    sigma: float = typer.Option(0.03, help="The offset's standard deviation per arm joint, rad."),
    side: str = typer.Option("left", help="The arm perturbed: left, right or both."),
    tau: float = typer.Option(1.0, help="The offset's correlation time, s (it drifts, as a policy's error does)."),
    draws: int = typer.Option(1, help="Perturbed replays kept per episode."),
    tries: int = typer.Option(3, help="Draws tried per replay before the episode is left out."),
    episodes: int | None = typer.Option(None, help="Perturb only the first N kept episodes."),
    seed: int = typer.Option(0, help="Seed of the offsets."),
    resume: bool = typer.Option(False, help="Go on with an interrupted run into the same --out (same settings), "
                                "or add draws to it (more --draws)."),
    workers: int = typer.Option(1, help="Replay in this many processes (the store is the same as with one)."),
    cloud_near_hands: float | None = typer.Option(None, help="Share of each cloud's points drawn near the hands, "
                                                  "in [0, 1) (default: the source's; docs: guides/policies.md)."),
) -> None:
    """Re-record demonstrations under a drifting arm error, labelled with the plan's targets (DART).

    Each kept episode's actions are replayed in the task's gym env with a slowly drifting offset on one arm's
    joint targets; the observations come from that replay, the actions are the plan's. A replay that no longer
    passes the task is drawn again (--tries), then left out. The result trains a policy that has seen the way
    back to the path (`hgen dataset export OUT --zarr ...`, then `hgen policy train`). No pictures are re-rendered:
    it holds joint_pos, ee_pose, point_cloud (DP3) and qpos.

    Example: hgen dataset perturb data/close_drawer --out data/close_drawer_dart --sigma 0.03 --side left
    """
    from tqdm import tqdm

    from humanoidgen.episodes.dataset import DatasetError
    from humanoidgen.policies.perturb import Perturbation, describe, perturb_store

    store = _store(path)
    try:
        how = Perturbation(sigma=sigma, side=side, tau_s=tau, draws=draws, tries=tries, seed=seed)  # type: ignore[arg-type]
    except ValueError as exc:
        _fail(f"error: {exc}")
    if episodes is not None and episodes < 1:
        _fail("error: --episodes must be at least 1")
    if workers < 1:
        _fail("error: --workers must be at least 1")
    if cloud_near_hands is not None:
        from humanoidgen.sim.cloud_floor import check_near_hands

        try:
            check_near_hands(cloud_near_hands)
        except ValueError as exc:
            _fail(f"error: --cloud-near-hands: {exc}")
    total = min(len(store.kept()), episodes or len(store.kept())) * how.draws
    bar = tqdm(total=total, unit="episode", desc=f"perturb {store.meta()['task']}")
    try:
        stats = perturb_store(path, out, how, episodes=episodes, progress=lambda _: bar.update(1), resume=resume,
                              workers=workers, cloud_near_hands=cloud_near_hands)
    except DatasetError as exc:
        _fail(f"error: {exc}")
    finally:
        bar.close()
    console.print(f"{describe(stats, how)}; wrote {out}")
    if stats.kept == 0:
        _fail(f"error: no perturbed replay passed the task at sigma {sigma:g} rad; try a smaller --sigma")
