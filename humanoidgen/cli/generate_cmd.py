"""`hgen generate prompt|scene|script|eval`: LLM-generated task scenes and demonstration scripts.

Endpoint: --base-url / --model override $OPENAI_BASE_URL / $HGEN_LLM_MODEL; the key is read from
$OPENAI_API_KEY (not needed for a loopback server); --timeout bounds the wait for one answer. The key and any
Authorization header are redacted from everything written (--log, --cache-dir, --record, plans, tree logs).
With no endpoint configured, each command prints one line
saying so and exits with code 3 (1 for other errors: unreachable endpoint, rejected key, no valid result)."""

from __future__ import annotations

import contextlib
import json
import os
from pathlib import Path

import typer

from humanoidgen.cli.robot_option import robot_option, select_robot

app = typer.Typer(
    help=(
        "Generate task scenes and demonstration scripts with an LLM (OpenAI-compatible endpoint).\n\n"
        "Set $OPENAI_BASE_URL (e.g. https://api.deepseek.com/v1) and $OPENAI_API_KEY, or pass --base-url.\n\n"
        "Examples:\n\n"
        "  hgen generate prompt block_stack_single --kind script   (the exact prompt, no endpoint needed)\n\n"
        "  hgen generate scene \"stack the red cube on the green cube\" --out stack.yaml\n\n"
        "  hgen generate script stack.yaml --attempts 3 --out plan.py --log log.json\n\n"
        "  hgen run stack.yaml --script plan.py\n\n"
        "  hgen generate eval --tasks block_stack_single,open_drawer --trials 5 --json eval.json"
    ),
    no_args_is_help=True,
)

EXIT_NOT_CONFIGURED = 3

_BASE_URL = typer.Option(None, "--base-url", help="OpenAI-compatible endpoint (default: $OPENAI_BASE_URL).")
_MODEL = typer.Option(None, "--model", help="Model name (default: $HGEN_LLM_MODEL, else deepseek-reasoner).")
_CACHE = typer.Option(None, "--cache-dir", help="Cache responses here; identical requests are not re-sent.")
_RECORD = typer.Option(None, "--record", help="Append every request and response to this JSONL file.")
_REPLAY = typer.Option(None, "--replay", help="Answer from a --record file instead of the endpoint.")
_RETRIES = typer.Option(4, "--retries", min=0, help="Retries of a failed request (429, 5xx, unreachable).")
_TIMEOUT = typer.Option(60.0, "--timeout", min=0.1, metavar="SECONDS",
                        help="Seconds to wait for one LLM answer before it counts as failed (and is retried); "
                             "reasoning models may need several minutes.")
_MCTS = typer.Option(None, "--mcts", min=1, help="Search with MCTS, at most N LLM expansions (instead of "
                     "--attempts); the tree log (.tree.json) and picture (.tree.png) go next to the plan.")
_WORKERS = typer.Option(1, "--workers", min=1, help="With --mcts: expansions run at once (one sandbox each).")
_IMAGES = typer.Option(False, "--images", help="Send the head camera's view of the scene, its key points and axes "
                       "drawn and labelled, as an image part (the endpoint's model must take images; see it with "
                       "`hgen generate prompt TASK --images view.png`).")


def _fail(message: str, code: int = 1) -> None:
    typer.secho(message, fg=typer.colors.RED, err=True)
    raise typer.Exit(code)


def _client(base_url: str | None, model: str | None, cache_dir: Path | None, record: Path | None,
            replay: Path | None, retries: int = 4, timeout: float = 60.0):
    from humanoidgen.llm import LLMClient, LLMConfig

    if record is not None and replay is not None:
        _fail("use --record or --replay, not both")
    mode = "replay" if replay else "record" if record else "live"
    cfg = LLMConfig.from_env(base_url=base_url, model=model, cache_dir=cache_dir, mode=mode,
                             recording_path=replay or record, max_retries=retries, timeout_s=timeout)
    if mode != "replay" and not cfg.base_url:
        _fail("no LLM endpoint configured: set $OPENAI_BASE_URL (and $OPENAI_API_KEY) or pass --base-url, "
              "or answer from a recording with --replay", EXIT_NOT_CONFIGURED)
    return LLMClient(cfg)


