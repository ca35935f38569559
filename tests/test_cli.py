"""`hgen` from a user's point of view."""

import numpy as np
from PIL import Image
from typer.testing import CliRunner

from humanoidgen.cli.main import app

runner = CliRunner()


def test_help_lists_commands():
    res = runner.invoke(app, ["--help"])
    assert res.exit_code == 0
    for cmd in ("render", "assets"):
        assert cmd in res.output
    res = runner.invoke(app, ["render", "--help"])
    assert res.exit_code == 0 and "Example" in res.output


def test_render_writes_a_six_camera_mosaic(tmp_path):
    out = tmp_path / "scene.png"
    res = runner.invoke(app, ["render", "--out", str(out), "--width", "96", "--height", "72", "--settle", "0.1"])
    assert res.exit_code == 0, res.output
    img = np.asarray(Image.open(out))
    assert img.shape == (2 * 72, 3 * 96, 3)
    tiles = [img[r * 72:(r + 1) * 72, c * 96:(c + 1) * 96] for r in range(2) for c in range(3)]
    assert all(t.std() > 10 for t in tiles), "every camera tile shows something"


def test_render_rejects_unknown_modality(tmp_path):
    res = runner.invoke(app, ["render", "--out", str(tmp_path / "x.png"), "--modality", "thermal"])
    assert res.exit_code != 0
    assert "rgb, depth or segmentation" in res.output


def test_missing_assets_give_one_clear_message(tmp_path, monkeypatch):
    monkeypatch.setenv("HGEN_ASSETS", str(tmp_path / "nowhere"))
    res = runner.invoke(app, ["render", "--out", str(tmp_path / "x.png")])
    assert res.exit_code == 1
    assert "HGEN_ASSETS" in res.output


def test_assets_list_shows_families_models_and_annotations():
    res = runner.invoke(app, ["assets", "list"])
    assert res.exit_code == 0, res.output
    for family in ("cube", "bottle", "can", "cup", "bowl", "plate", "pot", "drawer", "laptop", "box", "safe",
                   "toaster"):
        assert f"{family} (" in res.output
    assert "grasp_point_base_right_hand" in res.output


def test_assets_show_draws_annotations(tmp_path):
    out = tmp_path / "drawer.png"
    res = runner.invoke(app, ["assets", "show", "drawer", "--out", str(out)])
    assert res.exit_code == 0, res.output
    img = np.asarray(Image.open(out))
    assert img.shape == (480, 1280, 3)  # two openness values side by side
    res = runner.invoke(app, ["assets", "show", "unicorn", "--out", str(tmp_path / "u.png")])
    assert res.exit_code == 1 and "known types" in res.output
