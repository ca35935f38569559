"""The unseen cheating battery (tests/cheats_unseen/NNN_*.py) through `hgen run --json` and `collect`.

Each file is a complete plan for the task in its `# task:` header; a `# cheat:` header says what it forges and
an `# honest: yes` header marks a control plan that must still succeed. For every plan this runs
`hgen run TASK --seed S --script FILE --json out.json` (a subprocess: the console path) and `collect(...)` with
one attempt and a camera-less recorder (the dataset path `hgen collect` runs), and records whether it was judged
a success, whether an episode was kept and the reason printed. Run from the repository root:

    PYTHONPATH=$PWD HGEN_ASSETS=/work/shared/assets python bench/cheats_unseen.py [--only 034,040] [--no-collect]

Writes bench/results/cheats_unseen.json.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

ROOT = Path(__file__).resolve().parent.parent
DIR = ROOT / "tests" / "cheats_unseen"
_HEADER = re.compile(r"^#\s*(task|cheat|honest):\s*(.*?)\s*$")


def battery() -> list[dict]:
    """[{name, path, task, cheat, honest}] for every tests/cheats_unseen/NNN_*.py, in order."""
    out = []
    for path in sorted(DIR.glob("[0-9][0-9][0-9]_*.py")):
        head = {}
        for line in path.read_text().splitlines()[:6]:
            if m := _HEADER.match(line):
                head[m.group(1)] = m.group(2)
        out.append({"name": path.stem, "path": str(path), "task": head["task"], "cheat": head.get("cheat", ""),
                    "honest": head.get("honest", "") == "yes"})
    return out


def via_cli(case: dict, seed: int, timeout_s: float = 400.0) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "out.json"
        t0 = time.time()
        try:
            p = subprocess.run([sys.executable, "-m", "humanoidgen.cli.main", "run", case["task"], "--seed", str(seed),
                                "--script", case["path"], "--json", str(out)], capture_output=True, text=True,
                               timeout=timeout_s, env={**os.environ, "COLUMNS": "200"})
        except subprocess.TimeoutExpired:
            return {"success": None, "reason": f"hgen run timed out after {timeout_s:.0f} s", "rc": None}
        res = json.loads(out.read_text()) if out.exists() else None
        tail = [ln for ln in p.stdout.splitlines() if ln.strip()][-3:]
        reason = ""
        if res is not None:
            bad = [s["error"] for s in res.get("steps", []) if not s.get("ok")]
            reason = (bad[0] if bad else "; ".join(c["detail"] for c in res.get("checks", []) if not c["ok"]))
        return {"success": None if res is None else bool(res["success"]), "rc": p.returncode,
                "reason": " ".join(reason.split())[:300], "console": " | ".join(t.strip() for t in tail)[:300],
                "stderr": p.stderr[-300:] if res is None else "", "seconds": round(time.time() - t0, 1)}


def via_collect(case: dict, seed: int) -> dict:
    from humanoidgen.episodes.collect import collect
    from humanoidgen.episodes.dataset import EpisodeStore
    from humanoidgen.episodes.recorder import RecorderConfig

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "data"
        t0 = time.time()
        try:
            stats = collect(case["task"], 1, out, seed=seed, recorder=RecorderConfig(), plan_path=case["path"],
                            max_attempts=1)
        except Exception as exc:  # noqa: BLE001 - a crash is recorded, not hidden
            return {"kept": None, "reason": f"collect raised {type(exc).__name__}: {exc}"[:300]}
        store = EpisodeStore(out)
        att = store.attempts()
        files = list((out / "episodes").glob("*")) if (out / "episodes").is_dir() else []
        return {"kept": stats.kept, "kept_list": len(store.kept()), "files": len(files),
                "success": any(a.get("success") for a in att),
                "reason": " ".join(str(att[0].get("error", "")).split())[:300] if att else "",
                "seconds": round(time.time() - t0, 1)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--only", default="")
    ap.add_argument("--no-collect", action="store_true")
    ap.add_argument("--out", default=str(ROOT / "bench" / "results" / "cheats_unseen.json"))
    args = ap.parse_args()
    only = [s for s in args.only.split(",") if s]
    cases = [c for c in battery() if not only or any(c["name"].startswith(o) for o in only)]
    rows = []
    for c in cases:
        row = {"name": c["name"], "task": c["task"], "honest": c["honest"], "cheat": c["cheat"],
               "run": via_cli(c, args.seed)}
        if not args.no_collect:
            row["collect"] = via_collect(c, args.seed)
        rows.append(row)
        r, k = row["run"], row.get("collect", {})
        flag = "OK " if (bool(r["success"]) == c["honest"] and (not k or bool(k.get("kept")) == c["honest"])) else "BAD"
        print(f"{flag} {c['name']:44s} run success={r['success']} collect kept={k.get('kept')} | "
              f"{r['reason'][:110] or r.get('stderr', '')[-110:]}", flush=True)
    bad = [r["name"] for r in rows if bool(r["run"]["success"]) != r["honest"]
           or ("collect" in r and bool(r["collect"].get("kept")) != r["honest"])]
    summary = {"cases": len(rows), "cheats": sum(not r["honest"] for r in rows),
               "cheats_judged_success": sum(bool(r["run"]["success"]) for r in rows if not r["honest"]),
               "cheats_kept": sum(bool(r.get("collect", {}).get("kept")) for r in rows if not r["honest"]),
               "honest_failed": [r["name"] for r in rows if r["honest"] and not r["run"]["success"]],
               "wrong": bad}
    Path(args.out).write_text(json.dumps({"summary": summary, "rows": rows}, indent=1))
    print(json.dumps(summary))


if __name__ == "__main__":
    main()
