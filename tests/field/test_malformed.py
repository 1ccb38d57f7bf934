"""Malformed field files: each kind of fault gives an error naming the file and line or key."""
from __future__ import annotations

from dataclasses import replace as dataclass_replace
from pathlib import Path

import pytest

from vbikit.field import FieldFileError, load_field_toml, read_response_csv
from vbikit.field.io import check_case_record


GOOD = """# comment
time [s],G5_disp [mm],G5_acc [m/s^2]
0.000,0.0,0.0
0.005,0.1,0.2
0.010,0.2,0.1
0.015,0.3,0.0
0.020,0.2,-0.1
"""


def write(tmp_path: Path, text: str, name: str = "r.csv") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def test_good_file_in_si(tmp_path):
    rec = read_response_csv(write(tmp_path, GOOD))
    assert rec.sampling_rate == pytest.approx(200.0)
    assert rec.channels["G5_disp"][1] == pytest.approx(1e-4)  # mm → m
    assert rec.units["G5_acc"] == "m/s^2"


@pytest.mark.parametrize(
    "bad, message",
    [
        (GOOD.replace("0.010,0.2,0.1", "0.010,nan,0.1"), r"r\.csv:5: column 2 \(G5_disp\): not finite"),
        (GOOD.replace("0.010,0.2,0.1", "0.010,,0.1"), r"r\.csv:5: column 2 \(G5_disp\): not a number"),
        (GOOD.replace("0.010,0.2,0.1", "0.004,0.2,0.1"), r"r\.csv:5: time 0\.004 s is not greater than the previous"),
        (GOOD.replace("0.015,0.3,0.0", "0.016,0.3,0.0"), r"r\.csv:6: non-uniform time step"),
        (GOOD.replace("G5_acc [m/s^2]", "G5_acc [furlong]"), r"r\.csv:2: header column 3: unknown unit; allowed"),
        (GOOD.replace("G5_acc [m/s^2]", "G5_acc"), r"r\.csv:2: header column 3 is not 'name \[unit\]'"),
        (GOOD.replace("time [s]", "time [mm]"), r"r\.csv:2: the first column must be time"),
        (GOOD.replace("0.010,0.2,0.1", "0.010,0.2"), r"r\.csv:5: expected 3 columns, got 2"),
    ],
    ids=["nan", "empty", "unsorted", "non-uniform", "unit", "header", "time-unit", "columns"],
)
def test_bad_csv(tmp_path, bad, message):
    with pytest.raises(FieldFileError, match=message):
        read_response_csv(write(tmp_path, bad))


def test_example_loads(example):
    spec = load_field_toml(example / "FIELD.toml")
    assert [c.name for c in spec.cases] == ["case1", "case2"]
    for case in spec.cases:
        check_case_record(case, read_response_csv(case.responses), spec.path)


def edit(example: Path, old: str, new: str, count: int = 1) -> Path:
    p = example / "FIELD.toml"
    text = p.read_text()
    assert old in text
    p.write_text(text.replace(old, new, count))
    return p


def test_missing_channel(example):
    spec = load_field_toml(edit(example, 'name = "G5_acc"', 'name = "G5_accel"'))
    case = spec.cases[0]
    with pytest.raises(FieldFileError, match=r"case1_responses\.csv: channel 'G5_accel' .* is missing; the file has: G5_disp"):
        check_case_record(case, read_response_csv(case.responses), spec.path)


def test_unit_mismatch(example):
    spec = load_field_toml(edit(example, 'unit = "mm"', 'unit = "m"'))
    case = spec.cases[0]
    with pytest.raises(FieldFileError, match=r"'G5_disp' is in \[mm\] but FIELD\.toml .* says \[m\]: unit mismatch"):
        check_case_record(case, read_response_csv(case.responses), spec.path)


def test_sampling_rate_mismatch(example):
    spec = load_field_toml(edit(example, "sampling_rate = 200.0", "sampling_rate = 100.0"))
    case = spec.cases[0]
    with pytest.raises(FieldFileError, match=r"sampled at 200 Hz but FIELD\.toml case 'case1' says sampling_rate = 100 Hz"):
        check_case_record(case, read_response_csv(case.responses), spec.path)


