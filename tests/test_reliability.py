"""Damaged inputs a hostile user (or a full disk) produces: each gives one clear line and a non-zero exit, never a
traceback, and nothing already collected is lost.

1. dataset files: truncated / random episode files, torn or garbled index lines, a broken meta.json;
2. task YAML with NaN, infinite or absurd numbers;
3. the LLM client: malformed 200 answers, empty choices, Retry-After, --timeout, secrets never written.
"""

from __future__ import annotations

import email.utils
import json
import logging
import os
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
import yaml  # noqa: E402
from typer.testing import CliRunner  # noqa: E402

from humanoidgen.cli.main import app  # noqa: E402
from humanoidgen.episodes import collect as collect_mod  # noqa: E402
from humanoidgen.episodes.dataset import DatasetError, EpisodeStore  # noqa: E402
from humanoidgen.llm import LLMClient, LLMConfig, LLMRateLimited, LLMServerError  # noqa: E402
from humanoidgen.llm import client as client_mod  # noqa: E402
from humanoidgen.llm.errors import LLMBadResponse  # noqa: E402
from humanoidgen.llm.fake_server import Response, ScriptedServer  # noqa: E402
from humanoidgen.llm.redact import REDACTED, redact, redact_text, watch_env  # noqa: E402
from humanoidgen.tasks.registry import SPECS_DIR, TaskSpecError, parse_task  # noqa: E402

TASK = "block_stack_single"
NAMES = [f"joint_{i}" for i in range(26)]


def _one_line_error(res, *needles: str) -> str:
    """The command failed with a short message naming `needles`, not a traceback."""
    assert res.exit_code != 0, res.output
    assert res.exception is None or isinstance(res.exception, SystemExit), repr(res.exception)
    err = res.stderr
    assert "Traceback" not in res.output and "Traceback" not in err
    for n in needles:
        assert n in err, err
    return err


# -- 1. dataset files ------------------------------------------------------------------------------------------
def _arrays(seed: int) -> dict[str, np.ndarray]:
    t = 4 + seed % 3
    rng = np.random.default_rng(seed)
    return {"action": rng.normal(size=(t, 26)).astype(np.float32),
            "joint_pos": rng.normal(size=(t, 26)).astype(np.float32),
            "ee_pose": rng.normal(size=(t, 14)).astype(np.float32),
            "qpos": rng.normal(size=(t, 40)), "time": 0.2 * np.arange(t),
            "rgb/head": rng.integers(0, 255, size=(t, 16, 16, 3), dtype=np.uint8)}


@pytest.fixture
def fake_attempts(monkeypatch):
    """Collection without simulation: every seed but multiples of 4 succeeds with small synthetic arrays."""
    seen: list[int] = []

    def attempt(req):
        seen.append(req.seed)
        ok = req.seed % 4 != 3
        return {"seed": req.seed, "success": ok, "error": "" if ok else "scripted failure"}, \
            (_arrays(req.seed) if ok else None)

    monkeypatch.setattr(collect_mod, "_attempt", attempt)
    return seen


@pytest.fixture
def dataset(tmp_path, fake_attempts) -> Path:
    root = tmp_path / "ds"
    stats = collect_mod.collect(TASK, 4, root)
    assert stats.kept == 4
    return root


def _truncate(path: Path) -> None:
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def _damage(store: EpisodeStore) -> None:
    """Episode 1 cut to half its bytes, episode 2 random bytes."""
    _truncate(store.episode_path(1))
    store.episode_path(2).write_bytes(np.random.default_rng(0).bytes(3000))


def test_damaged_episode_files_are_detected(dataset):
    store = EpisodeStore(dataset)
    _damage(store)
    assert set(store.corrupt()) == {1, 2}
    with pytest.raises(DatasetError, match="episode_000001.npz"):
        store.load(1)
    with pytest.raises(DatasetError, match="episode_000002.npz"):
        store.verify()
    assert store.load(0)["action"].shape[1] == 26  # the rest stays readable


def test_info_names_damaged_files_and_still_shows_the_rest(dataset):
    _damage(EpisodeStore(dataset))
    res = CliRunner().invoke(app, ["dataset", "info", str(dataset)])
    err = _one_line_error(res, "episode_000001.npz", "episode_000002.npz", "--resume")
    assert "4 episodes kept" in res.stdout and "action" in res.stdout  # summary and array table still shown
    assert len([ln for ln in err.splitlines() if ln.strip()]) == 3  # one line per damaged file, one summary