def _llm_errors():
    from humanoidgen.llm import LLMError, LLMNotConfigured

    return LLMError, LLMNotConfigured


@contextlib.contextmanager
def _reported_errors():
    """The user's errors as one red line and an exit code: 3 when no endpoint is configured, else 1."""
    LLMError, NotConfigured = _llm_errors()
    try:
        yield
    except NotConfigured as exc:
        _fail(str(exc), EXIT_NOT_CONFIGURED)
    except (LLMError, KeyError, FileNotFoundError, ValueError) as exc:
        _fail(str(exc).strip("'\""))


@app.command()
def scene(
    description: str = typer.Argument(..., help="What the task is, in words."),
    out: Path = typer.Option(..., "--out", "-o", help="Where to write the task YAML."),
    max_repairs: int = typer.Option(2, min=0, help="How many times invalid specs are sent back for repair."),
    log: Path = typer.Option(None, "--log", help="Write every turn (prompt, answer, problems, tokens) as JSON."),
    base_url: str = _BASE_URL, model: str = _MODEL, cache_dir: Path = _CACHE, record: Path = _RECORD,
    replay: Path = _REPLAY, retries: int = _RETRIES, timeout: float = _TIMEOUT,
    images: bool = typer.Option(False, "--images", help="Repair prompts carry the head camera's view of the "
                                "scene the last spec builds, annotated (the model must take images)."),
    robot: str = robot_option(),
) -> None:
    """Generate a task spec (objects, layout, success predicates) from a description, validated in simulation.

    Example: hgen generate scene "put cube 1 on cube 0 with the right hand" --out stack.yaml
    """
    select_robot(robot)
    os.environ.setdefault("MUJOCO_GL", "egl")
    from humanoidgen.generation.scene_gen import SceneGenerationError, generate_scene

    client = _client(base_url, model, cache_dir, record, replay, retries, timeout)
    LLMError, NotConfigured = _llm_errors()
    turns = None
    try:
        spec, turns = generate_scene(description, client, max_repairs=max_repairs, out=out, images=images)
    except SceneGenerationError as exc:
        turns = exc.log
        _fail(str(exc))
    except NotConfigured as exc:
        _fail(str(exc), EXIT_NOT_CONFIGURED)
    except LLMError as exc:
        _fail(str(exc))
    finally:
        if log is not None and turns is not None:
            _write_scene_log(log, turns)
    tokens = sum(t["tokens"]["total"] or 0 for t in turns)
    typer.echo(f"wrote {out} (task {spec.name}, {len(spec.objects)} objects, {len(turns)} turn(s), "
               f"{tokens} tokens); run it with: hgen run {out} --script PLAN.py")


def _write_scene_log(path: Path, turns: list[dict]) -> None:
    """The scene turns as JSON, redacted: a prompt (the user's description) or an answer may quote a key."""
    from humanoidgen.llm.redact import redact

    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(redact(turns), indent=1))


@app.command()
def prompt(
    task: str = typer.Argument(..., help="A task name (see `hgen tasks`) or a task YAML file; with --kind scene, "
                                         "a description in words or a task whose description is used."),
    kind: str = typer.Option("script", "--kind", help="Which prompt: script (generate script's first prompt), "
                             "scene (generate scene's) or mcts (the tree search's root expansion)."),
    seed: int = typer.Option(None, help="Scene seed (default: the task's default layout)."),
    out: Path = typer.Option(None, "--out", "-o", help="Write the prompt here instead of printing it."),
    images: Path = typer.Option(None, "--images", help="Also write the picture that --images sends with this "
                                "prompt (PNG) here."),
    robot: str = robot_option(),
) -> None:
    """Print the exact prompt an LLM gets for a task, without an endpoint.

    Example: hgen generate prompt open_drawer --kind script --seed 3 > prompt.md
    Example: hgen generate prompt open_drawer --seed 3 --images view.png (the picture --images sends)
    """
    select_robot(robot)
    os.environ.setdefault("MUJOCO_GL", "egl")
    if kind not in ("script", "scene", "mcts"):
        _fail(f"unknown --kind {kind!r}: choose script, scene or mcts")
    if images is not None and kind == "scene":
        _fail("--images: the first scene prompt has no picture (there is no scene yet); with --images, "
              "generate scene shows the scene a spec builds in its repair prompts")
    from humanoidgen.generation import prompt_preview, prompts

    with _reported_errors():
        if kind == "scene":
            text = prompts.scene_prompt(_description_of(task))
        else:
            view = prompt_preview.scene_view(task, seed)
            if kind == "script":
                text = prompt_preview.script_prompt(view)
            else:
                from humanoidgen.generation.script_gen import step_names
                from humanoidgen.mcts.prompt import root_prompt

                text = root_prompt(view, step_names())
        if images is not None:
            _write_picture(task, seed, images)
    if out is None:
        typer.echo(text)
    else:
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text)
        typer.echo(f"wrote {out} ({len(text)} characters)")