@pytest.mark.parametrize(
    "old, new, message",
    [
        ('model = "dump-truck"\n', "", r"missing key vehicle\.model"),
        ("speed_kmh = 64.4", "speed_kmh = -1", r"crossing\.speed_kmh: expected a number in \[0\.0036, 1080\] \[km/h\], got -1"),
        ("speed_kmh = 64.4", "speed_kmh = 2000", r"crossing\.speed_kmh: expected a number in \[0\.0036, 1080\] \[km/h\]"),  # a scenario's range
        ("speed_kmh = 64.4", "speed_kmh = 64.4\nspeed = 3", r"crossing\.speed: unknown key; allowed: "),
        ('quantity = "strain"', 'quantity = "stress"', r"case\[1\]\.channel\[3\]\.quantity must be one of"),
        ('unit = "microstrain"', 'unit = "mm"', r"case\[1\]\.channel\[3\]\.unit \[mm\] is not a strain unit"),
        ("girder = 5", "girder = 0", r"case\[1\]\.channel\[1\]\.girder: expected an integer >= 1, got 0"),
        ("trigger_time = 1.237\n", "", r"case\[1\]\.trigger_time is required with align = 'trigger'"),
        ('responses = "case1_responses.csv"', 'responses = "nope.csv"', r"case\[1\]\.responses: file not found"),
        ('drift = "quiet"', 'drift = "magic"', r"signal\.drift must be"),
        ("x = 8.38", "x = 'mid'", r"case\[1\]\.channel\[1\]\.x: expected a number >= 0, got str 'mid'"),
    ],
    ids=["missing", "negative", "too fast", "unknown", "quantity", "unit", "girder", "trigger", "file", "drift", "x"],
)
def test_bad_toml(example, old, new, message):
    with pytest.raises(FieldFileError, match=message):
        load_field_toml(edit(example, old, new))


def test_not_toml(tmp_path):
    with pytest.raises(FieldFileError, match="not valid TOML"):
        load_field_toml(write(tmp_path, "bridge = ", "FIELD.toml"))


def test_flat_layout_is_read_with_a_deprecation_message(example):
    """The earlier flat FIELD.toml keys (bridge = "…", truck = "…", speed_kmh … at the top) give
    the same test as the sectioned layout, with a FutureWarning naming the new keys."""
    new = load_field_toml(example / "FIELD.toml")
    text = (example / "FIELD.toml").read_text()
    flat = text.replace('[bridge]\nmodel = "cypress-bayou"', 'bridge = "cypress-bayou"').replace(
        '[vehicle]\nmodel = "dump-truck"', 'truck = "dump-truck"').replace("[crossing]\n", "")
    (example / "OLD.toml").write_text(flat)
    with pytest.warns(FutureWarning, match=r"bridge → bridge\.model, truck → vehicle\.model"):
        old = load_field_toml(example / "OLD.toml")
    assert (old.bridge, old.truck, old.speed, old.approach, old.free_vibration, old.n_modes, old.damping_ratio) == \
        (new.bridge, new.truck, new.speed, new.approach, new.free_vibration, new.n_modes, new.damping_ratio)
    assert old.cases == new.cases


@pytest.mark.parametrize("name", ["case1\\n", "case1\\r", "case1\\t", "case1/x"])
def test_case_name_with_a_line_break_or_separator_is_refused(example, name):
    """A case name names output files: a trailing newline (which a '$'-anchored pattern lets
    through) or another control character is refused, naming the key."""
    with pytest.raises(FieldFileError, match=r"case\[1\]\.name = .* cannot be used in a file name"):
        load_field_toml(edit(example, 'name = "case1"', f'name = "{name}"'))


def test_response_file_that_is_not_a_regular_file_is_refused_unread(tmp_path):
    """A FIFO with no writer (would block the read forever) and a folder are refused by type,
    before they are opened."""
    import os

    fifo = tmp_path / "r.csv"
    os.mkfifo(fifo)
    with pytest.raises(FieldFileError, match=r"r\.csv is a FIFO \(named pipe\), not a regular file"):
        read_response_csv(fifo)
    with pytest.raises(FieldFileError, match="is a folder, not a regular file"):
        read_response_csv(tmp_path)


@pytest.mark.parametrize("cut, ok", [(1e-9, False), (1.0 / 0.02 * 0.99, False), (50.0, True), (100.0, False), (250.0, False)],
                         ids=["1e-9 Hz", "just below 1/T", "1/T", "Nyquist", "above Nyquist"])
def test_lowpass_must_fit_the_record(tmp_path, example, cut, ok):
    """``signal.lowpass_hz`` against a case's record (0.02 s at 200 Hz): from 1/T = 50 Hz up to below
    the Nyquist frequency 100 Hz; outside, an error naming the key, the case, the file and the range
    (a cut-off of 1e-9 Hz made the filter's start-up solve singular: a traceback, found by fuzzing)."""
    spec = load_field_toml(example / "FIELD.toml")
    case = dataclass_replace(spec.cases[0], channels=())
    record = read_response_csv(write(tmp_path, GOOD))
    if ok:
        check_case_record(case, record, spec.path, cut)
        return
    with pytest.raises(FieldFileError, match=r"FIELD\.toml: signal\.lowpass_hz = .* Hz does not fit the record of case "
                                             r"'case1' \(r\.csv: 0\.02 s sampled at 200 Hz\): the cut-off must be at least "
                                             r"1/duration = 50 Hz and below the Nyquist frequency 100 Hz"):
        check_case_record(case, record, spec.path, cut)
