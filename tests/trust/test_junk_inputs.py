"""The two gaps a new user found: a CSV that is no train table ('foo,bar' then '1,2') validated as
a train of one axle, through ``vbikit validate`` (its kind guessed or told) and a railway file's
``[trains] tables``; and a lifetime detail ``category = "EN 37"`` (EN 1993-1-9 has no 37, a typo of
36) ran to a fatigue life.  Each is now refused before any computation, with one error line that
names the file or key and what is allowed, and never the file's text."""
from __future__ import annotations

import copy

import pytest
from fuzz_commands import BASES, RECORDS, write_input
from fuzzing import cli_refused
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
JUNK = "foo,bar\n1,2\n"  # the user's file
RAIL = ("[bridge]\nspan = 20.0\nEI = 7.9e10\nmass_per_length = 25000.0\n[trains]\ntables = [\"junk.csv\"]\n"
        "[speeds]\nmin = 100.0\nmax = 200.0\nstep = 10.0\n")


@pytest.mark.parametrize("argv", [["validate", "junk.csv"], ["validate", "--kind", "train", "junk.csv"],
                                  ["validate", "RAIL.toml"], ["rail", "RAIL.toml", "--out-dir", "out"]])
def test_a_csv_that_is_no_train_table_is_refused(tmp_path, monkeypatch, argv):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "junk.csv").write_text(JUNK)
    (tmp_path / "RAIL.toml").write_text(RAIL)
    err = cli_refused(runner.invoke(app, argv), "junk.csv, line 1: not a train table",
                   "'position [m], load [kN]'", *(["trains.tables[1]: "] if "RAIL.toml" in argv else []))
    assert "foo" not in err and "bar" not in err
    assert not (tmp_path / "out").exists()  # refused before the run made anything
    # only a guessed kind says it was guessed, and how to name another (a records file missing its time column…)
    assert ("read as a train table" in err and "--kind: " in err) == (argv == ["validate", "junk.csv"])


def test_a_real_train_table_still_validates(tmp_path):
    (tmp_path / "train.csv").write_text("position_m,load_kN\n0,170\n3,170\n14,170\n17,170\n")
    res = runner.invoke(app, ["validate", str(tmp_path / "train.csv")])
    assert res.exit_code == 0 and "4 axles over 17 m" in res.output, res.output


@pytest.mark.parametrize("command", ["validate", "lifetime"])
def test_a_detail_category_en_1993_1_9_does_not_list_is_refused(tmp_path, command):
    from vbikit.fatigue import EN_CATEGORIES

    data = copy.deepcopy(BASES["lifetime"])
    data["fatigue"]["details"][0]["category"] = "EN 37"
    path = write_input(tmp_path, "lifetime", data, {"records.csv": "\n".join(RECORDS) + "\n"})
    argv = [command, str(path)] + (["--out-dir", str(tmp_path / "out")] if command == "lifetime" else [])
    cli_refused(runner.invoke(app, argv), "fatigue.details[1].category: 'EN 37' is not a detail category",
             "(the nearest EN category is 36)", "allowed: EN " + ", ".join(map(str, EN_CATEGORIES)))
    assert not (tmp_path / "out").exists()


def test_a_named_train_table_refused_does_not_say_it_was_guessed(tmp_path):
    """A CSV whose header names the train-table columns is a train table, not a guess: refused for an
    axle load out of range, its message does not add the guessed-kind note."""
    (tmp_path / "heavy.csv").write_text("position [m], load [kN]\n0, 170\n3, 20000\n")
    res = runner.invoke(app, ["validate", str(tmp_path / "heavy.csv")])
    err = cli_refused(res, "heavy.csv")
    assert "read as a train table" not in err
