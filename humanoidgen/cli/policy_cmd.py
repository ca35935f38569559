"""`hgen policy ...`: train Diffusion Policy / DP3 on exported demonstrations and evaluate them closed-loop."""

from __future__ import annotations

import json
import os
from pathlib import Path

import typer

from humanoidgen.cli.robot_option import robot_option, select_robot

app = typer.Typer(help="Train and evaluate visuomotor policies (DP, DP3) on collected demonstrations.\n\n"
                       "Example: hgen policy train --policy dp3 --data data/close_drawer.zarr --out runs/cd_dp3",
                  no_args_is_help=True)


def _fail(message: str) -> None:
    typer.secho(message, fg=typer.colors.RED, err=True)
    raise typer.Exit(1)


def _overrides(epochs: int | None, batch_size: int | None, episodes: int | None, checkpoint_every: int | None,
               config: str | None) -> dict:
    over: dict = {}
    if config:
        text = config if config.lstrip().startswith("{") else None
        if text is None:
            if not Path(config).is_file():
                _fail(f"--config: {config} is neither a JSON object nor a file")
            text = Path(config).read_text()
        try:
            over = json.loads(text)
        except ValueError as exc:
            _fail(f"--config must be JSON (or a JSON file): {exc}")
        if not isinstance(over, dict):
            _fail("--config must be a JSON object, e.g. '{\"unet\": {\"down_dims\": [64, 128, 256]}}'")
    train = dict(over.get("train", {}))
    for key, value in (("epochs", epochs), ("batch_size", batch_size), ("episodes", episodes),
                       ("checkpoint_every", checkpoint_every)):
        if value is not None:
            train[key] = value
    return {**over, "train": train} if train else over


def _errors():
    from pydantic import ValidationError

    from humanoidgen.episodes.dataset import DatasetError
    from humanoidgen.policies.checkpoint import CheckpointError
    from humanoidgen.policies.data import DataError
    from humanoidgen.policies.eval import EvalError

    from humanoidgen.episodes.ray_session import RaySetupError, TaskLost

    return (DataError, CheckpointError, EvalError, DatasetError, ValidationError, ValueError, KeyError,
            FileNotFoundError, RaySetupError, TaskLost)


def _one_line(exc: Exception) -> str:
    from pydantic import ValidationError

    if isinstance(exc, ValidationError):
        first = exc.errors()[0]
        return f"bad config: {'.'.join(str(p) for p in first['loc'])}: {first['msg']}"
    text = str(exc.args[0]) if isinstance(exc, KeyError) and exc.args else str(exc)  # KeyError quotes its text
    return (text.splitlines() or [type(exc).__name__])[0]


@app.command()
def train(
    policy: str = typer.Option(..., "--policy", help="dp (head RGB + joints) or dp3 (point cloud + joints)."),
    data: Path = typer.Option(..., "--data", help="A zarr from `hgen dataset export --zarr`."),
    out: Path = typer.Option(..., "--out", help="Run folder: checkpoints/, latest.pt, config.json."),
    recipe: str | None = typer.Option(None, "--recipe", help="paper (the paper's GPU recipe: 3000 epochs, batch 256), "
                                                             "fast (CPU-sized: 40 epochs, batch 64, a small U-Net) or "
                                                             "reduced; default: paper with CUDA, fast without."),
    epochs: int | None = typer.Option(None, min=1, help="Epochs (default: the recipe's; paper 3000, fast 40)."),
    episodes: int | None = typer.Option(None, min=1, help="Train on the first N episodes (20, 50, 100 ...)."),
    batch_size: int | None = typer.Option(None, min=1, help="Batch size (default: the recipe's; paper 256)."),
    checkpoint_every: int | None = typer.Option(None, min=1, help="Keep a checkpoint every N epochs (and the last)."),
    config: str | None = typer.Option(None, help="More settings as JSON (or a JSON file), e.g. "
                                                 "'{\"unet\": {\"down_dims\": [64, 128, 256]}, \"num_points\": 512}'."),
    task: str | None = typer.Option(None, help="The task, for a zarr exported without it."),
    device: str = typer.Option("auto", help="auto, cpu or cuda."),
    resume: bool = typer.Option(False, help="Continue the run in --out from its latest.pt."),
    threads: int | None = typer.Option(None, min=1, help="CPU threads for torch (default: torch's)."),
) -> None:
    """Train DP or DP3 with a progress bar; Ctrl-C saves latest.pt, and --resume continues from it.

    Example: hgen policy train --policy dp3 --data data/cd.zarr --out runs/cd_dp3 --episodes 50 --epochs 200
    """
    import torch

    from humanoidgen.policies.train import train as run_train

    if threads:
        torch.set_num_threads(threads)
    over = _overrides(epochs, batch_size, episodes, checkpoint_every, config)
    try:
        over, line = _with_recipe(policy, recipe, over, device, resume)
        result = run_train(policy, data, out, over, device=device, resume=resume, task=task,
                           on_start=lambda steps, per_step: typer.echo(_start_line(line, steps, per_step)))
    except _errors() as exc:
        _fail(_one_line(exc))
        return
    if result.interrupted:
        _fail(f"interrupted after epoch {result.epochs}; continue with the same command and --resume")
    typer.echo(f"trained {policy} for {result.new_epochs} epochs ({result.epochs} in all) in "
               f"{result.seconds / 60:.1f} min ({result.seconds_per_epoch:.2f} s/epoch, {result.steps_per_epoch} "
               f"steps each); loss {result.losses[0]:.4f} -> {result.losses[-1]:.4f}; checkpoints in "
               f"{out / 'checkpoints'}")


