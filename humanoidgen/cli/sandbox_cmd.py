"""`hgen sandbox check`: what the plan worker's lockdown holds on this machine."""

from __future__ import annotations

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

app = typer.Typer(help="The locked-down plan worker (seccomp + Landlock) that every plan runs in.",
                  no_args_is_help=True)


@app.command()
def check() -> None:
    """Start a plan worker, try each thing plan code must not do (write files, run programs, fork, open
    sockets, signal or read other processes, raise its limits) with the real modules in hand, and show that
    the kernel refused every one. Exit code 1 if any got through or a layer is missing.

    Example: hgen sandbox check
    """
    from humanoidgen.sandbox.probe import run_probes

    report, results = run_probes()
    console = Console()
    report = report or {}
    console.print(f"seccomp: {'[green]on[/green]' if report.get('seccomp') else '[red]OFF[/red]'}   "
                  f"Landlock: {'[green]ABI ' + str(report.get('landlock_abi')) + '[/green]' if report.get('landlock_abi') else '[red]OFF[/red]'}")
    for w in report.get("warnings", []):
        console.print(f"[red]warning:[/red] {escape(str(w))}")
    table = Table("attempt", "route", "result", "kernel's answer")
    for r in results:
        table.add_row(r.name, r.route, "[green]blocked[/green]" if r.blocked else "[red]GOT THROUGH[/red]",
                      escape(r.detail.removeprefix("blocked: ").split(": '")[0][:60]))
    console.print(table)
    ok = all(r.blocked for r in results) and report.get("seccomp") and report.get("landlock_abi")
    raise typer.Exit(0 if ok else 1)
