"""Every input file goes through the one safe reader (``vbikit._files``): no content of a file in any
message (a train table pointing at a system file, also through a symbolic link), a 10 MB CSV field
refused with a clear error instead of the ``csv`` module's field-size error, folders and FIFOs refused."""
from __future__ import annotations

import os
import sys

import pytest

from vbikit.errors import VbikitError

SECRET = "SECRET-token-4711:do-not-print"
BIG = "1" * (10 * 2**20)  # one 10 MiB CSV field


def _readers():
    from vbikit.bridge.modefile import modes_from_file as read_modes
    from vbikit.field.io import read_response_csv
    from vbikit.road.measured import read_profile_csv
    from vbikit.traffic.records import read_records
    from vbikit.vehicle.trains import read_train_table

    return {"train table": read_train_table, "records": read_records, "road profile": read_profile_csv,
            "field response": read_response_csv, "mode file": read_modes}


READERS = ["train table", "records", "road profile", "field response", "mode file"]


@pytest.mark.parametrize("reader", READERS)
@pytest.mark.parametrize("via_link", [False, True])
def test_no_content_in_messages(tmp_path, reader, via_link):
    """A 'system file' (first line a secret) given as an input: the error names the file, never its content."""
    secret = tmp_path / "passwd"
    secret.write_text(f"{SECRET}\n{SECRET},{SECRET}\n")
    path = secret
    if via_link:
        path = tmp_path / "train.csv"
        path.symlink_to(secret)
    with pytest.raises(VbikitError) as err:
        _readers()[reader](path)
    assert "SECRET" not in str(err.value) and "4711" not in str(err.value)
    assert path.name in str(err.value)


def test_rail_table_at_a_system_file_via_the_command(tmp_path):
    """The case of the issue: a RAIL.toml whose table is a system file, directly and through a link."""
    from typer.testing import CliRunner

    from vbikit.cli import app

    secret = tmp_path / "system-file"
    secret.write_text(f"{SECRET}\n")
    (tmp_path / "link.csv").symlink_to(secret)
    for table in (str(secret), "link.csv"):
        (tmp_path / "RAIL.toml").write_text(
            "[bridge]\nspan = 20.0\nEI = 7.9e10\nmass_per_length = 25000.0\n"
            f"[trains]\ntables = [{table!r}]\n[speeds]\nmin = 100.0\nmax = 200.0\n".replace("'", '"'))
        res = CliRunner().invoke(app, ["rail", str(tmp_path / "RAIL.toml"), "--out-dir", str(tmp_path / "out")])
        assert res.exit_code == 2, res.output
        assert "SECRET" not in res.output and "trains.tables[1]" in res.output


@pytest.mark.parametrize("reader", READERS)
def test_ten_megabyte_field(tmp_path, reader):
    """A 10 MiB CSV field: a clear error naming the line (the csv module's limit is 128 KiB)."""
    path = tmp_path / "big.csv"
    path.write_text(f"{BIG},1\n")
    with pytest.raises(VbikitError) as err:
        _readers()[reader](path)
    assert "big.csv" in str(err.value) and len(str(err.value)) < 400


@pytest.mark.parametrize("reader", READERS)
def test_folder_and_fifo_refused(tmp_path, reader):
    with pytest.raises(VbikitError, match="folder"):
        _readers()[reader](tmp_path)
    if sys.platform != "win32":
        fifo = tmp_path / "pipe.csv"
        os.mkfifo(fifo)
        with pytest.raises(VbikitError, match="FIFO"):
            _readers()[reader](fifo)


def test_open_quote_names_the_line():
    from vbikit._files import csv_rows

    with pytest.raises(ValueError, match=r"^src:3: not a CSV line"):
        csv_rows('a,b\n# note\n1,"2\n', ValueError, "src")
    assert csv_rows(' a , b \n\n#c\n1,2\r\n', ValueError, "s") == [(1, ["a", "b"]), (4, ["1", "2"])]


def test_train_axles_must_increase():
    """All axles at position 0 (a train of zero length) is refused; so is any repeated position."""
    from vbikit.vehicle.trains import TrainError, parse_train_table

    with pytest.raises(TrainError, match="line 3: axle positions must increase"):
        parse_train_table("position,load\n0,100\n0,100\n0,100\n", "t")
    assert parse_train_table("0,100\n2.5,100\n", "t").length == pytest.approx(2.5)


def test_train_heavy_axle_warned(caplog):
    from vbikit.vehicle.trains import parse_train_table

    parse_train_table("0,1000\n3,200\n", "t")
    assert any("1 axle(s) above 400 kN" in r.getMessage() for r in caplog.records)
