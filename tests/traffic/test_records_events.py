"""Vehicle records (CSV), events of overlapping vehicles, synthetic streams."""
from __future__ import annotations

import itertools

import numpy as np
import pytest

from vbikit.traffic import (
    LaneTraffic,
    RecordsError,
    parse_records,
    partition,
    read_records,
    synthetic_stream,
    write_records,
)

GOOD = """# two trucks
time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]
0.0,1,+x,80,53.4 75.6 75.6 75.6 75.6,5.5 1.3 9.5 1.3
1.5,2,-x,72,45 90,5.0
"""


def test_records_read_in_si_units():
    a, b = parse_records(GOOD)
    assert a.axle_loads == pytest.approx((53.4e3, 75.6e3, 75.6e3, 75.6e3, 75.6e3))
    assert a.speed == pytest.approx(80 / 3.6) and a.direction == "+x" and a.lane == 1
    assert b.axle_spacings == (5.0,) and b.direction == "-x" and b.line == 4
    assert a.length == pytest.approx(17.6)


@pytest.mark.parametrize("text, match", [
    ("time [s],lane,direction,speed [mph],axle_loads [kN],axle_spacings [m]\n", r"records:1: column 4 \(speed\) has a unit it does not take: write `speed \[km/h\]` or `speed \[m/s\]`\. "
     r"A header reads, e\.g\.: id,time \[s\],lane,direction,speed \[km/h\],axle_loads \[kN\],axle_spacings \[m\]$"),
    ("time [s],lane,direction,speed [km/h]\n0,1,+x,80\n", "records:2: model axles needs the column axle_loads"),
    ("time [s],direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n", r"missing required column\(s\) lane or lateral_offset"),
    (GOOD.replace("1.5,2,-x", "1.5,2,west"), r"records:4: column 3 \(direction\): must be \+x or -x$"),
    (GOOD.replace("45 90,5.0", "45 90,5.0 3"), r"records:4: column 6 \(axle_spacings \[m\]\): needs 1 spacing"),
    (GOOD.replace(",72,", ",fast,"), r"records:4: column 4 \(speed \[km/h\]\): not a number$"),
    (GOOD.replace("0.0,1,", "-1,1,"), r"records:3: column 1 \(time \[s\]\): must be >= 0, got -1$"),
    (GOOD.replace("0.0,1,+x", "0.0,0,+x"), r"records:3: column 2 \(lane\): must be a lane number"),
    (GOOD + "2.0,1,+x,80\n", r"records:5: 4 cells, the header has 6"),
    ("time [s],lane,weight [kN]\n", r"records:1: column 3 of the header is not a known column; allowed: time \[s\]"),
])
def test_bad_records_name_the_line_and_column(text, match):
    with pytest.raises(RecordsError, match=match):
        parse_records(text)


def test_header_errors_say_what_is_wrong_and_how_the_header_reads():
    """A new user's header ``time,lane,speed,gross`` was refused as "column 1 (time) takes [s], not
    the unit given" although no unit was given: now every problem of the header is named — the
    units left out, the unknown column, the required column missing — with a header that reads
    right, and nothing of the file's text but the format's own column names."""
    with pytest.raises(RecordsError) as err:
        parse_records("time,lane,speed,gross\n0,1,80,300\n", "user.csv")
    msg = str(err.value)
    assert msg.startswith("user.csv:1: column 4 of the header is not a known column; allowed: time [s], lane,")
    assert "column 1 (time) has no unit: write `time [s]`" in msg
    assert "column 3 (speed) has no unit: write `speed [km/h]` or `speed [m/s]`" in msg
    assert "missing required column(s) direction (required: time, lane or lateral_offset, direction, speed; id, " \
           "model, gross_weight optional)" in msg
    assert msg.endswith(". A header reads, e.g.: id,time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]")
    assert "not the unit given" not in msg and "gross," not in msg.replace("gross_weight", "")
    with pytest.raises(RecordsError) as err:  # a unit given: which one is wrong, not echoed
        parse_records("time [h],lane [m],direction,speed [km/h]\n", "user.csv")
    msg = str(err.value)
    assert "column 1 (time) has a unit it does not take: write `time [s]`" in msg
    assert "column 2 (lane) takes no unit: write `lane`" in msg and "[h]" not in msg and "missing" not in msg
    # the header of the docs' example is read (the records then parse)
    assert len(parse_records("id,time [s],lane,direction,speed [km/h],axle_loads [kN],axle_spacings [m]\n"
                             "v1,0,1,+x,80,45 90,5.0\n")) == 1



