"""Records files that are not records: never echoed, refused by type and size before they are
read, with limits on records, line length and axles; implausible axle loads warned of, impossible
ones refused.  Every message names the file and line (and column), never the text found there."""
from __future__ import annotations

import logging
import os
import re
import subprocess
import sys
import time

import pytest

from vbikit.traffic import RecordsError, parse_records, read_records
from vbikit.traffic.records import MAX_AXLES, MAX_LINE, MAX_RECORDS

HEAD = "time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n"
ROW = "0.0,1,+x,80,53.4 75.6,5.5\n"
CLI = [sys.executable, "-c", "from vbikit.cli import main; main()"]
SECRET = "s3cr3t-T0KEN-4f9a"


def _traffic(path, tmp_path, env=None, timeout=120):
    """`vbikit traffic PATH …` in a subprocess (a hang fails by the timeout)."""
    return subprocess.run([*CLI, "traffic", str(path), "--bridge", "paper-bridge-2-beam", "--out",
                           str(tmp_path / "x.nc"), "--no-progress"], capture_output=True, text=True, timeout=timeout,
                          env={**os.environ, **(env or {})})


def test_a_password_like_file_is_not_echoed(tmp_path):
    """A file of another format (accounts, as /etc/passwd) is refused naming the file, line and
    column; none of its text appears in the message."""
    fake = tmp_path / "passwd"
    fake.write_text(f"root:x:0:0:{SECRET}:/root:/bin/bash\nuser:{SECRET}:1000\n")
    with pytest.raises(RecordsError) as info:
        read_records(fake)
    msg = str(info.value)  # the file named as given (the whole path), then its line and column
    assert msg.startswith(f"{fake}:1: column 1 of the header is not a known column; allowed: time [s]")
    rest = msg.removeprefix(str(fake))  # (the temporary folder's name may hold "root")
    assert SECRET not in rest and "root" not in rest and "bash" not in rest
    if os.path.isfile("/etc/passwd"):  # the real file, through the command line
        res = _traffic("/etc/passwd", tmp_path)
        assert res.returncode == 2 and "passwd:1: column 1 of the header is not a known column" in res.stderr
        assert "root" not in res.stderr and "/bin/" not in res.stderr and "Traceback" not in res.stderr


@pytest.mark.parametrize("cell, column", [("speed", 4), ("axle_loads", 5), ("direction", 3), ("lane", 2)])
def test_a_bad_cell_is_named_by_line_and_column_not_echoed(cell, column):
    header = HEAD.strip().split(",")
    row = ROW.strip().split(",")
    row[column - 1] = SECRET
    with pytest.raises(RecordsError) as info:
        parse_records(HEAD + ",".join(row) + "\n")
    assert str(info.value).startswith(f"records:2: column {column} ({header[column - 1].strip()}): ")
    assert SECRET not in str(info.value)


@pytest.mark.skipif(not os.path.exists("/proc/self/environ"), reason="needs Linux /proc")
def test_proc_environ_is_refused_without_its_variables(tmp_path):
    """/proc/self/environ (the process's environment, NUL-separated, reported as 0 bytes) is
    refused as binary, naming the line of the first NUL byte; no variable is echoed."""
    res = _traffic("/proc/self/environ", tmp_path, env={"VBIKIT_TEST_SECRET": SECRET})
    assert res.returncode == 2, res.stderr
    assert "/proc/self/environ:1: a NUL byte: not a text file" in res.stderr
    assert SECRET not in res.stderr and "PATH=" not in res.stderr and "Traceback" not in res.stderr


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_devices_fifos_and_folders_are_refused_before_reading(tmp_path):
    """/dev/zero (an endless read: MemoryError before), a FIFO without a writer (blocked the read
    for ever) and a folder: refused by their type at once."""
    fifo = tmp_path / "records.csv"
    os.mkfifo(fifo)
    for path, kind in (("/dev/zero", "a character device"), (fifo, r"a FIFO \(named pipe\)"), (tmp_path, "a folder")):
        t0 = time.perf_counter()
        with pytest.raises(RecordsError, match=f"^{path} is {kind}, not a regular file; give the records file"):
            read_records(path)
        assert time.perf_counter() - t0 < 1.0
    res = _traffic(fifo, tmp_path, timeout=60)
    assert res.returncode == 2 and "FIFO" in res.stderr and "Traceback" not in res.stderr


