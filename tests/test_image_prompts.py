"""Image prompts (`--images`, issue 35 item 2): the annotated head-camera picture goes with the prompt as an image
part, only when asked; it is the picture `hgen generate prompt --images` writes; records keep it as a PNG file
beside the JSON lines and a replay makes the identical request; a text-only endpoint gives one clear line."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import base64  # noqa: E402
import io  # noqa: E402
import json  # noqa: E402
from pathlib import Path  # noqa: E402
from types import SimpleNamespace  # noqa: E402

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402
from typer.testing import CliRunner  # noqa: E402

from humanoidgen.cli.generate_cmd import app  # noqa: E402
from humanoidgen.generation import generate_scene  # noqa: E402
from humanoidgen.generation.scene_image import HEIGHT, WIDTH, scene_png  # noqa: E402
from humanoidgen.llm import LLMClient, LLMConfig, LLMImagesRejected  # noqa: E402
from humanoidgen.llm.fake_server import ScriptedServer  # noqa: E402
from humanoidgen.llm.images import PNG_PREFIX, images_dir_of, pngs, restored, stored, with_image  # noqa: E402
from humanoidgen.objects.draw import label_boxes  # noqa: E402

TASK = "block_stack_single"


def _client(srv: ScriptedServer, **kw) -> LLMClient:
    return LLMClient(LLMConfig(base_url=srv.base_url, model="scripted", backoff_s=0.01, max_retries=2, **kw))


def _image_parts(request: dict) -> list[dict]:
    return [p for m in request["messages"] if isinstance(m["content"], list) for p in m["content"]
            if p.get("type") == "image_url"]


@pytest.fixture(scope="module")
def view_png() -> bytes:
    return scene_png(TASK, 1)


# -- pure -----------------------------------------------------------------------------------------------------
def test_labels_do_not_overlap_each_other_or_leave_the_image() -> None:
    anchors = [(100.0 + 3 * i, 100.0 + 2 * i) for i in range(12)]  # a crowd of marks, as on a small object
    boxes = label_boxes([(80, 15)] * 12, anchors, 640, 480, dots=anchors)
    for i, a in enumerate(boxes):
        assert 0 <= a[0] and 0 <= a[1] and a[2] <= 640 and a[3] <= 480
        for b in boxes[:i]:
            assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]), (a, b)


def test_stored_request_keeps_a_hash_and_the_png_beside_it(tmp_path: Path, view_png: bytes) -> None:
    request = {"model": "m", "messages": [{"role": "user", "content": with_image("words", view_png, "cap")}]}
    kept = stored(request, tmp_path / "imgs")
    text = json.dumps(kept)
    assert PNG_PREFIX not in text and len(text) < 400  # no base64 in the record
    (png_file,) = (tmp_path / "imgs").iterdir()
    assert png_file.read_bytes() == view_png and png_file.stem in text
    assert restored(kept, tmp_path / "imgs") == request and pngs(request["messages"]) == [view_png]
    assert images_dir_of(Path("a/run.jsonl")) == Path("a/run.images")


# -- the picture ----------------------------------------------------------------------------------------------
def test_picture_is_deterministic_png_of_the_camera_size_and_depends_on_the_seed(view_png: bytes) -> None:
    img = Image.open(io.BytesIO(view_png))
    assert img.format == "PNG" and img.size == (WIDTH, HEIGHT)
    assert scene_png(TASK, 1) == view_png  # same (task, seed), same bytes
    assert scene_png(TASK, 2) != view_png  # another seed moves the cubes
    # Labels are drawn: white label boxes with black text near the cubes (the bare render has no pure white).
    rgb = np.asarray(img.convert("RGB"))
    assert (rgb == 255).all(axis=2).sum() > 2000


def test_prompt_command_writes_the_picture_that_is_sent(tmp_path: Path, view_png: bytes) -> None:
    res = CliRunner().invoke(app, ["prompt", TASK, "--seed", "1", "--images", str(tmp_path / "v.png"),
                                   "--out", str(tmp_path / "p.md")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "v.png").read_bytes() == view_png
    bad = CliRunner().invoke(app, ["prompt", "a cube", "--kind", "scene", "--images", str(tmp_path / "s.png")])
    assert bad.exit_code == 1 and "--images" in bad.output and not (tmp_path / "s.png").exists()


# -- what is sent, recorded and replayed ----------------------------------------------------------------------
def test_script_request_carries_the_picture_only_with_images_and_replays_identically(tmp_path: Path,
                                                                                    view_png: bytes) -> None:
    rec = tmp_path / "run.jsonl"
    args = ["script", TASK, "--seed", "1", "--attempts", "1", "--out", str(tmp_path / "plan.py")]
    with ScriptedServer(["no code here"] * 2) as srv:
        res = CliRunner().invoke(app, args + ["--base-url", srv.base_url, "--images", "--record", str(rec)])
        assert res.exit_code == 1 and "no successful plan" in res.output, res.output
        res = CliRunner().invoke(app, args + ["--base-url", srv.base_url])
        assert res.exit_code == 1, res.output
        with_img, without = srv.requests
    (part,) = _image_parts(with_img)
    assert part["image_url"]["url"].startswith(PNG_PREFIX)
    assert base64.b64decode(part["image_url"]["url"][len(PNG_PREFIX):]) == view_png
    assert with_img["messages"][0]["content"][0]["text"] == without["messages"][0]["content"]  # same words
    assert not _image_parts(without)
    # The record: a hash in the JSON line, the PNG beside it; restored, it is the request that was sent.
    line = rec.read_text()
    assert PNG_PREFIX not in line and len(line) < len(json.dumps(with_img)) / 2
    recorded = json.loads(line)["request"]
    assert restored(recorded, images_dir_of(rec))["messages"] == with_img["messages"]
    # Replay builds the identical request (its key is the full request's, picture included) with no endpoint.
    replay = CliRunner().invoke(app, args + ["--images", "--replay", str(rec), "--log", str(tmp_path / "l.json")])
    assert replay.exit_code == 1 and "no successful plan" in replay.output, replay.output
    log = json.loads((tmp_path / "l.json").read_text())
    assert log["attempts"][0]["cached"] and log["attempts"][0]["image"] == images_dir_of(rec).joinpath(
        next(images_dir_of(rec).iterdir()).name).stem
    # Without --images the replay asks for another request, which the recording does not hold.
    other = CliRunner().invoke(app, args + ["--replay", str(rec)])
    assert other.exit_code == 1 and "no recorded response" in other.output


def test_text_only_endpoint_gives_one_line_naming_images_and_the_endpoint(tmp_path: Path) -> None:
    log = tmp_path / "log.json"
    with ScriptedServer(["no code here"], vision=False) as srv:
        url = srv.base_url
        res = CliRunner().invoke(app, ["script", TASK, "--attempts", "1", "--images", "--out", str(tmp_path / "p.py"),
                                       "--base-url", url, "--log", str(log)])
        assert len(srv.requests) == 1  # not retried: another try cannot help
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert res.exit_code == 1 and len(lines) == 1, res.output
    assert "--images" in lines[0] and url in lines[0] and "HTTP 400" in lines[0]
    assert json.loads(log.read_text())["task"] == TASK  # the attempt log is still written
    with ScriptedServer(["hello"], vision=False) as srv, pytest.raises(LLMImagesRejected):
        _client(srv).chat([{"role": "user", "content": with_image("hi", scene_png(TASK, 1))}])
    with ScriptedServer(["hello"], vision=False) as srv:  # the same endpoint answers text
        assert _client(srv).chat([{"role": "user", "content": "hi"}]).text == "hello"


def test_cache_keeps_pictures_as_files(tmp_path: Path, view_png: bytes) -> None:
    messages = [{"role": "user", "content": with_image("hi", view_png)}]
    with ScriptedServer(["hello"]) as srv:
        client = _client(srv, cache_dir=tmp_path / "cache")
        assert client.chat(messages).text == "hello" and client.chat(messages).cached
        assert len(srv.requests) == 1
    entry = next((tmp_path / "cache").glob("*.json")).read_text()
    assert PNG_PREFIX not in entry
    assert [p.read_bytes() for p in (tmp_path / "cache" / "images").iterdir()] == [view_png]


def test_scene_repair_prompt_shows_the_scene_the_spec_builds() -> None:
    # A spec that parses and builds but has a problem (the cubes overlap): its repair prompt shows its scene.
    bad = """```yaml
name: two_cube_stack
description: With the right hand, put cube 1 on top of cube 0.
arms: single
horizon: short
objects:
  - {type: cube, type_id: 0, pos: [-0.32, -0.05]}
  - {type: cube, type_id: 1, pos: [-0.33, -0.06]}
success:
  - {type: stacked, objs: ["cube[0]", "cube[1]"]}
```"""
    with ScriptedServer([bad, "no yaml"]) as srv:
        with pytest.raises(Exception):
            generate_scene("two cubes", _client(srv), max_repairs=1, images=True)
        first, repair = srv.requests
    assert isinstance(first["messages"][0]["content"], str)  # no scene yet, no picture
    parts = _image_parts(repair)
    assert len(parts) == 1 and isinstance(repair["messages"][-1]["content"], list)
    assert "overlap" in repair["messages"][-1]["content"][0]["text"]


def test_mcts_expansions_carry_the_picture(view_png: bytes) -> None:
    from humanoidgen.mcts import MCTS, FakeExecutor, MCTSConfig
    from humanoidgen.tasks.registry import load_task

    sent = []

    class Client:
        def chat(self, messages):
            sent.append(messages[-1]["content"])
            return SimpleNamespace(text="no code", usage=SimpleNamespace(total=1), cached=False)

    spec = load_task(TASK).model_dump(mode="json")
    result = MCTS(spec, Client(), [FakeExecutor(goal=["x"])], seed=1,
                  config=MCTSConfig(expansions=2, verify=False, images=True)).run()
    assert len(sent) == 2 and all(pngs([{"content": c}]) == [view_png] for c in sent)
    assert all(e["image"] for e in result.log)


def test_eval_and_mcts_commands_pass_images_on(tmp_path: Path, view_png: bytes) -> None:
    with ScriptedServer(default="no code here") as srv:
        res = CliRunner().invoke(app, ["eval", "--tasks", TASK, "--trials", "2", "--images", "--base-url",
                                       srv.base_url])
        assert res.exit_code == 0, res.output
        res = CliRunner().invoke(app, ["script", TASK, "--seed", "1", "--mcts", "1", "--images", "--base-url",
                                       srv.base_url, "--out", str(tmp_path / "plan.py")])
        assert res.exit_code == 1 and "no successful plan" in res.output, res.output
        seed0, seed1, mcts = srv.requests
    assert [pngs(r["messages"]) for r in (seed1, mcts)] == [[view_png], [view_png]]  # trial i: the scene of seed i
    assert pngs(seed0["messages"]) == [scene_png(TASK, 0)]