def _write_picture(task: str, seed: int | None, path: Path) -> None:
    from humanoidgen.generation.scene_image import HEIGHT, WIDTH, scene_png

    png = scene_png(task, seed)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(png)
    typer.echo(f"wrote {path} (the picture --images sends: {WIDTH}x{HEIGHT} PNG, {len(png)} bytes)", err=True)


def _description_of(task: str) -> str:
    """A known task's (or task file's) description; anything else is taken as the description itself."""
    from humanoidgen.tasks.registry import load_task

    if Path(task).suffix in (".yaml", ".yml"):
        return load_task(task).description  # a task file: its errors are the user's to see
    try:
        return load_task(task).description
    except KeyError:  # not a task name: a description in words, as `generate scene` takes it
        return task


@app.command()
def script(
    task: str = typer.Argument(..., help="A task name (see `hgen tasks`) or a task YAML file."),
    out: Path = typer.Option(..., "--out", "-o", help="Where to write the successful plan (`# step:` format)."),
    attempts: int = typer.Option(3, min=1, help="Attempts; each failure is described in the next prompt."),
    seed: int = typer.Option(None, help="Scene seed (default: the task's default layout)."),
    log: Path = typer.Option(None, "--log", help="Attempt log: JSON, or JSONL when the name ends in .jsonl."),
    step_timeout: float = typer.Option(120.0, min=1.0, help="Seconds one step may run before it is stopped."),
    base_url: str = _BASE_URL, model: str = _MODEL, cache_dir: Path = _CACHE, record: Path = _RECORD,
    replay: Path = _REPLAY, retries: int = _RETRIES, mcts: int = _MCTS, workers: int = _WORKERS,
    timeout: float = _TIMEOUT, images: bool = _IMAGES,
    robot: str = robot_option(),
) -> None:
    """Generate a demonstration script for a task, run it in a sandbox, retry with the failure explained.

    Example: hgen generate script block_stack_single --attempts 3 --out plan.py --log log.json
    (then: hgen run block_stack_single --script plan.py)

    With --mcts N: tree search over LLM continuations, e.g. --mcts 20 --workers 4 (--log: the tree log).
    """
    select_robot(robot)
    os.environ.setdefault("MUJOCO_GL", "egl")
    from humanoidgen.generation.script_gen import generate_script

    client = _client(base_url, model, cache_dir, record, replay, retries, timeout)
    if mcts is not None:
        _script_mcts(task, client, mcts, workers, seed, step_timeout, out, log, images)
        return
    with _reported_errors():
        result = generate_script(task, client, attempts=attempts, seed=seed, step_timeout_s=step_timeout,
                                 out=out, log_path=log, images=images)
    for a in result.attempts:
        verdict = "success" if a.success else a.failure.splitlines()[0] if a.failure else "failed"
        typer.echo(f"attempt {a.attempt}: {len(a.steps)} step(s) run, {a.tokens.get('total')} tokens: {verdict}")
    if not result.success:
        _fail(f"no successful plan for {result.task} in {attempts} attempt(s)" + (f"; see {log}" if log else ""))
    typer.echo(f"wrote {out}; replay it with: hgen run {task} --script {out}")