def _start_line(recipe_line: str, steps: int, seconds_per_step: float) -> str:
    """What a run says before its first step: the recipe the device chose (when it chose one) and an estimate of
    its time from one step timed here (the first steps of a run are a little slower: warm-up)."""
    total = steps * seconds_per_step
    took = (f"{total / 86400:.1f} days" if total >= 2 * 86400 else f"{total / 3600:.1f} h" if total >= 2 * 3600
            else f"{max(1 if steps else 0, round(total / 60))} min")  # a finished run resumed: nothing to do
    estimate = f"{steps} optimizer steps at about {seconds_per_step:.2f} s a step here: about {took}"
    return f"{recipe_line}\n{estimate}" if recipe_line else estimate


def _with_recipe(policy: str, recipe: str | None, over: dict, device: str, resume: bool) -> tuple[dict, str]:
    """(The run's settings: the recipe's (named, or by device: `recipes.default_recipe`) under `over`; the line
    that says which, when the device chose it, to print once training starts, else ''). A resumed run keeps its
    own settings unless a recipe is named."""
    from humanoidgen.policies.recipes import default_recipe, recipe_overrides
    from humanoidgen.policies.registry import policy_type
    from humanoidgen.policies.train import resolve_device

    if recipe is None and resume:
        return over, ""
    name = recipe or default_recipe(resolve_device(device))
    over = recipe_overrides(name, policy, over)
    if recipe is not None:
        return over, ""
    ptype = policy_type(policy)
    cfg = ptype.config(over)
    size = sum(p.numel() for p in ptype.model_cls()(cfg).parameters()) / 1e6
    why = "no CUDA device: the CPU-sized 'fast' recipe" if name == "fast" else "CUDA: the paper's recipe"
    return over, (f"{why} ({size:.1f} M parameters, U-Net {'/'.join(map(str, cfg.unet.down_dims))}, batch "
                  f"{cfg.train.batch_size}, {cfg.train.epochs} epochs); "
                  + ("--recipe paper trains the paper's" if name == "fast" else "--recipe fast for a smaller one"))


