"""The ``vbikit`` command line.  Only this package prints; the library logs.

Modules by job: this one holds the app, its global options and the list of commands;
``guard`` the one error guard; ``render`` the text report, JSON
and CSV outputs; ``execute`` the one function that runs a scenario; the command
groups ``scenarios`` (run, cite, demo, compare-tires), ``validate`` (every input kind),
``models`` (presets, bridge), ``field``, ``study``, ``driveby``, ``rail``, ``lifetime``
and ``traffic``.  Command modules import numpy, scipy, numba, xarray and
matplotlib only inside the commands, so ``--version``, ``--help`` and shell completion start
fast.
"""
from __future__ import annotations

import logging
from typing import Any

import typer
from typer.core import TyperGroup

from vbikit.cli import driveby, field, lifetime, models, rail, scenarios, study, traffic, validate
from vbikit.cli.guard import STATE

#: the global options, accepted after the subcommand as well (``vbikit run X.toml -q``)
GLOBAL_FLAGS = ("-q", "--quiet", "--debug", "-v", "--verbose")


def _is_global_flag(arg: str) -> bool:
    return arg in GLOBAL_FLAGS or (len(arg) > 2 and arg[0] == "-" and arg[1] != "-" and set(arg[1:]) == {"v"})


class _Group(TyperGroup):
    """The root command: global flags given after a subcommand (``-q``, ``-v``/``-vv``, ``--verbose``,
    ``--quiet``, ``--debug``; not after ``--``) are moved before it, where the root's options take them."""

    def parse_args(self, ctx: Any, args: list[str]) -> list[str]:
        end = args.index("--") if "--" in args else len(args)
        first = next((i for i, a in enumerate(args[:end]) if not a.startswith("-")), end)  # the subcommand
        moved = [a for a in args[first + 1:end] if _is_global_flag(a)]
        if moved:
            args = moved + args[:first + 1] + [a for a in args[first + 1:end] if not _is_global_flag(a)] + args[end:]
        return super().parse_args(ctx, args)

    def main(self, *args: Any, standalone_mode: bool = True, **kwargs: Any) -> Any:
        """As click's, but a usage error — a bad option value, an unknown option, a missing argument, which
        click parses before any command runs — ends like every other error of the command line: one line
        ``error: …`` on stderr naming the command and its ``--help``, exit 2 (click prints its usage text
        and ``Error: …`` instead)."""
        if not standalone_mode:
            return super().main(*args, standalone_mode=False, **kwargs)
        import sys

        try:
            rv = super().main(*args, standalone_mode=False, **kwargs)
        except SystemExit as end:  # click ends a run whose output pipe closed (`vbikit presets | head -1`) with 1,
            if end.code == 1 and type(sys.stdout).__name__ == "PacifyFlushWrapper":  # our code of a bug: say 141
                sys.exit(EXIT_BROKEN_PIPE)  # (what a program the signal ends gives, as `yes | head -1`)
            raise
        except _click_error("UsageError") as err:
            typer.echo(usage_error_line(err), err=True)
            sys.exit(err.exit_code)
        except _click_error("ClickException") as err:  # (click's other errors, e.g. a file option it opens)
            typer.echo(f"error: {err.format_message()}", err=True)
            sys.exit(err.exit_code)
        except typer.Abort:
            typer.echo("Aborted!", err=True)
            sys.exit(1)
        sys.exit(rv if isinstance(rv, int) else 0)  # (typer.Exit's code; a command itself returns None)


#: the exit code of a run whose standard output was closed by its reader (128 + SIGPIPE, as the shells give a
#: program that signal ends): not a bug (1), not a user error (2)
EXIT_BROKEN_PIPE = 141


def _click_error(name: str) -> type:
    """click's exception class ``name`` (``UsageError``, ``ClickException``) as typer raises it, found
    among the bases of the public ``typer.BadParameter`` (typer vendors click in its own namespace)."""
    return next(c for c in typer.BadParameter.__mro__ if c.__name__ == name)


def usage_error_line(err: Any) -> str:
    """The one line of a click usage error: ``error: vbikit CMD: <click's message>; see 'vbikit CMD --help'``."""
    command = err.ctx.command_path if err.ctx is not None else "vbikit"
    return f"error: {command}: {err.format_message().rstrip('.')}; see '{command} --help'"