def test_files_above_the_size_limit_are_refused_before_reading(tmp_path):
    """The default limit (256 MiB) on a sparse 300 MiB file: refused from its size, without reading
    it; a smaller limit from VBIKIT_MAX_INPUT_MB; the message names the limit and how to raise it."""
    big = tmp_path / "big.csv"
    with open(big, "wb") as fh:
        fh.truncate(300 * 2**20)  # sparse: no data written
    t0 = time.perf_counter()
    with pytest.raises(RecordsError, match=r"big\.csv: the records file \(CSV\) is 300\.0 MiB, more than the 256\.0 MiB "
                                           r"allowed for an input file; set the environment variable VBIKIT_MAX_INPUT_MB"):
        read_records(big)
    assert time.perf_counter() - t0 < 1.0
    small = tmp_path / "small.csv"
    small.write_text(HEAD + ROW * 100)  # 71 + 100 × 26 = 2,671 bytes
    assert len(read_records(small)) == 100
    res = _traffic(small, tmp_path, env={"VBIKIT_MAX_INPUT_MB": "0.001"})  # int(0.001 × 2^20) = 1,048 bytes
    assert res.returncode == 2, res.stderr
    assert "small.csv: the records file (CSV) is 2,671 bytes, more than the 1,048 bytes allowed" in res.stderr
    assert "set the environment variable VBIKIT_MAX_INPUT_MB (in MiB)" in res.stderr
    res = _traffic(small, tmp_path, env={"VBIKIT_MAX_INPUT_MB": "lots"})
    assert res.returncode == 2 and "VBIKIT_MAX_INPUT_MB must be a size in MiB > 0" in res.stderr


def test_a_huge_cell_and_a_huge_axle_list_are_refused():
    """A 10 MB cell and a list of 100,000 axle loads (tracebacks before): the line is refused by its
    length; a list of more than MAX_AXLES axles within the line limit by its count."""
    with pytest.raises(RecordsError, match=rf"records:2: a line of 10,000,017 characters; a records line holds at "
                                           rf"most {MAX_LINE:,}"):
        parse_records(HEAD + "0.0,1,+x,80,53.4," + "x" * 10_000_000 + "\n")
    # 12 + (4 × 100,000 − 1) + 1 + (4 × 99,999 − 1) = 800,007 characters
    with pytest.raises(RecordsError, match=r"records:2: a line of 800,007 characters"):
        parse_records(HEAD + "0.0,1,+x,80," + " ".join(["100"] * 100_000) + "," + " ".join(["1.2"] * 99_999) + "\n")
    n = MAX_AXLES + 1
    with pytest.raises(RecordsError, match=rf"records:2: column 5 \(axle_loads \[kN\]\): {n} values; a vehicle has at "
                                           rf"most {MAX_AXLES} axles"):
        parse_records(HEAD + "0.0,1,+x,80," + " ".join(["50"] * n) + "," + " ".join(["1.2"] * (n - 1)) + "\n")
    assert len(parse_records(HEAD + "0.0,1,+x,80," + " ".join(["50"] * MAX_AXLES) + ","
                             + " ".join(["1.2"] * (MAX_AXLES - 1)) + "\n")[0].axle_loads) == MAX_AXLES


def test_nul_bytes_are_refused_with_their_line(tmp_path):
    path = tmp_path / "nul.csv"
    path.write_bytes((HEAD + ROW + "1.0,1,+x,80,53.4\x0075.6,5.5\n").encode())
    with pytest.raises(RecordsError, match=r"nul\.csv:3: a NUL byte: not a text file"):
        read_records(path)