@app.command()
def eval(  # noqa: A001 - the command is called eval
    run: Path = typer.Argument(..., help="A run folder (all its kept checkpoints), one checkpoint file, or a "
                                          "LeRobot checkpoint (its pretrained_model folder); with --policy "
                                          "random|noop, the task."),
    policy: str | None = typer.Option(None, "--policy", help="A baseline instead of a trained run: random "
                                                             "(uniform joint targets, each held 4 actions) or noop "
                                                             "(hold the start posture)."),
    checkpoint: list[Path] = typer.Option(None, "--checkpoint", help="Only these checkpoints (repeatable)."),
    task: str | None = typer.Option(None, help="The task to evaluate on; it must be the one trained on."),
    episodes: int = typer.Option(20, min=1, help="Episodes per seed and checkpoint."),
    seeds: str = typer.Option("0,1,2", help="Evaluation seeds (scenes 100000 + 1000*seed + episode)."),
    video: Path | None = typer.Option(None, "--video", help="Write one MP4 per episode into this folder."),
    out: Path | None = typer.Option(None, "--out", help="Write the report (JSON) here."),
    device: str = typer.Option("auto", help="auto, cpu or cuda."),
    threads: int | None = typer.Option(None, min=1, help="CPU threads for torch."),
    max_steps: int | None = typer.Option(None, min=1, help="Cut episodes at N actions (default: the task's "
                                                           "time limit)."),
    ray_address: str | None = typer.Option(None, "--ray", help="Each episode a Ray task: 'local', 'auto' or "
                                                               "'ray://host:port' (checkpoints on a shared folder)."),
    ray_gpus: float = typer.Option(0.0, min=0.0, help="With --ray, GPUs per episode."),
    action_steps: int | None = typer.Option(None, "--action-steps", help="Actions executed per prediction "
                                                                          "(default: the run's n_action_steps)."),
    temporal_ensemble: float | None = typer.Option(None, "--temporal-ensemble", min=0.0, help="Predict at every "
                                                   "action and execute the weighted mean of the overlapping "
                                                   "predictions (ACT's temporal ensembling; weights exp(-M i), "
                                                   "oldest first: 0.1 is nearly a plain mean)."),
    baselines: bool = typer.Option(True, "--baselines/--no-baselines", help="Also run the random and noop "
                                                                            "baselines on the same scenes."),
    data: Path | None = typer.Option(None, "--data", help="With --policy random: draw targets within this zarr's "
                                                         "action range and at its action rate (default: the joint "
                                                         "limits, 10 Hz). With a LeRobot checkpoint: the export it "
                                                         "was trained on (default: its train_config.json's)."),
    randomize: bool = typer.Option(False, "--randomize", help="Also evaluate on the same scenes randomized from "
                                   "their seeds (a room and its table height, textures, lights, camera jitter, "
                                   "distractors) and report clean and randomized side by side."),
    robot: str = robot_option(),
) -> None:
    """Run the policy in its task and report success mean and std over seeds and checkpoints, with the random
    and no-op baselines' on the same scenes beside it; with --randomize, clean and randomized side by side.

    Example: hgen policy eval runs/cd_dp3 --task close_drawer --episodes 20 --seeds 0,1,2

    Example (a baseline alone): hgen policy eval --policy random close_drawer --episodes 20

    Example (LeRobot, in its environment): .venv-lerobot/bin/hgen policy eval
    outputs/train/cd_diffusion/checkpoints/last/pretrained_model --episodes 20
    """
    os.environ.setdefault("MUJOCO_GL", "egl")
    select_robot(robot)
    import torch

    from humanoidgen.policies.eval import evaluate
    from humanoidgen.policies.registry import BASELINE_NAMES

    if threads:
        torch.set_num_threads(threads)
    try:
        seed_list = tuple(int(s) for s in seeds.split(",") if s.strip())
    except ValueError:
        _fail(f"--seeds must be comma-separated integers, got {seeds!r}")
        return
    if policy is not None and temporal_ensemble is not None:
        _fail("--temporal-ensemble runs a trained policy's predictions; the baselines (--policy) have none to average")
    if policy is not None and policy not in BASELINE_NAMES:
        _fail(f"--policy is for the baselines ({', '.join(BASELINE_NAMES)}); a trained {policy} is evaluated from "
              f"its run folder: hgen policy eval RUN")
    reports = []
    try:
        for randomized in ((False, True) if randomize else (False,)):
            if policy is not None:
                report = _baseline_report(policy, str(run), episodes, seed_list, data, max_steps, video, randomized)
            else:
                report = evaluate(run, task, episodes, seed_list, checkpoints=checkpoint or None, device=device,
                                  video_dir=video, max_steps=max_steps, ray_address=ray_address, ray_gpus=ray_gpus,
                                  action_steps=action_steps, baselines=baselines, randomize=randomized,
                                  dataset=data, temporal_ensemble=temporal_ensemble)
            reports.append(report)
            for (ckpt, seed), rate in report.rates().items():
                typer.echo(f"{Path(ckpt).name} seed {seed} ({report.scenes}): {100 * rate:.0f}% of {episodes}")
    except _errors() as exc:
        _fail(_one_line(exc))
        return
    for report in reports:  # side by side at the end, clean first
        typer.echo(report.summary())
        if report.baseline_line():
            typer.echo(report.baseline_line())
    if out is not None:
        out.parent.mkdir(parents=True, exist_ok=True)
        body = reports[0].to_dict() if len(reports) == 1 else {r.scenes: r.to_dict() for r in reports}
        out.write_text(json.dumps(body, indent=2))
        typer.echo(f"wrote {out}")