def test_export_and_replay_name_the_damaged_file(dataset, tmp_path):
    _truncate(EpisodeStore(dataset).episode_path(2))
    runner = CliRunner()
    res = runner.invoke(app, ["dataset", "export", str(dataset), "--zarr", str(tmp_path / "d.zarr")])
    _one_line_error(res, "episode_000002.npz")
    lerobot = tmp_path / "lerobot"
    res = runner.invoke(app, ["dataset", "export", str(dataset), "--lerobot", str(lerobot),
                              "--lerobot-cameras", "head"])
    _one_line_error(res, "episode_000002.npz")
    assert not lerobot.exists(), "no half-written LeRobot dataset is left behind"
    res = runner.invoke(app, ["dataset", "replay", str(dataset), "--episode", "2", "--video",
                              str(tmp_path / "v.mp4")])
    _one_line_error(res, "episode_000002.npz")
    res = runner.invoke(app, ["dataset", "replay", str(dataset), "--episode", "9", "--video",
                              str(tmp_path / "v.mp4")])
    _one_line_error(res, "episode 9")


def test_resume_recollects_damaged_episodes_and_keeps_the_rest(dataset, fake_attempts):
    store = EpisodeStore(dataset)
    _damage(store)
    good = {i: store.load(i)["action"] for i in (0, 3)}
    tried_before = len(store.attempts())
    stats = collect_mod.collect(TASK, 4, dataset, resume=True)
    assert stats.kept == 4
    store = EpisodeStore(dataset)
    assert store.corrupt() == {}
    kept = [k["episode"] for k in store.kept()]
    assert len(kept) == 4 and {0, 3} <= set(kept) and not {1, 2} & set(kept)
    for i, action in good.items():  # nothing that was fine is lost or rewritten
        assert np.array_equal(store.load(i)["action"], action)
    seeds = [a["seed"] for a in store.attempts()]
    assert len(seeds) == len(set(seeds)) and len(seeds) > tried_before
    # The damaged files are kept aside, the index before the repair too.
    assert (dataset / "episodes" / "episode_000001.npz.corrupt").is_file()
    assert (dataset / "episodes" / "episode_000002.npz.corrupt").is_file()
    assert (dataset / "index.jsonl.bak").is_file()
    dropped = [a for a in store.attempts() if a.get("dropped_episode") is not None]
    assert sorted(a["dropped_episode"] for a in dropped) == [1, 2] and not any(a["success"] for a in dropped)
    res = CliRunner().invoke(app, ["dataset", "info", str(dataset)])
    assert res.exit_code == 0, res.output


def test_torn_and_garbled_index_lines(dataset, fake_attempts):
    store = EpisodeStore(dataset)
    lines = store.index_path.read_text().splitlines()
    # A garbled line in the middle, and a last line cut short by an interruption.
    lines.insert(2, '{"seed": "x", "succ')
    store.index_path.write_text("\n".join(lines) + '\n{"seed": 99, "succ')
    assert len(store.kept()) == 4  # lines after the garbled one still count
    assert len(store.index_problems()) == 2
    res = CliRunner().invoke(app, ["dataset", "info", str(dataset)])
    assert res.exit_code == 0 and "4 episodes kept" in res.stdout
    assert "line 3" in res.stderr and "cut short" in res.stderr and "Traceback" not in res.output
    # add() after a torn line starts a new line: the new record is not swallowed.
    stats = collect_mod.collect(TASK, 6, dataset, resume=True)
    assert stats.kept == 6 and len(EpisodeStore(dataset).kept()) == 6
    assert EpisodeStore(dataset).index_problems() == []


def test_add_after_torn_line_without_repair(tmp_path):
    store = EpisodeStore(tmp_path / "s")
    store.create({"task": "synthetic"})
    store.add({"seed": 0, "success": True}, _arrays(0))
    with open(store.index_path, "a") as f:
        f.write('{"seed": 1, "succ')
    store.add({"seed": 2, "success": True}, _arrays(2))
    assert [a["seed"] for a in store.attempts()] == [0, 2]
    assert [k["episode"] for k in store.kept()] == [0, 1]


def test_broken_meta_json_is_one_line(dataset):
    store = EpisodeStore(dataset)
    store.meta_path.write_text('{"task": "block_st')
    runner = CliRunner()
    _one_line_error(runner.invoke(app, ["dataset", "info", str(dataset)]), "meta.json", "not valid JSON")
    _one_line_error(runner.invoke(app, ["collect", TASK, "-n", "5", "--out", str(dataset), "--resume"]),
                    "meta.json")
    store.meta_path.write_text("[1, 2]")
    _one_line_error(runner.invoke(app, ["dataset", "export", str(dataset), "--zarr", str(dataset / "z")]),
                    "meta.json")


