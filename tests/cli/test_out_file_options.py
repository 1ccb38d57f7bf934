"""Output file options (``--out``, ``--summary``, ``--plot``) are checked as the command line is
read, by one shared check (``guard.check_out_file`` → ``vbikit._files.output_file``).

What a new user found on main at 7bca391, each case below failing there:
``vbikit run bridge2_hs20_girder4.toml --out adir`` (``adir`` a folder) ran the crossing, then
``error: [Errno 21] cannot write adir: Is a directory`` (``--summary adir`` the same);
``--plot afile/x.png`` (``afile`` a file) ``[Errno 17] File exists: 'afile'``; ``vbikit traffic …
--plot afile/p.png`` ran all 319 events first; ``vbikit study run … --out afile/m.nc`` failed with
``[Errno 17] … cannot create the folder afile``.
"""
from __future__ import annotations

import os
import time
from pathlib import Path
from types import SimpleNamespace

import pytest
import typer.core
import typer.main
from typer.testing import CliRunner

from vbikit.cli import app
from cli_walk import commands as _commands

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
SCENARIO = str(EXAMPLES / "paper" / "bridge2_hs20_girder4.toml")
TRAFFIC = [str(EXAMPLES / "traffic" / "stream.csv"), "--bridge", str(EXAMPLES / "traffic" / "base" / "bridge2.toml")]

#: every output file option of every command, with the arguments that make the command run (shipped examples)
OUT_FILE_OPTIONS = {
    ("run", "--out"): [SCENARIO],
    ("run", "--summary"): [SCENARIO],
    ("run", "--plot"): [SCENARIO],
    ("study run", "--out"): [str(EXAMPLES / "studies" / "modes_sensitivity.toml")],
    ("traffic", "--out"): TRAFFIC,
    ("traffic", "--plot"): [*TRAFFIC, "--out", "{tmp}/t2.nc"],
    ("bridge", "--plot"): ["paper-bridge-1-beam"],
}
#: options that take a path to READ (none yet); any other path option must be an output option
INPUT_PATH_OPTIONS: set[tuple[str, str]] = set()


def test_every_output_file_option_is_the_one_checked_option():
    """Every option that takes a path (annotated ``Path``) or is called --out/--plot/--summary, other than
    --out-dir (checked by check_out_dir) and the listed input options, is checked by the one
    shared callback guard.check_out_file, and every such option is exercised below."""
    from vbikit.cli.guard import check_figure_file, check_out_file

    found = {}
    for name, cmd in _commands(typer.main.get_command(app)):
        for param in cmd.params:
            if not isinstance(param, typer.core.TyperOption) or "--out-dir" in param.opts:
                continue
            annotation = param.type_descriptor.annotation  # Optional[Path] → Path
            if (isinstance(annotation, type) and issubclass(annotation, os.PathLike)) or {"--out", "--plot", "--summary"} & set(param.opts):
                found[(name, max(param.opts, key=len))] = param.callback
    assert set(found) == set(OUT_FILE_OPTIONS) | INPUT_PATH_OPTIONS
    for key in OUT_FILE_OPTIONS:  # typer wraps the callback (functools.wraps)
        # (a figure, --plot: check_figure_file, which is check_out_file and the figure format)
        expected = check_figure_file if key[1] == "--plot" else check_out_file
        assert getattr(found[key], "__wrapped__", None) is expected, key


def _invoke(command: str, option: str, value: str, tmp_path: Path):
    args = [a.replace("{tmp}", str(tmp_path)) for a in OUT_FILE_OPTIONS[(command, option)]]
    t0 = time.process_time()
    res = runner.invoke(app, [*command.split(), *args, option, value])
    assert time.process_time() - t0 < 2.0  # refused as the command line is read (traffic ran 319 events first)
    return res