def _baseline_report(policy: str, task: str, episodes: int, seeds: tuple[int, ...], data: Path | None,
                     max_steps: int | None, video: Path | None, randomize: bool = False):
    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.policies.baseline_eval import evaluate_baseline, zarr_range

    action_range, cfg = None, TaskEnvConfig(max_steps=max_steps, randomize=randomize)
    if data is not None:
        action_range, attrs = zarr_range(data)
        if attrs.get("task") not in (None, task):
            raise ValueError(f"{data} holds task {attrs['task']!r}, not {task!r}")
        cfg = TaskEnvConfig.from_recorder(dict(attrs.get("recorder") or {}), float(attrs.get("control_hz", 50.0)),
                                          max_steps=max_steps, randomize=randomize)
    report = evaluate_baseline(policy, task, episodes, seeds, env_config=cfg, action_range=action_range,
                               video_dir=video)
    if policy == "random" and not randomize:
        typer.echo(f"random targets within {report.info['action_range']['source']}, each held "
                   f"{report.info['hold_actions']} actions")
    return report


@app.command()
def bench(
    tasks: str = typer.Option("close_drawer,open_box_easy,dual_bottles_pick_easy",
                              help="Comma-separated tasks ('paper': the paper's 14)."),
    demos: str = typer.Option("20,50,100", help="Numbers of demonstrations."),
    policies: str = typer.Option("dp,dp3", help="Policies."),
    data_root: Path = typer.Option(Path("data/policy_study"), help="Where <task>.zarr are (collected if missing)."),
    runs_root: Path = typer.Option(Path("runs/policy_study"), help="Where the runs go."),
    recipe: str | None = typer.Option(None, "--recipe", help="paper, fast or reduced (as for train; default: paper "
                                                             "with CUDA, fast without)."),
    epochs: int | None = typer.Option(None, min=1, help="Epochs per run (default: the recipe's)."),
    config: str | None = typer.Option(None, help="Settings for every run, JSON (as for train --config)."),
    episodes: int = typer.Option(20, min=1, help="Evaluation episodes per seed."),
    seeds: str = typer.Option("0,1,2", help="Evaluation seeds."),
    out: Path = typer.Option(Path("bench/results/policies.json"), help="JSON of the rows; a .png plot beside it."),
    device: str = typer.Option("auto", help="auto, cpu or cuda."),
    workers: int = typer.Option(1, min=1, help="Collection workers for missing data."),
    baselines: bool = typer.Option(True, "--baselines/--no-baselines", help="The random and noop baselines on "
                                                                            "each row's scenes too."),
    randomize: bool = typer.Option(False, "--randomize", help="Evaluate each run on clean and on randomized "
                                   "scenes (a row for each, `scenes` clean|randomized)."),
    train_randomized: bool = typer.Option(False, "--train-randomized", help="Also train each run on randomized "
                                          "demonstrations (collected in the scenes --randomize evaluates on; rows "
                                          "say `train_scenes` clean|randomized)."),
    robot: str = robot_option(),
) -> None:
    """The study: tasks x demos x policies, trained and evaluated; writes a table, a JSON and a plot.

    Example (GPU, the paper's recipe): hgen policy bench --tasks paper --device cuda

    Example (CPU, the fast recipe): hgen policy bench --tasks close_drawer --policies dp3 --demos 50
    """
    os.environ.setdefault("MUJOCO_GL", "egl")
    select_robot(robot)
    from humanoidgen.policies.bench import PAPER_TASKS, StudyConfig, format_row, run_study, write_results
    from humanoidgen.policies.recipes import default_recipe
    from humanoidgen.policies.train import resolve_device

    over = _overrides(epochs, None, None, None, config)
    task_list = PAPER_TASKS if tasks == "paper" else tuple(t.strip() for t in tasks.split(",") if t.strip())
    policy_list = tuple(p.strip() for p in policies.split(","))
    try:
        chosen = {p: _with_recipe(p, recipe, over, device, False) for p in policy_list}
    except _errors() as exc:
        _fail(_one_line(exc))
        return
    by_policy = {p: o for p, (o, _) in chosen.items()}
    for p, (_, line) in chosen.items():
        if line:
            typer.echo(f"{p}: {line}")
    cfg = StudyConfig(tasks=task_list, demos=tuple(int(d) for d in demos.split(",")),
                      policies=policy_list, data_root=data_root,
                      runs_root=runs_root, overrides=by_policy, eval_episodes=episodes,
                      eval_seeds=tuple(int(s) for s in seeds.split(",")), device=device, collect_workers=workers,
                      baselines=baselines, scenes=("clean", "randomized") if randomize else ("clean",),
                      train_scenes=("clean", "randomized") if train_randomized else ("clean",),
                      recipe=recipe or default_recipe(resolve_device(device)))
    try:
        rows = run_study(cfg)
    except _errors() as exc:
        _fail(_one_line(exc))
        return
    typer.echo("\n".join(format_row(r) for r in rows))
    write_results(rows, cfg, out, out.with_suffix(".png"))
    typer.echo(f"wrote {out} and {out.with_suffix('.png')}")
