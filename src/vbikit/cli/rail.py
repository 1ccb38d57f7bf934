"""``vbikit rail``: speed sweeps of HSLM and real trains over a railway span with the EN 1991-2 /
EN 1990 dynamic checks."""
from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from vbikit.cli.guard import guard


def rail_cmd(
    spec: Path = typer.Argument(..., help="RAIL.toml: [bridge], [trains], [speeds] (docs/railway.md)."),
    out_dir: Path = typer.Option(..., "--out-dir", help="Directory for rail.nc, rail-report.txt, rail-summary.json and rail-acceleration.png."),
    workers: Optional[int] = typer.Option(None, "--workers", min=1, help="Worker processes (default: run.workers)."),
    figures: bool = typer.Option(True, "--figures/--no-figures", help="Draw the acceleration-envelope figure."),
) -> None:
    """Sweep every train over every speed: envelopes of deck acceleration, deflection, moment and
    shear, phi'dyn, resonance speeds and the pass/fail report."""
    from vbikit.rail.run import run_rail

    result = guard(lambda: run_rail(spec, out_dir, workers=workers, figures=figures))
    typer.echo(result.report, nl=False)
    for f in result.files:
        typer.echo(f"wrote {f}", err=True)
    typer.echo(f"{result.dataset.train.size} trains × {result.dataset.speed.size} speeds in {result.seconds:.1f} s", err=True)