def test_axle_loads_beyond_legal_limits_are_warned_impossible_ones_refused(caplog):
    """30 t (294.2 kN) is about three times a legal single axle: a 100-tonne axle is read with a
    warning naming the line; a negative, non-finite or > 1,000 t axle load is refused."""
    text = HEAD + ROW + "2.0,1,+x,80,53.4 980.7,5.5\n" + "3.0,2,-x,80,290 294,1.3\n"
    with caplog.at_level(logging.WARNING, logger="vbikit.traffic.records"):
        recs = parse_records(text)
    assert recs[1].axle_loads[1] == pytest.approx(980.7e3)  # 100 t × 9.807 m/s² = 980.7 kN: read, not changed
    warnings = [r.getMessage() for r in caplog.records]
    assert warnings == ["records: 1 record(s) with an axle load above 30 t (294 kN), far beyond legal axle limits "
                        "(line 3); check the values and their units"]
    for loads, match in (("53.4 -75.6", r"every axle load must be > 0 \(got -75\.6 kN\)"), ("53.4 nan", "not a list of finite numbers"),
                         ("inf 75", "not a list of finite numbers"), ("53.4 1e7", r"an axle load of 1\.02e\+06 t is impossible")):
        with pytest.raises(RecordsError, match=rf"records:2: column 5 \(axle_loads \[kN\]\): {match}"):
            parse_records(HEAD + f"0.0,1,+x,80,{loads},5.5\n")


def test_speeds_beyond_200_kmh_are_warned(caplog):
    with caplog.at_level(logging.WARNING, logger="vbikit.traffic.records"):
        parse_records(HEAD + ROW.replace(",80,", ",199,") + ROW.replace(",80,", ",210,"))
    assert [r.getMessage() for r in caplog.records if "speed above" in r.getMessage()] == [
        "records: 1 record(s) with a speed above 200 km/h (line 3); check the values and their units"]


def test_a_speed_out_of_range_is_refused_with_the_range_it_must_be_in():
    """A record's speed is 0.0036 … 252 km/h (0.001 … 70 m/s: the scenario's smallest speed, a road
    vehicle's largest).  Both refusals state that range; before 2026-12-06 a speed above it said "the allowed
    0 … 252 km/h", though 0.001 km/h is refused too, and the smallest speed's own message gave no upper bound."""
    allowed = "allowed 0.0036 … 252 km/h (0.001 … 70 m/s)"
    with pytest.raises(RecordsError, match=re.escape(f"records:2: column 4 (speed [km/h]): 253 km/h is above the "
                                                     f"largest speed 252 km/h; {allowed}")):
        parse_records(HEAD + ROW.replace(",80,", ",253,"))
    with pytest.raises(RecordsError, match=re.escape(f"records:2: column 4 (speed [km/h]): 0.001 km/h is below the "
                                                     f"smallest speed 0.0036 km/h (such a crossing would last days); "
                                                     f"{allowed}")):
        parse_records(HEAD + ROW.replace(",80,", ",0.001,"))
    with pytest.raises(RecordsError, match=re.escape("column 4 (speed [m/s]): 252.4 km/h is above the largest speed "
                                                     f"252 km/h; {allowed}")):  # (70.1 m/s: given in m/s)
        parse_records(HEAD.replace("speed [km/h]", "speed [m/s]") + ROW.replace(",80,", ",70.1,"))
    # just past an end: the value printed with the digits that put it there (before 2026-12-06 "252 km/h is above
    # the largest speed 252 km/h" for 252.01 km/h, "0.0036 km/h is below … 0.0036 km/h" for 0.0035999 km/h)
    with pytest.raises(RecordsError, match=re.escape("252.01 km/h is above the largest speed 252 km/h;")):
        parse_records(HEAD + ROW.replace(",80,", ",252.01,"))
    with pytest.raises(RecordsError, match=re.escape("0.0035999 km/h is below the smallest speed 0.0036 km/h")):
        parse_records(HEAD + ROW.replace(",80,", ",0.0035999,"))
    # 0 or a negative speed: the same refusal with the range (before 2026-12-06 "must be > 0, got -60", as if
    # 0.001 km/h would do, and not a word on the direction column that gives the sense of travel)
    with pytest.raises(RecordsError, match=re.escape("-60 km/h is below the smallest speed 0.0036 km/h (a speed is "
                                                     "positive: the direction column, +x or -x, gives the sense of "
                                                     f"travel); {allowed}")):
        parse_records(HEAD + ROW.replace(",80,", ",-60,"))
    with pytest.raises(RecordsError, match=re.escape("0 km/h is below the smallest speed 0.0036 km/h (a speed is")):
        parse_records(HEAD + ROW.replace(",80,", ",0,"))
    for kmh in ("0.0036", "252"):  # the ends themselves are read
        assert parse_records(HEAD + ROW.replace(",80,", f",{kmh},"))[0].speed == pytest.approx(float(kmh) / 3.6)


