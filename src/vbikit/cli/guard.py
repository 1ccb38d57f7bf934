"""The one error guard of the command line, and the run-wide options it reads.

A user error ([`VbikitError`][vbikit.errors.VbikitError]: bad input, a refused budget or time step),
an ``OSError`` (an input that cannot be read, an output that cannot be written) and a
``MemoryError`` exit with code 2 and one line ``error: …`` on stderr, as does a worker process of a
pool stopped by the system (``BrokenProcessPool``: most often the machine out of memory).  A command that reads an input
file passes it (``guard(action, file=path)``): a user error then names that file in its first line
(``vbikit.errors.naming_file``: ``error: invalid scenario bad.toml:`` and the key lines), the one
place every command's input-file errors get their file name.  Any other exception is a
programming error and shows its traceback, as does every error with ``--debug``.
"""
from __future__ import annotations

import contextlib
from collections.abc import Iterator
from pathlib import Path
from typing import Any, Callable, Optional, TypeVar

import typer

from vbikit.errors import OptionError, VbikitError, naming_file

T = TypeVar("T")

#: the global options of this invocation (set by the root command before a subcommand runs; ``json``: the
#: command's ``--json``, which gives standard output to the summary JSON alone, ``say``)
STATE = {"debug": False, "quiet": False, "json": False}

_OUT_OF_MEMORY = ("error: out of memory; give a lower --max-memory (vbikit run, validate, compare-tires, field, study run, "
                  "traffic, lifetime) to be "
                  "refused before starting, or reduce the inputs named in the budget message of `vbikit validate`")


def guard(action: Callable[[], T], file: Optional[Path] = None) -> T:
    """Run ``action``; a user error, an unreadable input or unwritable output, or running out of
    memory exits with code 2 and one message (``--debug``: the traceback instead).  ``file``: the
    input file ``action`` reads, named (as given) in the first line of a user error's message
    unless that line names it already; an option's error (``OptionError``) is not about the file."""
    try:
        return action()
    except (VbikitError, OSError) as err:
        if STATE["debug"]:
            raise
        about_file = file is not None and isinstance(err, VbikitError) and not isinstance(err, OptionError)
        typer.echo(f"error: {naming_file(str(err), file) if about_file else err}", err=True)
        for note in getattr(err, "__notes__", ()):  # what the run leaves (e.g. a lifetime run's resumable work)
            typer.echo(f"note: {note}", err=True)
        raise typer.Exit(code=2) from None
    except MemoryError as err:
        if STATE["debug"]:
            raise
        typer.echo(_OUT_OF_MEMORY, err=True)
        for note in getattr(err, "__notes__", ()):
            typer.echo(f"note: {note}", err=True)
        raise typer.Exit(code=2) from None
    except Exception as err:
        if _interrupted(err) and not STATE["debug"]:  # Ctrl-C inside a compiled kernel: numba wraps it; the caller's
            raise KeyboardInterrupt from None  # `except KeyboardInterrupt` then says what is kept
        if STATE["debug"] or not _worker_died(err):
            raise
        typer.echo(_WORKER_DIED, err=True)
        raise typer.Exit(code=2) from None


def _interrupted(err: BaseException) -> bool:
    """Whether ``err`` was raised by a Ctrl-C: a ``KeyboardInterrupt`` in its chain of causes and contexts (numba
    turns one raised inside a compiled function into "SystemError: … returned a result with an exception set")."""
    seen = set()
    cause: BaseException | None = err
    while cause is not None and id(cause) not in seen:
        if isinstance(cause, KeyboardInterrupt):
            return True
        seen.add(id(cause))
        cause = cause.__cause__ or cause.__context__
    return False


_WORKER_DIED = ("error: a worker process ended abruptly: the system stopped it, most often because the machine ran "
                "out of memory; run again with fewer --workers (or when memory is free): the batches that finished "
                "are kept and the same command resumes from them")


def _worker_died(err: BaseException) -> bool:
    """Whether ``err`` says a pool's worker process died (``concurrent.futures.BrokenExecutor``: killed by
    the system, e.g. out of memory) — not a bug of vbikit.  (Read only if that module is loaded: the
    CLI's start-up imports no more than it needs.)"""
    import sys

    futures = sys.modules.get("concurrent.futures")
    return futures is not None and isinstance(err, futures.BrokenExecutor)