app = typer.Typer(
    cls=_Group,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,  # plain help texts: "[tire]" or "[m]" stay as written
    help="vbikit — vehicle–bridge coupled vibration: run scenarios, list presets, run the demo.\n\n"
         "Commands that write files write them into --out-dir (default vbikit-out/); options that name "
         "one file (--out, --plot, --summary) take that path as given.",
)


def _version(value: bool) -> None:
    if value:
        from vbikit._version import __version__

        typer.echo(f"vbikit {__version__}")
        raise typer.Exit()


class _PlainWarnings(logging.Formatter):
    """Log records at WARNING and above as the CLI prints its own (``warning: …``, ``error: …``),
    without the logger's name (``-v``, ``-vv`` and ``--debug`` keep it); others as ``fmt``."""

    def format(self, record: logging.LogRecord) -> str:
        if record.levelno >= logging.WARNING:
            return f"{'error' if record.levelno >= logging.ERROR else 'warning'}: {record.getMessage()}"
        return super().format(record)


@app.callback(invoke_without_command=True)
def _main(
    ctx: typer.Context,
    verbose: int = typer.Option(0, "--verbose", "-v", count=True, help="More log messages (-v info, -vv debug)."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="Only errors: no warnings, no progress bars."),
    debug: bool = typer.Option(False, "--debug", help="Show full tracebacks and debug logs."),
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="Print the version and exit."),
) -> None:
    STATE["debug"], STATE["quiet"], STATE["json"] = debug, quiet, False
    level = logging.DEBUG if debug or verbose > 1 else logging.INFO if verbose else logging.ERROR if quiet else logging.WARNING
    logging.basicConfig(level=level, format="%(levelname)s %(name)s: %(message)s", force=True)
    if level >= logging.WARNING:  # the default: a logged warning reads as the CLI's own (`warning: …`)
        for handler in logging.getLogger().handlers:
            handler.setFormatter(_PlainWarnings("%(levelname)s %(name)s: %(message)s"))
    if not quiet:
        logging.getLogger("vbikit.solve.compile").setLevel(logging.INFO)  # "compiling kernels, first run only"
    if quiet:
        import warnings

        warnings.simplefilter("ignore")
    if ctx.invoked_subcommand is None:  # bare `vbikit`: the help, exit code 0
        typer.echo(ctx.get_help())
        raise typer.Exit()


app.add_typer(study.app, name="study")
app.command("traffic")(traffic.traffic_cmd)
app.command("driveby")(driveby.driveby_cmd)
app.command("lifetime")(lifetime.lifetime_cmd)
app.command()(scenarios.run)
app.command()(validate.validate)
app.command()(scenarios.cite)
app.command()(scenarios.demo)
app.command("compare-tires")(scenarios.compare_tires)
app.command()(models.presets)
app.command()(models.bridge)
app.command("field")(field.field_)
app.command("rail")(rail.rail_cmd)


@app.command("compile")
def compile_() -> None:
    """Compile every numerical kernel now and keep it in numba's cache (for a cluster image, a
    container or a shared installation: later runs, study batches and Dask workers load them in
    under a second instead of compiling on first use)."""
    from vbikit.cli.guard import guard

    def work() -> None:
        import numba

        from vbikit.analysis.warmup import compile_effect_kernels, compile_history_kernels
        from vbikit.driveby.warmup import compile_driveby_kernels
        from vbikit.random.warmup import compile_random_kernels
        from vbikit.solve.numba_cache import cache_location
        from vbikit.solve.warmup import compile_kernels

        typer.echo("compiling the kernels of every integrator (one lane and many lanes), or loading those numba's "
                   "cache holds (the kernels vbikit ships compiled, docs/getting-started.md)...", err=True)
        for name, seconds in compile_kernels().items():
            typer.echo(f"  {name:<8} ready in {seconds:.1f} s")
        typer.echo(f"  {'random':<8} ready in {compile_random_kernels():.1f} s (pseudo-excitation)")
        typer.echo(f"  {'effects':<8} ready in {compile_effect_kernels():.1f} s (load effects on beams and grillage decks)")
        typer.echo(f"  {'history':<8} ready in {compile_history_kernels():.1f} s (static modal histories, exact static peaks)")
        typer.echo(f"  {'driveby':<8} ready in {compile_driveby_kernels():.1f} s (decoupled drive-by passes)")
        typer.echo(f"numba cache: {cache_location()}" + ("" if numba.config.CACHE_DIR else
                                                          " and the __pycache__ folders beside vbikit's other kernel sources"))

    guard(work)


def main() -> None:
    """Console-script entry point."""
    app()


__all__ = ["app", "main"]
