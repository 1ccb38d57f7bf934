"""A single run's dataset (``Report.to_xarray``) carries the run's flags, as
every population dataset does: a trial read Girder 1's IM of 1.36 from the dataset of the Bridge 2 example with no
word that the run flags it (``small_static``) or that the road is one realisation (``one_realisation``)."""
from __future__ import annotations

import json

import vbikit
from vbikit.scenario import demo_scenario_text


def test_the_runs_dataset_carries_its_flags_records_warnings_and_codes():
    report = vbikit.run(demo_scenario_text(), step_check=False)
    assert any(f["code"] == "one_realisation" for f in report.summary["flags"])  # (the demo's class-C realisation)
    ds = report.to_xarray()
    assert json.loads(ds.attrs["flags"]) == report.summary["flags"]
    assert ds.attrs["warnings"] == "; ".join(report.summary["warnings"])
    assert "one_realisation" in ds.attrs["flag_codes"].split(",")


def test_a_study_datasets_small_static_flag_names_its_point_and_share():
    from vbikit.analysis.checks import SMALL_STATIC_FRACTION, small_static_dataset_flags

    # three crossings, points a and b: b under 20 % of a in crossings 0 and 2 (shares 0.1 and 0.05), not in 1
    static = [[-1.0, -0.1], [-1.0, -0.5], [-2.0, -0.1]]
    (flag,) = small_static_dataset_flags(["a", "b"], static)
    assert flag.code == "small_static" and flag.point == "b" and flag.output == "impact_factor"
    assert flag.value == 0.05 and flag.threshold == SMALL_STATIC_FRACTION
    assert "point b: " in flag.message and "in 2 of 3 crossings" in flag.message
    assert set(flag.as_dict()) >= {"code", "message", "output", "subject", "girder", "point", "wheel", "value",
                                   "threshold"}


def test_a_relative_change_prints_two_significant_figures():
    from vbikit.scenario.step_check import percent_words

    assert percent_words(2.3e-5) == "0.0023 %" and percent_words(0.0077) == "0.77 %" and percent_words(0.0) == "0 %"