def warn(warnings: list[str], most: Optional[int] = None) -> None:
    """Print the input warnings of a run on stderr (not with ``-q``); ``most``: at most that many,
    then one line ``warning: … and N more warnings``."""
    if STATE["quiet"]:
        return
    for text in warnings[:most]:
        typer.echo(f"warning: {text}", err=True)
    if most is not None and len(warnings) > most:
        typer.echo(f"warning: … and {len(warnings) - most} more warnings", err=True)


def option(parse: Callable[[str], T], text: str) -> T:
    """``parse(text)`` for a command-line option value; its ``ValueError`` (the message names the
    option) becomes an [`OptionError`][vbikit.errors.OptionError]."""
    try:
        return parse(text)
    except VbikitError:
        raise
    except ValueError as err:
        raise OptionError(str(err)) from None


def limits(max_memory: Optional[str], max_steps: Optional[float]) -> Any:
    """The ``Limits`` of ``--max-memory`` and ``--max-steps``."""
    from vbikit.solve.budget import Limits

    kw: dict[str, Any] = {}
    if max_memory is not None:
        kw["max_memory"] = memory_option(max_memory)
    if max_steps is not None:
        kw["max_steps"] = int(steps_option(max_steps))
    return Limits(**kw)


def steps_option(value: float, name: str = "--max-steps") -> float:
    """``--max-steps``: a finite number of steps in [1, MAX_STEPS_LIMIT] (exit 2 naming the option)."""
    from vbikit._validation import MAX_STEPS_LIMIT, number

    return guard(lambda: number(value, name, 1, MAX_STEPS_LIMIT, error=OptionError))


def budget_value(value: float, name: str, most: float) -> float:
    """A budget option's value (``--budget-hours``, ``vbikit rail --max-steps`` …): a finite number > 0 and at most
    ``most``, the largest its input-file key takes (exit 2 naming the option and the range)."""
    from vbikit._validation import number

    return guard(lambda: number(value, name, 0, most, lo_open=True, error=OptionError))


def memory_option(text: str) -> float:
    """``--max-memory``: a size such as 8GiB, finite and > 0 [bytes] (exit 2 naming the option)."""
    from vbikit.solve.budget import parse_size

    return guard(lambda: option(parse_size, text))


def check_out_dir(path: Any) -> Any:
    """``--out-dir``: the output folder, checked now (exit 2 when it names a file, a system folder …:
    ``vbikit._files.output_dir``), before any computation; the writers create it.  None passes."""
    from vbikit._files import output_dir

    return None if path is None else guard(lambda: output_dir(path, create=False))


#: the output folder of every command that writes several files, when none is given
DEFAULT_OUT_DIR = Path("vbikit-out")


def out_dir_option(help: str, default: Any = DEFAULT_OUT_DIR) -> Any:
    """The ``--out-dir`` option of every command that writes into a folder (default ``vbikit-out``;
    None: the command writes files only when asked): ``check_out_dir`` runs as the command line is
    parsed, so a bad folder is refused before the command computes anything."""
    return typer.Option(default, "--out-dir", help=help, callback=check_out_dir)


def check_out_file(param: typer.CallbackParam, path: Any) -> Any:
    """An output file option (``--out``, ``--summary``, ``--plot`` …), checked now (exit 2 naming the
    option when it names a folder, lies in a system folder, or its folder is a file or not writable:
    ``vbikit._files.output_file``), before any computation.  None passes."""
    from vbikit._files import output_file

    name = max(param.opts, key=len)
    return None if path is None else guard(lambda: output_file(path, name))


def out_file_option(name: str, help: str, default: Any = None) -> Any:
    """The option ``name`` of an output file (default None: not written; ``...``: required), checked by
    ``check_out_file`` as the command line is parsed: a bad path is refused before the command computes."""
    return typer.Option(default, name, help=help, callback=check_out_file)