def test_a_million_rows_are_refused_before_parsing(tmp_path):
    """1,000,001 rows (a 9-minute read and validation before): refused from the row count within
    seconds; the message names the count, the limit and how to raise it."""
    path = tmp_path / "million.csv"
    path.write_text(HEAD + "0,1,+x,80,50,\n" * 1_000_001)
    t0 = time.perf_counter()
    with pytest.raises(RecordsError, match=r"million\.csv: 1,000,001 vehicle records, more than the 100,000 allowed "
                                           r"in one stream; split the file, or raise the limit \(vbikit traffic "
                                           r"--max-vehicles"):
        read_records(path)
    assert time.perf_counter() - t0 < 10.0
    assert MAX_RECORDS == 100_000
    few = HEAD + ROW * 3
    assert len(parse_records(few, max_records=3)) == 3
    with pytest.raises(RecordsError, match="3 vehicle records, more than the 2 allowed"):
        parse_records(few, max_records=2)
    (tmp_path / "three.csv").write_text(few)
    res = subprocess.run([*CLI, "traffic", str(tmp_path / "three.csv"), "--bridge", "paper-bridge-2-beam", "--out",
                          str(tmp_path / "x.nc"), "--max-vehicles", "2"], capture_output=True, text=True, timeout=120)
    assert res.returncode == 2 and "three.csv: 3 vehicle records, more than the 2 allowed" in res.stderr


def test_lane_centres_must_be_finite(tmp_path):
    (tmp_path / "one.csv").write_text(HEAD + ROW)
    for lanes in ("nan,0", "1e300,0", "inf"):
        res = subprocess.run([*CLI, "traffic", str(tmp_path / "one.csv"), "--bridge", "paper-bridge-2-beam", "--out",
                              str(tmp_path / "x.nc"), "--lanes", lanes], capture_output=True, text=True, timeout=120)
        assert res.returncode == 2 and "--lanes: lane centres must be finite numbers within ±50 m" in res.stderr, lanes


