"""MkDocs hook: serve bench/results' pictures and JSON files in the site without copying them into docs/.

The measured results live in bench/results/ (written by the benchmark scripts, one place for each figure).
MkDocs only serves files under docs/, so this hook adds them to the build as generated files:
bench/results/NAME.png -> results/img/NAME.png and bench/results/NAME.json -> results/data/NAME.json. Pages link
them relatively (from docs/results/x.md: `img/NAME.png`), and `mkdocs build --strict` checks those links.
"""

from __future__ import annotations

from pathlib import Path

from mkdocs.structure.files import File, Files

TABLE_MARK = "<!-- recoveries-table -->"

RESULTS = Path(__file__).resolve().parent.parent / "bench" / "results"
SERVED = {".png": "results/img", ".json": "results/data"}


def on_files(files: Files, config) -> Files:
    for path in sorted(RESULTS.iterdir()):
        folder = SERVED.get(path.suffix)
        if folder is None or not path.is_file():
            continue
        files.append(File.generated(config, f"{folder}/{path.name}", abs_src_path=str(path)))
    return files


def recoveries_table() -> str:
    """The planning pipeline's recoveries as a Markdown table, from its registry (planning/pipeline.py)."""
    from humanoidgen.planning.pipeline import design_table

    rows = ["| # | stage | when | recovery | answers | tries | event |", "|---|---|---|---|---|---|---|"]
    for k, r in enumerate(design_table(), 1):
        rows.append(f"| {k} | {r['stage']} | {r['trigger']} | `{r['recovery']}` (`{r['file']}`) | {r['answers']} | "
                    f"{r['tries']} | {r['event']} |".replace("<", "&lt;"))
    return "\n".join(rows)


def on_page_markdown(markdown: str, page, config, files) -> str:
    """The design page's table of recoveries is generated from the registry at every build."""
    return markdown.replace(TABLE_MARK, recoveries_table()) if TABLE_MARK in markdown else markdown


def on_serve(server, config, builder):
    server.watch(str(RESULTS))
    return server
