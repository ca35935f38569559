"""MkDocs hook: serve bench/results' pictures and JSON files in the site without copying them into docs/.

The measured results live in bench/results/ (written by the benchmark scripts, one place for each figure).
MkDocs only serves files under docs/, so this hook adds them to the build as generated files:
bench/results/NAME.png -> results/img/NAME.png and bench/results/NAME.json -> results/data/NAME.json. Pages link
them relatively (from docs/results/x.md: `img/NAME.png`), and `mkdocs build --strict` checks those links.
"""

from __future__ import annotations

from pathlib import Path

from mkdocs.structure.files import File, Files

RESULTS = Path(__file__).resolve().parent.parent / "bench" / "results"
SERVED = {".png": "results/img", ".json": "results/data"}


def on_files(files: Files, config) -> Files:
    for path in sorted(RESULTS.iterdir()):
        folder = SERVED.get(path.suffix)
        if folder is None or not path.is_file():
            continue
        files.append(File.generated(config, f"{folder}/{path.name}", abs_src_path=str(path)))
    return files


def on_serve(server, config, builder):
    server.watch(str(RESULTS))
    return server
