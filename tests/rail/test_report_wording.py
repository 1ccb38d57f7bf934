"""What an engineer reads of `vbikit rail`: one way of writing a speed, and the speed grid's error
stated once, on one line."""
from __future__ import annotations

import re

import pytest

from vbikit.rail.report import kmh, speed_words


def test_a_speed_is_written_to_a_tenth_of_a_km_per_h():
    # 250.56 km/h = 69.6 m/s (hand: 250.56 / 3.6); 1 m/s = 3.6 km/h
    assert kmh(250.56 / 3.6) == "250.6" and speed_words(250.56 / 3.6) == "250.6 km/h"
    assert speed_words(1.0) == "3.6 km/h"


@pytest.fixture(scope="module")
def report():
    from vbikit.rail.run import run_rail

    return run_rail({"bridge": {"span": 20.0, "EI": 7.9e10, "mass_per_length": 25000.0},
                     "trains": {"presets": ["hslm-a4"]}, "speeds": {"min": 200.0, "max": 240.0, "step": 10.0}},
                    figures=False)


def test_every_speed_of_the_report_has_one_format(report):
    """Every "… km/h" number of the report has one decimal (before, the acceleration's governing speed
    had two and the same speed elsewhere one); the governing speed reads the same everywhere."""
    speeds = re.findall(r"(\d+(?:\.\d+)?) km/h", report.report)
    assert speeds and all(re.fullmatch(r"\d+\.\d", v) for v in speeds), speeds
    governing = speed_words(report.checks["acceleration"]["speed"])
    lines = report.report.splitlines()
    assert governing in next(x for x in lines if x.startswith("deck acceleration: peak"))
    assert governing in lines[-1] and lines[-1].startswith("result:")


def test_the_speed_grid_error_is_one_statement(report):
    """One line speaks of the speed grid (before, the acceleration's grid error had a line of its own
    beside the line of every check's, and the moment and shear lines their own clauses); it gives
    the acceleration's grid value, its shortfall and bound, and the bound over all the trains' peaks."""
    acc = report.checks["acceleration"]
    grid_lines = [x for x in report.report.splitlines() if "speed grid" in x or "error bound" in x]
    assert len(grid_lines) == 1 and grid_lines[0].startswith("speed grid error of the governing peaks")
    line = grid_lines[0]
    assert f"the sweep's grid ({acc['grid_peak']:.3f} m/s²) {100 * acc['grid_error']:.2f} % low" in line
    assert f"of all trains' refined peaks at most {100 * acc['largest_refinement_bound']:.3f} %" in line
    assert f"({report.checks['moment']['grid_design'] / 1e3:.4g} kN m)" in line  # the moment's grid value, in kN m