@pytest.mark.parametrize("command,option", sorted(OUT_FILE_OPTIONS))
def test_a_folder_a_file_as_folder_and_dev_are_refused_before_computing(tmp_path, command, option):
    adir, afile = tmp_path / "adir", tmp_path / "afile"
    adir.mkdir()
    afile.write_text("x")
    cases = ((str(adir), "is a folder, not a file; give the path of a file in a writable folder"),
             (f"{afile}/x.png", f"its folder {afile}: exists and is not a folder"),
             (f"{afile}/sub/x.png", "is not a folder"),
             ("/dev/null", "lies in /dev, a system folder"),
             ("/dev/x.nc", "lies in /dev, a system folder"))
    for value, message in cases:
        res = _invoke(command, option, value, tmp_path)
        assert res.exit_code == 2, res.output
        assert res.stderr.startswith(f"error: {option} {value}: "), res.stderr
        assert message in res.stderr and res.stderr.count("\n") == 1, res.stderr
        assert "Traceback" not in res.output
    assert afile.read_text() == "x" and not any(adir.iterdir())
    assert sorted(p.name for p in tmp_path.iterdir()) == ["adir", "afile"]  # nothing written


def test_the_new_users_commands(tmp_path, monkeypatch):
    """The four command lines of the report, as typed (relative paths)."""
    monkeypatch.chdir(tmp_path)
    Path("adir").mkdir()
    Path("afile").write_text("x")
    for args, line in (
        (["run", SCENARIO, "--out", "adir"], "error: --out adir: is a folder, not a file"),
        (["run", SCENARIO, "--summary", "adir"], "error: --summary adir: is a folder, not a file"),
        (["run", SCENARIO, "--plot", "afile/x.png"], "error: --plot afile/x.png: its folder afile: exists and is not a folder"),
        (["traffic", *[a.replace("{tmp}", ".") for a in OUT_FILE_OPTIONS[("traffic", "--plot")]], "--plot", "afile/p.png"],
         "error: --plot afile/p.png: its folder afile: exists and is not a folder"),
        (["study", "run", *OUT_FILE_OPTIONS[("study run", "--out")], "--out", "afile/m.nc"],
         "error: --out afile/m.nc: its folder afile: exists and is not a folder"),
    ):
        t0 = time.process_time()
        res = runner.invoke(app, [*args])
        assert res.exit_code == 2 and res.stderr.startswith(line), res.stderr
        assert time.process_time() - t0 < 2.0
    assert not Path("t2.nc").exists()


def test_output_file_passes_new_and_existing_files_and_creates_nothing(tmp_path):
    from vbikit._files import output_file
    from vbikit.cli.guard import check_out_file

    assert output_file(tmp_path / "new" / "deeper" / "x.csv", "--out") == tmp_path / "new" / "deeper" / "x.csv"
    assert not (tmp_path / "new").exists()  # checked, not created: the writers create it
    (tmp_path / "old.json").write_text("{}")
    assert output_file(tmp_path / "old.json", "--summary") == tmp_path / "old.json"  # replaced by the writer
    assert check_out_file(SimpleNamespace(opts=["--plot"]), None) is None


def test_output_file_refuses_an_unwritable_folder(tmp_path, monkeypatch):
    """The parent folder's write permission (os.access; faked here, as root may write anywhere)."""
    from vbikit._files import OutputError, output_file

    real_access = os.access
    monkeypatch.setattr(os, "access", lambda p, mode: False if Path(p) == tmp_path else real_access(p, mode))
    # (the folder exists: not writable, not "cannot create")
    with pytest.raises(OutputError, match=r"--out .*x\.nc: its folder .*: the folder is not writable$"):
        output_file(tmp_path / "x.nc", "--out")


def test_a_symbolic_link_as_output_is_replaced_as_before(tmp_path):
    """A symbolic link given as the output file, to a file or dangling, passes the check (the writers'
    os.replace replaces the link itself, as before the check existed); a link into /dev does not."""
    from vbikit._files import OutputError, output_file

    (tmp_path / "target.csv").write_text("x")
    (tmp_path / "to_file.csv").symlink_to(tmp_path / "target.csv")
    (tmp_path / "dangling.csv").symlink_to(tmp_path / "nowhere.csv")
    assert output_file(tmp_path / "to_file.csv", "--out") == tmp_path / "to_file.csv"
    assert output_file(tmp_path / "dangling.csv", "--out") == tmp_path / "dangling.csv"
    (tmp_path / "null.csv").symlink_to("/dev/null")
    with pytest.raises(OutputError, match="/dev"):
        output_file(tmp_path / "null.csv", "--out")
