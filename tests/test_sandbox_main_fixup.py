"""A plan worker does not re-run its parent's `__main__` script (the `hgen` console script, Ray's
`default_worker.py`: 0.3 s of imports per worker in a Ray actor), unless its setup lives in that script."""

import subprocess
import sys
import textwrap

from humanoidgen.sandbox.forkserver import WORKER_NAME, WORKER_NAME_MAIN, worker_name

SCRIPT = textwrap.dedent('''
    import os
    import sys

    # Top level: runs once as the program, and once more in every worker that re-runs the main script (the
    # fixup happens before the worker locks itself down, so it can still append here).
    with open(sys.argv[1], "a") as f:
        f.write(f"{os.getpid()}\\n")


    def main_setup():
        return {}


    if __name__ == "__main__":
        from humanoidgen.sandbox import SandboxWorker

        with SandboxWorker(dict) as w:  # importable setup: no fixup
            assert w.run_step("x = 1").ok
        lines = len(open(sys.argv[1]).read().split())
        with SandboxWorker(main_setup) as w:  # a setup from __main__: the worker needs the script
            assert w.run_step("x = 1").ok
        print(lines, len(open(sys.argv[1]).read().split()))
''')


def test_worker_names():
    def local_setup():
        return {}

    assert worker_name(dict) == WORKER_NAME
    assert worker_name(local_setup) == WORKER_NAME  # this test module is importable
    local_setup.__module__ = "__main__"
    assert worker_name(local_setup) == WORKER_NAME_MAIN


def test_only_a_worker_whose_setup_is_in_main_re_runs_the_main_script(tmp_path):
    script, marker = tmp_path / "main_script.py", tmp_path / "runs.txt"
    script.write_text(SCRIPT)
    r = subprocess.run([sys.executable, str(script), str(marker)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    after_importable, after_main = map(int, r.stdout.split())
    assert after_importable == 1  # the program itself only
    assert after_main == 2  # the worker holding main_setup ran the script once more, and found its setup