def test_model_column_and_gross_weight_check():
    text = ("time [s],lateral_offset [m],direction,speed [m/s],model,axle_loads [N],axle_spacings [m],gross_weight [kN]\n"
            "0,1.8,+x,20,hs20-44,,,\n"
            "3,-1.8,-x,20,,40000 90000,4.5,130\n")
    a, b = parse_records(text)
    assert a.model == "hs20-44" and a.lateral_offset == 1.8 and a.axle_loads == ()
    assert b.model == "axles" and b.gross_weight == 130e3
    with pytest.raises(RecordsError, match=r":3: column 8 \(gross_weight \[kN\]\): .* differs"):
        parse_records(text.replace(",130\n", ",140\n"))
    with pytest.raises(RecordsError, match=r":2: column 5 \(model\): not a vehicle preset; allowed: axles, "):
        parse_records(text.replace("hs20-44", "truck"))


def test_written_stream_reads_back_identical(tmp_path):
    lanes = [LaneTraffic(1, "+x", 600, 80), LaneTraffic(2, "-x", 400, 70)]
    stream = synthetic_stream(lanes, 300, seed=3)
    write_records(stream, tmp_path / "s.csv")
    assert read_records(tmp_path / "s.csv") == stream
    assert synthetic_stream(lanes, 300, seed=3) == stream  # same seed, same stream
    assert synthetic_stream(lanes, 300, seed=4) != stream


def test_poisson_arrivals_per_lane():
    """Headways h_min + Exp: mean 3600/flow (here 6 s and 12 s) and coefficient of variation
    (1 − h_min/mean) for a shifted exponential (0.67, 0.83); 4000 trucks: ±4 % (≈ 3 σ)."""
    lanes = [LaneTraffic(1, "+x", 600, 80), LaneTraffic(2, "-x", 300, 70)]
    stream = synthetic_stream(lanes, 4000, seed=11)
    for lane, flow in ((1, 600), (2, 300)):
        t = np.array([r.time for r in stream if r.lane == lane])
        h = np.diff(t)
        mean = 3600 / flow
        assert h.min() >= 2.0 - 1e-3
        assert h.mean() == pytest.approx(mean, rel=0.04)
        assert h.std() / h.mean() == pytest.approx(1 - 2.0 / mean, rel=0.06)
    assert all(r.direction == ("+x" if r.lane == 1 else "-x") for r in stream)
    share9 = np.mean([len(r.axle_loads) == 5 for r in stream])
    assert share9 == pytest.approx(0.60, abs=0.03)  # class 9 share of TRUCK_MIX


def _components(start, end):
    """Connected components of the interval-overlap graph, by brute force (union–find)."""
    parent = list(range(len(start)))

    def find(i):
        while parent[i] != i:
            i = parent[i]
        return i

    for i, j in itertools.combinations(range(len(start)), 2):
        if start[i] < end[j] and start[j] < end[i]:
            parent[find(i)] = find(j)
    groups: dict[int, set] = {}
    for i in range(len(start)):
        groups.setdefault(find(i), set()).add(i)
    return sorted(map(frozenset, groups.values()), key=min)


def test_events_partition_the_stream():
    lanes = [LaneTraffic(1, "+x", 900, 80), LaneTraffic(2, "-x", 900, 60, 15)]
    stream = synthetic_stream(lanes, 400, seed=5)
    span = 39.62
    t = [r.time for r in stream]
    v = [r.speed for r in stream]
    length = [r.length for r in stream]
    events = partition(t, v, length, span)
    members = [i for e in events for i in e.vehicles]
    assert sorted(members) == list(range(len(stream)))  # each vehicle in exactly one event
    start = np.array(t)
    end = start + (span + np.array(length)) / np.array(v)
    assert sorted(map(frozenset, (e.vehicles for e in events)), key=min) == _components(start, end)
    assert any(e.multiple_presence for e in events) and any(not e.multiple_presence for e in events)
    for a, b in zip(events, events[1:]):
        assert a.end <= b.start  # events do not overlap
    for e in events:
        assert e.start == pytest.approx(start[list(e.vehicles)].min())
        assert e.end == pytest.approx(end[list(e.vehicles)].max())


def test_partition_by_hand():
    # span 10 m, 10 m/s, length 0: on the bridge for 1 s each (touching intervals do not overlap)
    events = partition([0.0, 0.5, 3.0, 3.99, 4.98, 7.0], [10.0] * 6, [0.0] * 6, 10.0)
    assert [e.vehicles for e in events] == [(0, 1), (2, 3, 4), (5,)]


def test_partition_counts_a_skew_decks_oblique_ends():
    """A skew deck reaches ``reach`` beyond its supports along x: a vehicle is on it reach / v
    before its entry support and reach / v after the span (by hand: span 10 m, 10 m/s, reach
    1.5 m: on the deck from t − 0.15 s to t + 1.15 s), so two vehicles 1.2 s apart share it."""
    assert [e.vehicles for e in partition([0.0, 1.2], [10.0] * 2, [0.0] * 2, 10.0)] == [(0,), (1,)]
    events = partition([0.0, 1.2], [10.0] * 2, [0.0] * 2, 10.0, reach=1.5)
    assert [e.vehicles for e in events] == [(0, 1)]
    assert events[0].start == pytest.approx(-0.15, abs=1e-15)
    assert events[0].end == pytest.approx(1.2 + 1.15, abs=1e-15)
