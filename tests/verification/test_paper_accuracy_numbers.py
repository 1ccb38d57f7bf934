"""The paper programme against RK4 in docs/verification.md: the page quotes
docs/figures/paper-accuracy-numbers.json (written by docs/scripts/paper_accuracy_numbers.py), the
stored numbers are consistent with each other, and (slow: a few minutes) the script computes them
again.

The reference of every ΔIM is independent of the integrator under study: classical RK4 (the
paper's integrator) at its own automatic step, on the same crossings."""
from __future__ import annotations

from pathlib import Path

import pytest

from tests.verification.test_convergence_numbers import _script as _load, recomputed_equals_stored

ROOT = Path(__file__).resolve().parents[2]
HINT = "run python docs/scripts/paper_accuracy_numbers.py, then python docs/scripts/generate.py"


def _script():
    return _load("paper_accuracy_numbers")


def test_page_quotes_the_stored_numbers():
    script = _script()
    page = (ROOT / "docs" / "verification.md").read_text(encoding="utf-8")
    assert script.render() in page, HINT


def test_stored_numbers_are_the_scripts_programme():
    # every figure of the programme, with the script's number of profiles: 72 points a figure
    # (Figs. 5–8: 8 tires × 3 speeds × 3 classes; Figs. 10, 11: 3 tires × 8 speeds × 3 classes)
    script = _script()
    numbers = script.stored()
    assert list(numbers["figures"]) == list(script.FIGS), HINT
    assert numbers["samples"] == script.SAMPLES and numbers["required"] == script.REQUIRED, HINT
    for fig, f in numbers["figures"].items():
        assert f["crossings"] == 72 * script.SAMPLES, fig
        assert f["p95"] <= f["largest"] and f["largest_of_means"] <= f["largest"], fig
        assert 0 <= f["above_required"] <= f["checked"] <= f["crossings"], fig  # (every one above REQUIRED is checked)
        assert 0 <= f["checked_above_required"] <= f["checked"], fig
        if f["checked"]:
            # the largest against the refined reference is the difference of the IMs stored for its crossing
            c = f["checked_worst"]
            assert abs(c["default"] - c["rk4_half_step"]) == pytest.approx(f["checked_largest"], rel=1e-12), fig


def test_worst_crossing_is_the_largest_and_its_series_starts_at_its_checked_run():
    # the step series is of the crossing furthest from RK4 at half its step, and starts with that
    # crossing's checked IMs (the same single runs at the automatic steps)
    numbers = _script().stored()
    worst = numbers["worst"]
    f = numbers["figures"][worst["figure"]]
    assert f["checked_largest"] == max(g["checked_largest"] for g in numbers["figures"].values())
    assert worst["cell"] == f["checked_largest_cell"]
    assert worst["exact"]["impact_factor"][0] == pytest.approx(f["checked_worst"]["default"], abs=1e-12)
    assert worst["rk4"]["impact_factor"][0] == pytest.approx(f["checked_worst"]["rk4"], abs=1e-12)
    assert worst["rk4"]["impact_factor"][1] == pytest.approx(f["checked_worst"]["rk4_half_step"], abs=1e-12)
    for name in ("exact", "rk4"):
        dts = worst[name]["dt"]
        assert all(b < a for a, b in zip(dts, dts[1:])), name


@pytest.mark.slow
def test_the_script_reproduces_the_stored_numbers():
    recomputed_equals_stored(_script(), "paper-accuracy-numbers", HINT, 1e-9)
