"""MkDocs hooks: serve bench/results' pictures and JSON files in the site without copying them into docs/, and
fill the pages' generated sections (the recoveries table, the planner API reference, the annotation vocabulary).

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


def api_reference() -> str:
    """The planner API reference the prompts show (generation/api_reference.py), with the example of each
    statement about what the calls accept (tests/test_api_reference.py runs them)."""
    from humanoidgen.generation.api_reference import facts, reference

    examples = "\n\n".join(f"- {f['statement']}\n\n```python\n{f['example'].strip()}\n```" for f in facts())
    return reference().replace("### ", "## ") + "\n\n## the statements, run\n\n" \
        "Each example runs on its task's scene in the tests; its asserts are the statement.\n\n" + examples


def annotation_vocabulary() -> str:
    """What every family's points, axes and openness mean (generation/object_text.py: the prompts' text)."""
    from humanoidgen.generation.object_text import all_families_text

    return all_families_text(indent="    ")


# Markers a page holds, replaced at every build by text generated from the code and data.
GENERATED = {
    TABLE_MARK: recoveries_table,
    "<!-- planner-api-reference -->": api_reference,
    "<!-- annotation-vocabulary -->": annotation_vocabulary,
}


def on_page_markdown(markdown: str, page, config, files) -> str:
    """The design page's table of recoveries, the planner API reference and the objects' annotation vocabulary
    are generated at every build."""
    for mark, make in GENERATED.items():
        if mark in markdown:
            markdown = markdown.replace(mark, make())
    return markdown


def on_serve(server, config, builder):
    server.watch(str(RESULTS))
    return server