def test_records_whose_wheels_leave_the_deck_are_refused_before_the_run():
    """paper-bridge-2 is a 9.75 m wide deck (edges at ±4.875 m); an axle-record truck has its
    wheels at ±0.9 m (axles.HALF_TRACK): a centreline at 3.975 m puts the outer wheels on the edge
    (accepted), at 3.98 m (either direction, mirrored) off it (refused, naming the line; 1e300 m
    the reader refuses, beyond any deck's ±50 m); the same for a lane centre given with --lanes."""
    from vbikit.study.spec import StudyError
    from vbikit.traffic.study import base_scenario, traffic_study

    base, _ = base_scenario("paper-bridge-2")
    head = "time [s],lateral_offset [m],direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n"
    assert traffic_study(parse_records(head + "0,3.975,+x,80,50 90,4.2\n0,-3.975,-x,80,50 90,4.2\n"), base).size == 1
    for y, direction in (("3.98", "+x"), ("-3.98", "-x")):
        with pytest.raises(StudyError, match=rf"records:3: lateral_offset at y = {re.escape(f'{float(y):g}')} m puts wheels at y = "
                                             rf"[0-9.e+]+ m from the centreline, off the 9\.75 m wide deck"):
            traffic_study(parse_records(head + "0,0,+x,80,50 90,4.2\n" + f"9,{y},{direction},80,50 90,4.2\n"), base)
    from vbikit.traffic.records import RecordsError

    with pytest.raises(RecordsError, match=r"3: column 2 \(lateral_offset \[m\]\): 1e\+300 m is beyond the allowed ±50 m"):
        parse_records(head + "0,0,+x,80,50 90,4.2\n" + "9,1e300,+x,80,50 90,4.2\n")  # (the reader: any bridge)
    with pytest.raises(StudyError, match=r"records:2: lane 2 at y = 4 m puts wheels at y = 4\.9 m from the centreline"):
        traffic_study(parse_records(HEAD + "0.0,2,+x,80,53.4 75.6,5.5\n"), base, lanes=[0.0, 4.0])


_CELLS = ["0", "1.5", "-1", "nan", "inf", "1e300", "-0", "", " ", "+x", "-x", "north", "80", "53.4 75.6", "5.5",
          "1;2", "hs20-44", "axles", "2", "0.0", '"a,b"', "\x01", "é", "1e7", "9" * 5000]


def test_any_row_is_read_or_refused_with_a_records_error():
    """Generated rows (hypothesis) under a valid header: each is read (finite values in their
    ranges) or refused with a RecordsError naming line 2 — never another exception."""
    import math

    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    header = "time [s],lane,lateral_offset [m],direction,speed [km/h],model,axle_loads [kN],axle_spacings [m]\n"
    cell = st.one_of(st.sampled_from(_CELLS), st.text(max_size=12))

    @settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
    @given(st.lists(cell, min_size=7, max_size=9))
    def check(cells):
        text = header + ",".join(c.replace("\n", " ").replace("\r", " ") for c in cells) + "\n"
        try:
            records = parse_records(text)
        except RecordsError as err:
            assert str(err).startswith("records:2: ")
            return
        if not records:  # a row starting with '#' (or blank) is a comment
            assert not text.split("\n")[1].strip() or text.split("\n")[1].lstrip().startswith("#")
            return
        [r] = records
        assert math.isfinite(r.time) and r.time >= 0 and 0 < r.speed <= 70 and r.direction in ("+x", "-x")
        assert all(math.isfinite(v) and 0 < v <= 1e6 * 9.80665 for v in r.axle_loads)
        assert len(r.axle_loads) <= MAX_AXLES

    check()


def test_the_dataset_names_the_records_file_without_the_users_folders(tmp_path, monkeypatch):
    """The stream dataset's ``records`` attribute: a relative path as given on the command line
    (``sub/one.csv``), an absolute one by its name only (``one.csv``; before 2026-12-06 the whole path,
    the user's folders in a dataset shared with others)."""
    import xarray as xr
    from typer.testing import CliRunner

    from vbikit.cli import app

    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "one.csv").write_text(HEAD + ROW)
    monkeypatch.chdir(tmp_path)
    for given, out, stored in ((str(tmp_path / "sub" / "one.csv"), "abs.nc", "one.csv"),
                               ("sub/one.csv", "rel.nc", "sub/one.csv")):
        res = CliRunner().invoke(app, ["traffic", given, "--bridge", "paper-bridge-2-beam", "--out", out,
                                       "--workers", "1", "--no-progress"])
        assert res.exit_code == 0, res.output
        with xr.open_dataset(tmp_path / out) as ds:
            assert ds.attrs["records"] == stored
            assert str(tmp_path) not in ds.attrs["records"]