def check_scheduler_option(value: Optional[str]) -> Optional[str]:
    """``--scheduler``: a Dask scheduler address of the form tcp://host:port, checked as the command line
    is parsed (``vbikit.study.workers.check_scheduler``; exit 2 naming the option), before any
    computation; nothing is connected yet.  None passes."""
    if value is None:
        return None
    from vbikit.study.workers import check_scheduler

    return guard(lambda: check_scheduler(value, OptionError))


#: the one help text of ``--scheduler`` (every command that runs on a Dask cluster)
SCHEDULER_HELP = "Dask distributed scheduler address (tcp://host:port): run on that cluster instead of local processes."


def scheduler_option() -> Any:
    """The ``--scheduler`` option of every command that runs on a Dask cluster (``check_scheduler_option``;
    help ``SCHEDULER_HELP``)."""
    return typer.Option(None, "--scheduler", help=SCHEDULER_HELP, callback=check_scheduler_option)


def check_workers_option(value: Optional[int]) -> Optional[int]:
    """``--workers``: an integer in [1, ``vbikit._validation.workers_limit()``] (exit 2 naming the option
    and the range), checked as the command line is parsed: before any process is started.  None passes."""
    from vbikit._validation import checked_workers

    return guard(lambda: checked_workers(value, "--workers", OptionError))


#: the one help text of ``--workers``: the one default of every command with local worker processes (None on the
#: command line: the input file's own setting where it has one, else ``vbikit._validation.default_workers()``)
WORKERS_HELP = "Local worker processes (1 = in this process); default: {default}all cores."


def workers_option(file_key: Optional[str] = None) -> Any:
    """The ``--workers`` option of every command with local worker processes (``check_workers_option``; help
    ``WORKERS_HELP``; default None: the input file's setting ``file_key`` where the command's file has one, else
    all cores)."""
    default = "" if file_key is None else f"the input file's {file_key}, else "
    return typer.Option(None, "--workers", help=WORKERS_HELP.format(default=default), callback=check_workers_option)


#: the one help text of ``--json`` of the commands that write a folder (traffic, lifetime, driveby, rail)
JSON_HELP = ("Print the summary JSON on standard output (the object of the folder's summary file); the report and "
             "every other line go to standard error.")


def json_option() -> Any:
    """The ``--json`` option of the commands that write a folder (``JSON_HELP``): ``use_json`` sets it for ``say``."""
    return typer.Option(False, "--json", help=JSON_HELP)


def use_json(as_json: bool) -> None:
    """The command's ``--json``: when given, standard output carries the summary JSON alone (``say_json``) and
    ``say`` sends every other result line to standard error."""
    STATE["json"] = bool(as_json)


def say(text: str, nl: bool = True) -> None:
    """A line of a command's results: on standard output, or on standard error when ``--json`` gives standard
    output to the summary JSON (``use_json``) — not at all with ``-q`` then (errors only: the JSON is the result)."""
    if STATE["json"] and STATE["quiet"]:
        return
    typer.echo(text, nl=nl, err=STATE["json"])


@contextlib.contextmanager
def finishing(dataset: Path) -> Iterator[None]:
    """The outputs written after a finished run (report, summary, figures): a Ctrl-C there exits with code 130 and
    says that the run's dataset ``dataset`` is complete and that the same command writes the rest from it (a
    trial's Ctrl-C at the end of ``vbikit traffic`` exited 130 without a word, a figure missing)."""
    try:
        yield
    except KeyboardInterrupt:
        typer.echo(f"\ninterrupted while writing the outputs: {dataset} is complete; run the same command again to "
                   "write the report, summary and figures from it (nothing is simulated again)", err=True)
        raise typer.Exit(code=130) from None


def say_summary_file(path: Path) -> None:
    """With ``--json``: the summary file ``path`` the command wrote (its folder's), on standard output (``say_json``)."""
    if STATE["json"]:
        say_json(guard(lambda: Path(path).read_text(encoding="utf-8")))


def say_json(summary: Any) -> None:
    """With ``--json`` (``use_json``): the summary, a dict or the text of a summary file, on standard output as one
    JSON object; nothing otherwise."""
    if not STATE["json"]:
        return
    if not isinstance(summary, str):
        from vbikit._files import json_text

        summary = json_text(summary, indent=1)
    typer.echo(summary.rstrip("\n"))