# -- 2. task YAML ------------------------------------------------------------------------------------------------
def _base_task() -> dict:
    return yaml.safe_load((SPECS_DIR / "pyramid_stack.yaml").read_text())


NAN, INF = float("nan"), float("inf")
BAD_TASKS = [
    (lambda d: d["objects"][0].__setitem__("pos", [NAN, 0.1]), "objects.0.pos"),
    (lambda d: d["objects"][1].__setitem__("pos", [-0.3, 0.1, INF]), "objects.1.pos"),
    (lambda d: d["objects"][0].__setitem__("pos", [-30.0, 0.1]), "objects.0.pos"),
    (lambda d: d["objects"][2].__setitem__("yaw_deg", NAN), "objects.2.yaw_deg"),
    (lambda d: d["objects"][2].__setitem__("yaw_deg", 1e9), "objects.2.yaw_deg"),
    (lambda d: d["randomization"].__setitem__("position", [0, NAN, 0, 0]), "randomization.position"),
    (lambda d: d["randomization"].__setitem__("position", [0, 20, 0, 0]), "randomization.position"),
    (lambda d: d["randomization"].__setitem__("yaw_deg", [-INF, 0]), "randomization.yaw_deg"),
    (lambda d: d["success"][0].__setitem__("xy_tol", INF), "success.0"),
    (lambda d: d["success"][0].__setitem__("xy_tol", 3.0), "success.0"),
    (lambda d: d["success"][0].__setitem__("z_tol", 0), "success.0"),
    (lambda d: d["success"][0].__setitem__("base_gap", NAN), "success.0"),
    (lambda d: d.__setitem__("time_limit_s", INF), "time_limit_s"),
    (lambda d: d.__setitem__("time_limit_s", 1e12), "time_limit_s"),
]


@pytest.mark.parametrize("mutate,field", BAD_TASKS)
def test_absurd_task_numbers_are_validation_errors(mutate, field):
    d = _base_task()
    mutate(d)
    with pytest.raises(TaskSpecError) as exc:
        parse_task(d, "bad.yaml")
    assert str(exc.value).startswith(f"bad.yaml: {field}"), str(exc.value)


def test_near_target_and_sane_tasks():
    d = _base_task()
    d["success"].append({"type": "near", "obj": "cube[0]", "target_xy": [NAN, 0.0]})
    with pytest.raises(TaskSpecError, match="target_xy"):
        parse_task(d, "bad.yaml")
    from humanoidgen.tasks.registry import list_tasks

    assert len(list_tasks()) >= 20  # every built-in task still validates


def test_cli_run_and_collect_reject_a_nan_task(tmp_path):
    bad = tmp_path / "bad.yaml"
    # YAML's own .nan, as a user would write it
    bad.write_text((SPECS_DIR / "pyramid_stack.yaml").read_text().replace("pos: [-0.385, 0.18]",
                                                                          "pos: [.nan, 0.18]"))
    runner = CliRunner()
    err = _one_line_error(runner.invoke(app, ["run", str(bad)]), "objects.0.pos", "finite")
    assert len(err.strip().splitlines()) == 1
    _one_line_error(runner.invoke(app, ["collect", str(bad), "-n", "1", "--out", str(tmp_path / "o")]),
                    "objects.0.pos")
    assert not (tmp_path / "o" / "meta.json").exists()


# -- 3. LLM client ------------------------------------------------------------------------------------------------
MSGS = [{"role": "user", "content": "Place the cube on the plate please"}]


def _cfg(url: str, **kw) -> LLMConfig:
    return LLMConfig(base_url=url, model="m", **{"timeout_s": 3.0, "max_retries": 2, "backoff_s": 0.01, **kw})


@pytest.fixture
def sleeps(monkeypatch) -> list[float]:
    """The client's retry delays, without sleeping them."""
    out: list[float] = []
    monkeypatch.setattr(client_mod, "_sleep", out.append)
    return out


@pytest.mark.parametrize("raw,ctype,needle", [
    ('{"choices": [{"message": ', "application/json", "not valid JSON"),
    ("<html><body>Welcome to nginx</body></html>", "text/html", "not valid JSON"),
    ("[1, 2, 3]", "application/json", "not a chat completion"),
    ('{"id": "x", "choices": []}', "application/json", "the endpoint returned no choices"),
    ('{"id": "x"}', "application/json", "the endpoint returned no choices"),
])
def test_malformed_200_answers_are_clear_errors(raw, ctype, needle):
    with ScriptedServer([Response.malformed(raw, content_type=ctype)]) as srv:
        with pytest.raises(LLMBadResponse, match=needle):
            LLMClient(_cfg(srv.base_url)).chat(MSGS)
        assert len(srv.requests) == 1  # not retried: the same endpoint answers the same way