def _script_mcts(task: str, client, expansions: int, workers: int, seed: int | None, step_timeout: float,
                 out: Path, log: Path | None, images: bool = False) -> None:
    from humanoidgen.mcts import search_plan

    with _reported_errors():
        result = search_plan(task, client, expansions=expansions, workers=workers, seed=seed, out=out,
                             log_path=log, step_timeout_s=step_timeout, images=images)
    for e in result.log:
        verdict = "success" if e.get("success") else (e.get("failure") or {}).get("error", "no success yet")
        typer.echo(f"expansion {e['id'] + 1} at node {e['node']}: {len(e['new_nodes'])} new node(s), reward "
                   f"{e['reward']:g}, {e['tokens']} tokens: {verdict.splitlines()[0] if verdict else ''}")
    tree_log = log or out.with_suffix(".tree.json")
    if not result.success:
        _fail(f"no successful plan for {result.task} in {expansions} expansion(s); tree log: {tree_log}")
    typer.echo(f"replayed from a fresh reset: {'success' if result.verified else 'FAILED'}")
    typer.echo(f"wrote {out} (tree log {tree_log}, picture {out.with_suffix('.tree.png')}); "
               f"replay it with: hgen run {task} --script {out}")


@app.command("eval")
def eval_(
    tasks: str = typer.Option(..., "--tasks", help="Comma-separated task names or YAML paths."),
    trials: int = typer.Option(5, min=1, help="Trials per task (trial i uses the scene of seed i)."),
    attempts: int = typer.Option(1, min=1, help="Attempts per trial."),
    json_out: Path = typer.Option(None, "--json", help="Write the table rows as JSON."),
    step_timeout: float = typer.Option(120.0, min=1.0, help="Seconds one step may run."),
    base_url: str = _BASE_URL, model: str = _MODEL, cache_dir: Path = _CACHE, record: Path = _RECORD,
    replay: Path = _REPLAY, retries: int = _RETRIES, mcts: int = _MCTS, workers: int = _WORKERS,
    timeout: float = _TIMEOUT, images: bool = _IMAGES,
    robot: str = robot_option(),
) -> None:
    """Success rate and token cost of script generation per task.

    Example: hgen generate eval --tasks block_stack_single,open_drawer --trials 5 --json eval.json
    """
    select_robot(robot)
    os.environ.setdefault("MUJOCO_GL", "egl")
    from rich.console import Console
    from rich.table import Table

    from humanoidgen.generation.evaluate import evaluate

    names = [t.strip() for t in tasks.split(",") if t.strip()]
    client = _client(base_url, model, cache_dir, record, replay, retries, timeout)
    if mcts is not None:
        _eval_mcts(names, trials, client, mcts, workers, step_timeout, json_out, images)
        return
    with _reported_errors():
        rows = evaluate(names, trials, client, attempts=attempts, step_timeout_s=step_timeout, images=images)
    table = Table("task", "success rate", "mean tokens", "tokens per success", "mean attempts")
    for r in rows:
        table.add_row(r.task, f"{r.successes}/{r.trials} ({100 * r.success_rate:.0f}%)", f"{r.mean_tokens:.0f}",
                      "-" if r.tokens_per_success is None else f"{r.tokens_per_success:.0f}", f"{r.mean_attempts:.1f}")
    Console().print(table)
    if json_out is not None:
        json_out.write_text(json.dumps([r.to_dict() for r in rows], indent=1))


def _eval_mcts(names: list[str], trials: int, client, expansions: int, workers: int, step_timeout: float,
               json_out: Path | None, images: bool = False) -> None:
    from rich.console import Console
    from rich.table import Table

    from humanoidgen.mcts import evaluate_mcts

    with _reported_errors():
        rows = evaluate_mcts(names, trials, client, expansions=expansions, workers=workers,
                             step_timeout_s=step_timeout, images=images)
    table = Table("task", "success rate", "tokens per run", "tokens per success", "distinct plans", "verified")
    for r in rows:
        table.add_row(r.task, f"{r.successes}/{r.trials} ({100 * r.success_rate:.0f}%)", f"{r.tokens_per_run:.0f}",
                      "-" if r.tokens_per_success is None else f"{r.tokens_per_success:.0f}", str(r.distinct_plans),
                      str(r.verified))
    Console().print(table)
    if json_out is not None:
        json_out.write_text(json.dumps([r.to_dict() for r in rows], indent=1))
