"""`hgen` ends a command that has written everything without the interpreter's teardown (`cli.fast_exit`):
its exit handlers still run, what it printed still arrives, its exit code is kept, a running thread is still
waited for, and a command that did not say so exits as before."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from humanoidgen.cli.fast_exit import exit_code

ROOT = Path(__file__).resolve().parents[1]

# A command of the real program (`app` called as `hgen` calls it) that prints without a newline (still in
# stdout's buffer at the end), registers an exit handler, and leaves an object whose finalizer only the
# interpreter's teardown runs.
PROGRAM = textwrap.dedent('''
    import atexit, sys, threading, time
    import typer
    from humanoidgen.cli import fast_exit
    from humanoidgen.cli.main import app

    marks = sys.argv[1]

    class Teardown:
        def __del__(self, _open=open, _marks=marks):  # (builtins may be gone by then)
            with _open(_marks, "a") as f:
                f.write("teardown\\n")

    keep = Teardown()

    @app.command("probe")
    def probe(allow: bool = True, thread: bool = False, code: int = 2) -> None:
        atexit.register(lambda: open(marks, "a").write("handler\\n"))
        if thread:  # a normal exit waits for it
            threading.Thread(target=lambda: (time.sleep(0.5), open(marks, "a").write("thread\\n"))).start()
        sys.stdout.write("result without a newline")
        if allow:
            fast_exit.allow()
        raise typer.Exit(code)

    app(sys.argv[2:])
''')


def _run(tmp_path: Path, *args: str) -> tuple[subprocess.CompletedProcess, list[str]]:
    script, marks = tmp_path / "program.py", tmp_path / "marks.txt"
    script.write_text(PROGRAM)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, str(script), str(marks), "probe", *args], capture_output=True, text=True,
                       timeout=120, cwd=ROOT, env=env)
    return r, marks.read_text().split() if marks.exists() else []


def test_a_command_that_wrote_everything_ends_without_the_teardown_keeping_output_handlers_and_code(tmp_path):
    r, marks = _run(tmp_path)
    assert r.returncode == 2, r.stderr[-2000:]
    assert r.stdout == "result without a newline"
    assert marks == ["handler"]  # the exit handler ran; the teardown's finalizer did not


@pytest.mark.parametrize("code", ["0", "1"])
def test_the_exit_code_is_the_commands(tmp_path, code):
    r, _ = _run(tmp_path, "--code", code)
    assert r.returncode == int(code), r.stderr[-2000:]


def test_a_command_that_did_not_say_so_exits_as_before(tmp_path):
    r, marks = _run(tmp_path, "--no-allow")
    assert r.returncode == 2 and r.stdout == "result without a newline"
    assert marks == ["handler", "teardown"]


def test_a_running_thread_is_waited_for(tmp_path):
    r, marks = _run(tmp_path, "--thread")
    assert r.returncode == 2 and r.stdout == "result without a newline"
    assert marks[0] == "thread" and "handler" in marks  # a normal exit: the thread finished first


def test_exit_codes_are_those_of_sys_exit(capsys):
    assert (exit_code(None), exit_code(0), exit_code(3), exit_code(256 + 4)) == (0, 0, 3, 4)
    assert exit_code("no such task") == 1
    assert "no such task" in capsys.readouterr().err