def test_cli_malformed_answer_is_one_line(tmp_path):
    runner = CliRunner()
    with ScriptedServer(default=Response.malformed('{"choices": [')) as srv:
        res = runner.invoke(app, ["generate", "scene", "stack", "--out", str(tmp_path / "t.yaml"),
                                  "--base-url", srv.base_url])
    err = _one_line_error(res, "not valid JSON")
    assert len(err.strip().splitlines()) == 1
    with ScriptedServer(default=Response.malformed('{"choices": []}')) as srv:
        res = runner.invoke(app, ["generate", "script", TASK, "--out", str(tmp_path / "p.py"),
                                  "--base-url", srv.base_url])
    _one_line_error(res, "the endpoint returned no choices")


def test_retry_after_seconds_and_http_date_are_honoured(sleeps):
    later = email.utils.formatdate(time.time() + 7, usegmt=True)
    script = [Response.error(429, headers={"Retry-After": "5"}),
              Response.error(503, headers={"Retry-After": later}), "ok"]
    with ScriptedServer(script) as srv:
        assert LLMClient(_cfg(srv.base_url)).chat(MSGS).text == "ok"
    assert sleeps[0] == 5.0
    assert 5.0 <= sleeps[1] <= 7.5


def test_retry_after_is_capped_and_says_so(sleeps, caplog):
    caplog.set_level(logging.WARNING)
    with ScriptedServer([Response.error(429, headers={"Retry-After": "86400"}), "ok"]) as srv:
        LLMClient(_cfg(srv.base_url, retry_after_max_s=30)).chat(MSGS)
    assert sleeps == [30.0]
    assert "86400" in caplog.text and "cap" in caplog.text


def test_without_retry_after_backoff_applies(sleeps):
    with ScriptedServer([Response.error(500), Response.error(429), "ok"]) as srv:
        LLMClient(_cfg(srv.base_url, backoff_s=0.5)).chat(MSGS)
    assert sleeps == [0.5, 1.0]
    with ScriptedServer([Response.error(503, headers={"Retry-After": "2"})] * 3) as srv:
        with pytest.raises(LLMServerError, match="gave up after 3"):
            LLMClient(_cfg(srv.base_url)).chat(MSGS)
    with ScriptedServer([Response.error(429, headers={"retry-after-ms": "250"})] * 3) as srv:
        with pytest.raises(LLMRateLimited):
            LLMClient(_cfg(srv.base_url)).chat(MSGS)
    assert sleeps[2:] == [2.0, 2.0, 0.25, 0.25]


def test_retry_after_parsing():
    now = 1_700_000_000.0
    assert client_mod.retry_after_s({"retry-after": "3"}) == 3.0
    assert client_mod.retry_after_s({"retry-after": "-3"}) == 0.0
    assert client_mod.retry_after_s({"retry-after": "soon"}) is None
    assert client_mod.retry_after_s({"retry-after": "nan"}) is None
    assert client_mod.retry_after_s({}) is None
    date = email.utils.formatdate(now + 12, usegmt=True)
    assert client_mod.retry_after_s({"retry-after": date}, now=now) == pytest.approx(12.0)
    assert client_mod.retry_after_s({"retry-after": email.utils.formatdate(now - 60, usegmt=True)}, now=now) == 0


def test_timeout_option(tmp_path):
    runner = CliRunner()
    for cmd in ("scene", "script", "eval"):
        res = runner.invoke(app, ["generate", cmd, "--help"], terminal_width=200)
        assert "--timeout" in res.output, cmd
    with ScriptedServer([Response("late", delay_s=3.0)]) as srv:
        res = runner.invoke(app, ["generate", "scene", "stack", "--out", str(tmp_path / "t.yaml"),
                                  "--base-url", srv.base_url, "--retries", "0", "--timeout", "0.5"])
    _one_line_error(res, "no answer within 0.5s")


