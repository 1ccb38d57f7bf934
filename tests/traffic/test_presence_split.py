"""The single / multiple-presence split of a traffic stream against an independent count.

Eight two-axle trucks (axles 5 m apart, 20 m/s) over a 20 m beam: a truck is on the bridge from
its entry time t until its rear axle leaves, t + (20 + 5) / 20 = t + 1.25 s.  The times are chosen
so that every boundary a split could get wrong is there: a pair that overlaps only because of the
trucks' length (1.1 s apart: overlapping for 0.15 s, not if the span alone is counted), a truck
entering 0.05 s after the last one left (alone), a chain of three in which the first and the third
never meet (one event of three), and one entering 0.02 s after the chain has left.  The events are
found here by brute force (every pair of on-bridge intervals, then connected components), and the
study's counts and mean impact factors of the single and multiple events must be those of this
count.  Swapping the split, counting two-vehicle events as single (``> 2``) or dropping the trucks'
length each changes the counts or the means.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from vbikit.study.run import run_study
from vbikit.traffic import VehicleRecord
from vbikit.traffic.study import traffic_study

from .test_records_events import _components

SPAN, SPEED, SPACING = 20.0, 20.0, 5.0
BASE = {"bridge": {"model": "beam", "span": SPAN, "EI": 1.0e10, "mass_per_length": 10000.0, "n_modes": 3},
        "road": {"class": "none"}}
#: (time [s], lane, direction, front and rear axle loads [N])
TRUCKS = [(0.0, 1, "+x", 60e3, 90e3), (1.1, 2, "-x", 40e3, 70e3), (2.40, 1, "+x", 80e3, 120e3),
          (5.0, 1, "+x", 50e3, 50e3), (8.0, 1, "+x", 70e3, 100e3), (8.5, 2, "-x", 45e3, 85e3),
          (9.6, 1, "+x", 65e3, 95e3), (10.87, 2, "-x", 55e3, 75e3)]


def _records() -> list[VehicleRecord]:
    return [VehicleRecord(t, d, SPEED, (front, rear), (SPACING,), lane=lane, id=f"v{i}")
            for i, (t, lane, d, front, rear) in enumerate(TRUCKS)]


def _groups(records) -> list[frozenset[int]]:
    """The events by brute force: connected components of the overlap graph of the on-bridge
    intervals [t, t + (span + length) / v]."""
    start = [r.time for r in records]
    end = [r.time + (SPAN + sum(r.axle_spacings)) / r.speed for r in records]
    return _components(start, end)


@pytest.fixture(scope="module")
def stream(tmp_path_factory):
    records = _records()
    job = traffic_study(records, BASE, lanes=[-1.0, 1.0], batch_size=8)
    return records, run_study(job, tmp_path_factory.mktemp("presence") / "s.nc", workers=1)


def test_the_hand_designed_events():
    # the brute-force count is the one the stream was designed for
    assert sorted(sorted(g) for g in _groups(_records())) == [[0, 1], [2], [3], [4, 5, 6], [7]]


def test_split_against_the_independent_count(stream):
    records, ds = stream
    groups = _groups(records)
    event_of = ds["vehicle_event"].values
    # the study's events are the brute-force groups
    assert sorted(sorted(np.flatnonzero(event_of == e).tolist()) for e in range(ds.sizes["event"])) == \
        sorted(sorted(g) for g in groups)
    im = ds["impact_factor"].values
    single = [float(im[event_of[min(g)]]) for g in groups if len(g) == 1]
    multiple = [float(im[event_of[min(g)]]) for g in groups if len(g) > 1]
    assert (len(single), len(multiple)) == (3, 2)
    assert ds.attrs["n_multiple_presence_events"] == len(multiple)
    assert ds.attrs["n_events"] == len(groups)
    assert ds["multiple_presence"].values.tolist() == [int((event_of == e).sum() > 1) for e in range(ds.sizes["event"])]
    assert ds.attrs["im_mean_single"] == pytest.approx(sum(single) / len(single), rel=1e-12)
    assert ds.attrs["im_mean_multiple"] == pytest.approx(sum(multiple) / len(multiple), rel=1e-12)
    # the two means differ by far more than round-off, so a swapped split cannot pass
    assert abs(sum(single) / len(single) - sum(multiple) / len(multiple)) > 1e-3
    assert all(math.isfinite(v) for v in single + multiple)


def test_small_static_events_are_counted_and_left_out_of_the_loaded_statistics():
    """Events whose static peak is below 20 % of the stream's largest (a light car, a far lane) give IMs
    on a small reference: counted, and the loaded-event mean and 95 % quantile leave them out — by hand
    on a made-up dataset whose small events carry huge IMs (a wrong mask, or one on the dynamic peaks,
    moves the loaded mean by far more than round-off)."""
    import xarray as xr

    from vbikit.traffic.study import stream_statistics

    static = np.array([10.0, 9.0, 1.9, 0.5, 8.0, 2.1])  # mm: 1.9 and 0.5 below 20 % of 10
    im = np.array([0.10, 0.20, 1.50, 3.00, 0.30, 0.40])
    dyn = static * (1 + im)
    ds = xr.Dataset({"impact_factor": ("event", im), "max_dynamic_displacement": ("event", -dyn * 1e-3),
                     "max_static_displacement": ("event", -static * 1e-3),
                     "multiple_presence": ("event", np.array([0, 1, 0, 0, 1, 0]))},
                    coords={"vehicle": np.arange(8)})
    a = stream_statistics(ds)
    assert a["n_small_static_events"] == 2 and a["small_static_fraction"] == 0.2
    kept = im[[0, 1, 4, 5]]
    assert a["im_mean_loaded"] == pytest.approx(kept.mean(), rel=1e-12)
    assert a["im_q95_loaded"] == pytest.approx(np.quantile(kept, 0.95), rel=1e-12)
    assert a["im_mean"] == pytest.approx(im.mean(), rel=1e-12)  # the all-event figures are unchanged