def check_figure_file(param: typer.CallbackParam, path: Any) -> Any:
    """A figure file option (``--plot``): ``check_out_file``, and a format matplotlib writes by the file's
    suffix (``vbikit._files.figure_format``), checked as the command line is parsed, before any
    computation (was: after the run, in ``vbikit traffic`` and ``vbikit bridge``).  None passes."""
    path = check_out_file(param, path)
    if path is not None:
        from vbikit._files import figure_format

        def check() -> None:
            try:
                figure_format(path)
            except OptionError as err:
                raise OptionError(f"{max(param.opts, key=len)} {err}") from None

        guard(check)
    return path


def figure_file_option(help: str) -> Any:
    """The ``--plot`` option of a command that draws one figure (``check_figure_file``; default None: none drawn)."""
    return typer.Option(None, "--plot", help=help, callback=check_figure_file)


def budget_help(counts: str, default: str, key: Optional[str] = None) -> str:
    """The one wording of a budget option's help: what it counts and over what (``counts``: "time steps of each
    event's run", "integration steps of the whole sweep"), the input file's key it overrides (``key``; None: the
    file has none) and the default; estimated before anything is computed, refused above.  A memory budget's
    help shows the form of a size."""
    size = "e.g. 8GiB; " if counts.startswith("memory") else ""
    where = f"{size}overrides the file's {key}; default {default}" if key else f"{size}default {default}"
    return f"Budget: the most {counts} ({where}); estimated before anything is computed, refused above."


def budget_option(name: str, counts: str, default: str, key: Optional[str] = None) -> Any:
    """A budget option ``name`` (``--max-steps``, ``--max-memory`` …) with the help of ``budget_help``
    (default None: the file's key, else the library's default)."""
    return typer.Option(None, name, help=budget_help(counts, default, key))


#: ``--max-memory`` and ``--max-steps`` of one run (``vbikit run``, ``vbikit validate``; each run of ``compare-tires``
#: and ``field``)
MAX_MEMORY = budget_option("--max-memory", "memory of the run", "4GiB")
MAX_STEPS = budget_option("--max-steps", "time steps of the run", "5e6")


def input_file_argument(metavar: str, kind: str, page: str) -> Any:
    """The input file of a population command (its one positional argument): ``metavar`` as the pages write it
    (``LIFETIME.toml``), the help "``kind`` (TOML, docs/``page``)." with the format from the metavar's suffix."""
    return typer.Argument(..., metavar=metavar, help=f"{kind} ({metavar.rsplit('.', 1)[-1].upper()}, docs/{page}).")


def progress_option() -> Any:
    """The ``--progress/--no-progress`` option of every command that shows progress bars (none with ``-q``)."""
    return typer.Option(True, "--progress/--no-progress", help="Show progress bars on stderr (never with -q).")


def figures_option() -> Any:
    """The ``--figures/--no-figures`` option of every command that draws its figures into ``--out-dir``."""
    return typer.Option(True, "--figures/--no-figures", help="Write the figures into --out-dir.")


def say_written(folder: Path, names: tuple[str, ...], since: float) -> None:
    """One line ``wrote PATH`` (``say``: on standard output, standard error with ``--json``) for each file or folder of ``folder`` that ``names`` (names or
    glob patterns) match and that the run wrote (modified at or after ``since``, a ``time.time()``), as every command
    that writes a folder says what it wrote."""
    found = sorted({p for name in names for p in Path(folder).glob(name) if p.stat().st_mtime >= since - 1.0})
    for path in found:
        say(f"wrote {path}")


def say_resumed(words: str, folder: Path) -> None:
    """After a finished run: one line on standard error (not with ``-q``) that it resumed from the work ``words``
    says ("3 of 95 batches", "2 of 12 trains": what the run itself found finished and used, after its checks) kept
    in ``folder``, not computed again — the run's time covers the rest only.  Nothing for ``words`` = ""."""
    if words and not STATE["quiet"]:
        typer.echo(f"resumed: {words} finished before were kept from {folder}, not run again (the time above is "
                   "this run's)", err=True)