def test_redact_function(monkeypatch):
    monkeypatch.setenv("MY_LLM_CREDENTIAL", "cred-0123456789")
    watch_env("MY_LLM_CREDENTIAL")
    monkeypatch.setenv("OPENAI_API_KEY", "canary-abcdefgh")
    monkeypatch.setenv("HGEN_SHORT_TOKEN", "abc")  # too short to be a real secret: left alone
    text = ("key canary-abcdefgh, Authorization: Bearer xyz.123-456789abc, cred-0123456789, "
            "sk-proj-1234567890abcdefXYZ abc")
    out = redact_text(text)
    for secret in ("canary-abcdefgh", "xyz.123-456789abc", "cred-0123456789", "sk-proj-1234567890abcdefXYZ"):
        assert secret not in out
    assert out.endswith(" abc") and REDACTED in out
    nested = {"a": ["canary-abcdefgh", ("x", 1)], "canary-abcdefgh": 2.5}
    assert redact(nested) == {"a": [REDACTED, ("x", 1)], REDACTED: 2.5}
    assert nested["a"][0] == "canary-abcdefgh"  # not modified in place


CANARY = "hgen-canary-7d1f0e9a2b"


def _no_canary(root: Path, *outputs: str) -> list[Path]:
    files = [f for f in root.rglob("*") if f.is_file()]
    leaked = [f for f in files if CANARY.encode() in f.read_bytes()]
    assert not leaked, f"the API key was written to {leaked}"
    for o in outputs:
        assert CANARY not in o
    return files


def test_secrets_are_never_written_by_generate_scene(tmp_path, monkeypatch, sleeps):
    monkeypatch.setenv("OPENAI_API_KEY", CANARY)
    stack = (SPECS_DIR / "block_stack_single.yaml").read_text().replace("plan: block_stack_single.py", "")
    answer = f"The key you gave me is {CANARY}; Authorization: Bearer {CANARY}\n```yaml\n{stack}```\n"
    leak_body = {"error": {"message": f"overloaded (your key {CANARY}, header Bearer {CANARY})"}}
    out = tmp_path / "out"
    with ScriptedServer([Response.error(500, body=leak_body), answer], api_key=CANARY) as srv:
        res = CliRunner().invoke(app, [
            "generate", "scene", f"stack the cubes; my key is {CANARY}", "--out", str(out / "t.yaml"),
            "--log", str(out / "log.json"), "--cache-dir", str(out / "cache"), "--record", str(out / "rec.jsonl"),
            "--base-url", srv.base_url, "--retries", "1"])
        assert all(a == f"Bearer {CANARY}" for a in srv.auth_headers)  # the key was sent, as it must be
    assert res.exit_code == 0, res.output
    files = _no_canary(tmp_path, res.output)
    names = {f.name for f in files}
    assert {"t.yaml", "log.json", "rec.jsonl"} <= names and any(f.parent.name == "cache" for f in files)
    assert REDACTED in (out / "log.json").read_text()


def test_secrets_are_never_written_by_generate_script(tmp_path, monkeypatch, sleeps):
    from humanoidgen.episodes.plans import load_plan

    monkeypatch.setenv("OPENAI_API_KEY", CANARY)
    steps = [(s.title, s.code) for s in load_plan(SPECS_DIR / f"{TASK}.py").steps]
    steps[0] = (steps[0][0], f"# key {CANARY}\n{steps[0][1]}")
    plan = f"Using {CANARY}.\n" + "\n".join(f"```python\n# step: {t}\n{c}\n```" for t, c in steps)
    leak_body = {"error": {"message": f"busy; key {CANARY}"}}
    out = tmp_path / "out"
    args = ["--cache-dir", str(out / "cache"), "--record", str(out / "rec.jsonl"), "--retries", "1"]
    with ScriptedServer([Response.error(503, body=leak_body), plan], api_key=CANARY) as srv:
        res = CliRunner().invoke(app, ["generate", "script", TASK, "--out", str(out / "plan.py"),
                                       "--log", str(out / "log.jsonl"), "--base-url", srv.base_url, *args])
    assert res.exit_code == 0, res.output
    # MCTS: the tree log holds prompts and answers too.
    with ScriptedServer([plan], api_key=CANARY) as srv:
        res2 = CliRunner().invoke(app, ["generate", "script", TASK, "--out", str(out / "mcts.py"), "--mcts", "1",
                                        "--base-url", srv.base_url, "--record", str(out / "rec2.jsonl")])
    assert res2.exit_code == 0, res2.output
    files = _no_canary(tmp_path, res.output, res2.output)
    names = {f.name for f in files}
    assert {"plan.py", "log.jsonl", "rec.jsonl", "mcts.py", "mcts.tree.json", "rec2.jsonl"} <= names
    assert REDACTED in (out / "plan.py").read_text() and REDACTED in (out / "mcts.tree.json").read_text()
    assert json.loads((out / "log.jsonl").read_text().splitlines()[0])["success"] is True
